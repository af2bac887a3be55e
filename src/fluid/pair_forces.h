#pragma once
/// The pair kernel: one formula for every pair of particles, whatever their materials.
#include <cstdint>
#include <span>
#include <vector>

#include "core/particle_store.h"
#include "forces/interaction_table.h"
#include "neighbors/cell_grid.h"

namespace softsub::fluid {

/// A half pair list (Verlet list): for each slot i, the slots j of every pair within
/// its cutoff plus a skin, each unordered pair once. Valid while the two largest
/// displacements since build() add up to less than the skin and the store has not been
/// reordered (solver::Simulation checks both).
/// What else a pair list needs beyond the interaction table (rigid bodies).
struct ListOptions {
  /// Per material: list radius before the skin; empty: each row's longest cutoff. Rows
  /// with contacts (rigid bodies) list pairs out to their contact distance too.
  std::span<const float> rowRadius;
  /// Pairs of two particles with the same owner >= this are not listed (the particles
  /// of one rigid body never interact). The default lists every pair.
  std::uint32_t exclusiveOwnersFrom = UINT32_MAX;
};

class PairList {
 public:
  /// Lists every pair closer than (row radius + skin) using `grid` (rebuilt on `store`).
  void build(const neighbors::CellGrid& grid, const forces::InteractionTable& table,
             const ParticleStore& store, float skin, const ListOptions& options = {});
  /// Partners of slot i.
  [[nodiscard]] std::span<const std::uint32_t> partners(std::size_t i) const {
    return {partners_.data() + offsets_[i], partners_.data() + offsets_[i + 1]};
  }
  /// Number of listed pairs.
  [[nodiscard]] std::size_t pairCount() const { return partners_.size(); }
  /// Bytes reserved.
  [[nodiscard]] std::size_t memoryBytes() const {
    return (offsets_.capacity() + partners_.capacity() + slot_.capacity() + kept_.capacity() +
            owner_.capacity()) * 4 +
           (bx_.capacity() + by_.capacity() + bz_.capacity() + r2_.capacity() + rowCut2_.capacity()) * 4;
  }

 private:
  std::vector<std::uint32_t> offsets_;
  std::vector<std::uint32_t> partners_;
  // Build scratch, kept between builds: one cell's candidates (positions, slots,
  // squared distances, kept slots) and each material row's squared list radius.
  std::vector<float> bx_, by_, bz_, r2_, rowCut2_;
  std::vector<std::uint32_t> slot_, kept_, owner_;
};

/// Adds to store.f the forces of every listed pair closer than its cutoff (Newton's
/// third law: what i gets, j gets with the opposite sign):
///   f_i += -F(r) n + damping (v_j - v_i) + k ((v_j - v_i) . n) n,  n = (x_j - x_i) / r
/// with F the pair's sampled function (positive = repulsion). No branch on function
/// kind, no virtual call, no allocation once warmed up.
void accumulatePairForces(const PairList& list, const forces::InteractionTable& table,
                          ParticleStore& store);

/// Adds to store.f the forces of every pair closer than its cutoff, each pair once
/// (Newton's third law: what i gets, j gets with the opposite sign):
///   f_i += -F(r) n + damping (v_j - v_i) + k ((v_j - v_i) . n) n,  n = (x_j - x_i) / r
/// with F the pair's sampled function. `store` must be in the order `grid` was rebuilt
/// with. Builds a pair list with no skin (allocates): for tests and one-off use.
void accumulatePairForces(const neighbors::CellGrid& grid, const forces::InteractionTable& table,
                          ParticleStore& store);

/// The same sum by brute force over all pairs, in double precision, straight from the
/// functions' formulas (not the tables). Reference for tests; O(n^2).
void referencePairForces(const forces::InteractionTable& table, const ParticleStore& store,
                         std::vector<double>& fx, std::vector<double>& fy, std::vector<double>& fz);

}  // namespace softsub::fluid
