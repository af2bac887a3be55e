#pragma once
/// The stepper: the seed's stages, in order, on (Model, State).
#include <cstdint>
#include <string>
#include <vector>

#include "core/snapshot.h"
#include "fluid/pair_forces.h"
#include "neighbors/cell_grid.h"
#include "rigid/solver.h"
#include "solver/model.h"

namespace softsub::solver {

/// Owns a State and the work buffers for stepping it under a Model. The Model must
/// outlive the Simulation.
class Simulation {
 public:
  Simulation(const Model& model, State state);

  /// One substep of length model.dt() (docs/architecture.md, "The step").
  void step();
  /// model.substeps substeps, then frame += 1. Throws BlowUpError (with frame, fluid,
  /// particle id, quantity and value) if any position or velocity is not finite.
  void advanceFrame();
  /// Ends a frame stepped substep by substep with step() (the viewer's -drawPerFrame 0):
  /// frame += 1, then the same finiteness check as advanceFrame.
  void finishFrame();

  /// The current frame as plain arrays in stable-id order (buffers reused).
  void snapshot(FrameSnapshot& out) const;
  /// Convenience: a fresh snapshot.
  [[nodiscard]] FrameSnapshot snapshot() const;

  /// Read access for tests, benchmarks and the viewer.
  [[nodiscard]] const State& state() const { return state_; }
  [[nodiscard]] const Model& model() const { return model_; }
  /// Seconds since the start.
  [[nodiscard]] double time() const;
  /// Bytes held by the particle store and the work buffers.
  [[nodiscard]] std::size_t memoryBytes() const;

  /// How many times the grid and pair list were rebuilt (diagnostics, benchmarks).
  [[nodiscard]] std::int64_t listBuilds() const { return listBuilds_; }

  /// Throws BlowUpError naming the first non-finite position/velocity, if any.
  void checkFinite() const;

  /// The rigid-body solver (contacts of the last substep, tests).
  [[nodiscard]] const rigid::RigidSolver& rigidSolver() const { return rigid_; }

 private:
  void computeForces();            // stages 2-3: grid + pair list when stale, pair forces
  [[nodiscard]] bool listIsStale() const;
  void kick(float h);    // v += (f/m + g) h
  void drift(float dt);  // x += v dt
  void applyWalls();
  void stepBodies(double dt);
  void listRigidPairs();
  [[nodiscard]] std::string entityName(std::uint32_t owner) const;

  const Model& model_;
  State state_;
  neighbors::CellGrid grid_;
  fluid::PairList list_;
  float cellSize_ = 1;  // longest cutoff
  float skin_ = 0;      // pair-list margin beyond the cutoff
  bool listValid_ = false;
  std::int64_t listBuilds_ = 0;
  std::vector<float> refX_, refY_, refZ_;  // positions when the list was built
  mutable std::vector<std::uint32_t> slotOfId_;
  // Rigid bodies.
  rigid::RigidSolver rigid_;
  std::vector<rigid::SlotPair> rigidPairs_;  // listed pairs that involve a body particle
  std::vector<float> rowRadius_, materialInverseMass_, materialRadius_;
  fluid::ListOptions listOptions_;
};

}  // namespace softsub::solver
