#pragma once
/// The stepper: the seed's stages, in order, on (Model, State).
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/snapshot.h"
#include "core/work_buffer.h"
#include "fluid/pair_forces.h"
#include "neighbors/cell_grid.h"
#include "rigid/solver.h"
#include "solver/list_guard.h"
#include "solver/model.h"

namespace softsub::solver {

/// Adaptive substeps keep every particle's move per substep within this fraction of its
/// interaction distance (docs/architecture.md, "Adaptive substeps").
inline constexpr double kAdaptiveTravel = 0.25;

/// Owns a State and the work buffers for stepping it under a Model. The Model must
/// outlive the Simulation.
class Simulation {
 public:
  Simulation(const Model& model, State state);

  /// One substep of length dt() (docs/architecture.md, "The step"), then the blow-up
  /// check (checkFinite). Throws BlowUpError naming the frame, the substep, the fluid
  /// or object, the particle id, the quantity and its value. Velocity Verlet runs in
  /// leapfrog form: after a substep that does not end the frame, the velocities are
  /// half a step ahead of the positions (the last substep of a frame brings them level).
  void step();
  /// What the first substep does before it moves anything, done now: velocity Verlet's
  /// first force evaluation (with the grid and the pair list). Nothing for the Euler
  /// schemes, whose every substep starts with its forces. For a benchmark that times the
  /// steps alone, as LAMMPS's "Loop time" leaves out its setup. The substeps that follow
  /// are the same; only adaptive substeps (Model::adaptiveSubsteps) may choose the first
  /// frame's count differently, as they then see these forces instead of none.
  void prepare();
  /// A whole frame: chooses its substep count (chooseSubsteps, when the model is
  /// adaptive), steps them, then frame += 1. BlowUpError as step().
  void advanceFrame();
  /// Ends a frame stepped substep by substep with step() (the viewer's -drawPerFrame 0):
  /// levelVelocities(), frame += 1, then the same check as advanceFrame.
  void finishFrame();
  /// Velocity Verlet: gives the velocities the half kick a substep inside a frame owes
  /// (step()), so that they are at the positions' time; nothing otherwise. For a caller
  /// that ends a frame after fewer substeps than substeps() (finishFrame does it) or
  /// takes the state mid-frame to continue it in another simulation.
  void levelVelocities();

  /// Substeps of the current (or next) frame: model.substeps, or with
  /// model.adaptiveSubsteps the count chosen at the frame's start.
  [[nodiscard]] int substeps() const { return substeps_; }
  /// Seconds per substep of the current frame.
  [[nodiscard]] double dt() const { return 1.0 / (model_.framesPerSecond * substeps_); }
  /// The substep count adaptive stepping would choose for the next frame, from the
  /// current state (docs/architecture.md, "Adaptive substeps"): at least model.substeps
  /// and the stability estimate's minimum, enough that no particle moves more than
  /// kAdaptiveTravel of its interaction distance per substep at its current speed or
  /// from rest under its current acceleration; at most model.maxSubsteps.
  [[nodiscard]] int chooseSubsteps() const { return capSubsteps(neededSubsteps()); }
  /// What chooseSubsteps asks for before model.maxSubsteps caps it (may exceed it).
  [[nodiscard]] double neededSubsteps() const;
  /// With adaptive substeps, how many the current frame needed when model.maxSubsteps
  /// held it back (its substeps() are then fewer: particles may move further a substep
  /// than adaptive stepping allows); 0 when the frame took what it needed.
  [[nodiscard]] double cappedSubsteps() const { return capped_; }
  /// The largest distance a particle covers in one substep at its current speed, in its
  /// interaction distances (what the blow-up check compares to model.maxTravelPerSubstep;
  /// `run --stats` prints it). Infinity when a velocity is not finite.
  [[nodiscard]] double travelPerSubstep() const;

  /// The dynamic body that moves the most particles of its own size in one substep at
  /// its current velocities: its farthest particle can move (|V| + |ω| r) dt. A body
  /// that moves more than a particle's diameter a substep can pass into, or through, a
  /// part of another body one particle thick (rigid contacts see overlaps, not paths).
  struct BodyTravel {
    std::size_t body = 0;
    double travel = 0;          ///< scene units a substep
    double particleRadius = 0;  ///< the body's
  };
  [[nodiscard]] std::optional<BodyTravel> fastestBody() const;

  /// The exact solver state beyond State that a checkpoint keeps so that a restored
  /// simulation continues bit for bit: the positions at which the pair list was built,
  /// in slot order (empty when no list is held).
  struct ListReference {
    std::span<const float> x, y, z;
  };
  [[nodiscard]] ListReference listReference() const;
  /// Replaces the state with a checkpointed one and rebuilds the pair list exactly as it
  /// was built (from `reference`, the ListReference saved with it; empty: rebuilt at the
  /// next step, as after a fresh start). The store must be in the slot order it was
  /// saved in. InputError-free: std::invalid_argument when the sizes do not fit the
  /// model or the reference is not the one the order was sorted by.
  void restore(State state, std::vector<float> refX, std::vector<float> refY, std::vector<float> refZ);

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
  /// The pair list's margin beyond the cutoff, in scene units (Model::pairListSkin or
  /// Model::windowListSkin of the longest interaction distance).
  [[nodiscard]] float listSkin() const { return skin_; }

  /// Throws BlowUpError naming the first particle (lowest id) or body whose position or
  /// velocity is not finite or whose speed is beyond model.maxTravelPerSubstep.
  void checkFinite() const;

  /// Runs the per-particle stages one pass each, as a scene with bodies does, instead of
  /// one sweep (tests: the two are bitwise the same).
  void useStagedPasses(bool staged) { staged_ = staged; }

  /// The rigid-body solver (contacts of the last substep, tests).
  [[nodiscard]] const rigid::RigidSolver& rigidSolver() const { return rigid_; }

 private:
  void computeForces();            // stages 2-3: grid + pair list when stale, pair forces
  [[nodiscard]] bool listIsStale();  // also sets fastestSlot_
  [[nodiscard]] bool listDiesYoung() const;
  void kick(float h);    // v += (f/m + g) h
  void drift(float dt);  // x += v dt
  void applyWalls();
  // kick(h) then drift(dt) (explicitEuler: drift, then kick), then applyWalls(), in one
  // pass over the particles, which also finds the two largest displacements since the
  // list was built (kept for the next computeForces()) and, with `check`, runs
  // checkFinite()'s scan. Bitwise the same as the stages one after another. Scenes
  // without bodies only (bodies move their particles after the walls).
  void sweep(float h, float dt, bool explicitEuler, bool check);
  struct ParticleOps;
  [[nodiscard]] ParticleOps particleOps();
  /// The bodies' implicit drag set up at the positions the forces were evaluated at
  /// (rigid::RigidSolver::prepareDrag), before the fluid moves.
  void prepareBodies();
  void stepBodies(double dt, rigid::FluidKick fluidKick = rigid::FluidKick::Whole);
  void closingKick();
  void keepFluidOutOfBodies();
  void listRigidPairs();
  [[nodiscard]] std::string entityName(std::uint32_t owner) const;
  [[noreturn]] void reportBlowUp() const;

  /// Largest |v| / reach and |a| / reach over the particles (reach: reach_ of the
  /// particle's material); `finite` false when any position or velocity is not finite
  /// (non-finite forces are left out of the acceleration). Exact maxima: the same for
  /// any split.
  struct Extremes {
    float speed = 0;         ///< max |v| / reach, 1/s
    float acceleration = 0;  ///< max |f/m + g| / reach, 1/s^2
    bool finite = true;
  };
  [[nodiscard]] Extremes scanParticles(bool withForces) const;
  void checkFinite(const Extremes* scanned) const;
  void scanSpeeds(const ParticleStore& s, std::size_t b, std::size_t e, float& speed2, bool& finite) const;
  static Extremes joinExtremes(Extremes a, const Extremes& b);
  // listWork_ large enough for a grid rebuild and for the reference positions.
  void reserveListWork();
  // Copies the reference positions into listWork_.
  void holdReference(std::span<const float> x, std::span<const float> y, std::span<const float> z);

  const Model& model_;
  State state_;
  neighbors::CellGrid grid_;
  fluid::PairList list_;
  int substeps_ = 1;       // of the current frame
  double capped_ = 0;      // cappedSubsteps()
  [[nodiscard]] int capSubsteps(double needed) const;
  int substepInFrame_ = 0; // substeps done in the current frame
  bool kickOwed_ = false;  // velocity Verlet: velocities are a half kick behind (step())
  int stableSubsteps_ = 1; // the stability estimate's minimum (adaptive only)
  std::vector<float> reach_;  // per material: the interaction distance speeds are measured in
  std::vector<float> invReach_;  // 1 / reach_
  bool uniformReach_ = false;    // every material has the same reach_
  float cellSize_ = 1;  // longest cutoff
  float skin_ = 0;      // pair-list margin beyond the cutoff
  bool listValid_ = false;
  // The stale-list test's answer for the positions as they are, found by sweep(): -1
  // unknown (computeForces() then scans), 0 fresh, 1 stale. Whatever moves particles
  // other than sweep() (stepBodies(), restore(), a rebuild) leaves it -1.
  int knownStale_ = -1;
  bool staged_ = false;  // useStagedPasses()
  std::int64_t listBuilds_ = 0;
  // Positions when the list was built (valid with listValid_), in listWork_, which the
  // grid uses as its work memory during a rebuild (core/work_buffer.h).
  WorkBuffer listWork_;
  const float* ref_ = nullptr;  // x of every slot, then y, then z
  // The second test of a list the two largest displacements call stale: particles that
  // moved together (solver/list_guard.h).
  ListGuard guard_;
  // The lowest slot with the largest displacement, found by the last stale test.
  std::uint32_t fastestSlot_ = UINT32_MAX;
  // Rigid bodies.
  rigid::RigidSolver rigid_;
  std::vector<rigid::SlotPair> rigidPairs_;  // listed pairs that involve a body particle
  std::vector<float> rowRadius_, materialInverseMass_, materialRadius_;
  std::vector<std::array<float, 3>> wallLo_, wallHi_;  // per material: the walls' centre bounds
  // The bounds a centre of any material may take without touching a wall (the largest
  // lows, the smallest highs; no high for y without a lid), for a cheap test first.
  std::array<float, 3> gateLo_{-INFINITY, -INFINITY, -INFINITY}, gateHi_{INFINITY, INFINITY, INFINITY};
  bool uniformMass_ = false;  // every material has the first one's inverse mass
  fluid::ListOptions listOptions_;
};

}  // namespace softsub::solver
