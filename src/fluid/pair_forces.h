#pragma once
/// The pair kernel: one formula for every pair of particles, whatever their materials.
#include "core/particle_store.h"
#include "forces/interaction_table.h"
#include "neighbors/cell_grid.h"

namespace softsub::fluid {

/// Adds to store.f the forces of every pair closer than its cutoff, each pair once
/// (Newton's third law: what i gets, j gets with the opposite sign):
///   f_i += -F(r) n + damping (v_j - v_i) + k ((v_j - v_i) . n) n,  n = (x_j - x_i) / r
/// with F the pair's sampled function (positive = repulsion). Reads positions and
/// velocities from `store` (`vx/vy/vz` unless `vel` arrays are given), which must be in
/// the order `grid` was rebuilt with. No branch on function kind, no allocation.
void accumulatePairForces(const neighbors::CellGrid& grid, const forces::InteractionTable& table,
                          ParticleStore& store);

/// The same sum by brute force over all pairs, in double precision, straight from the
/// functions' formulas (not the tables). Reference for tests; O(n^2).
void referencePairForces(const forces::InteractionTable& table, const ParticleStore& store,
                         std::vector<double>& fx, std::vector<double>& fy, std::vector<double>& fz);

}  // namespace softsub::fluid
