#pragma once
/// Model (read-only, compiled from a scene) and State (mutable). Every solver function
/// takes both explicitly; there is no global or "current" simulation.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/math.h"
#include "core/particle_store.h"
#include "forces/interaction_table.h"
#include "rigid/body.h"
#include "rigid/solver.h"

namespace softsub::solver {

/// Time integration scheme (docs/architecture.md has the exact update of each).
enum class Integrator : std::uint8_t { ExplicitEuler, SymplecticEuler, VelocityVerlet };

/// The container: walls at lo/hi on x and z, a floor at lo.y, a lid at hi.y if closed.
/// One definition for the fluid walls and the bodies' wall contacts.
using Container = rigid::Walls;

/// A fluid as the solver and the outputs see it.
struct FluidInfo {
  std::string name;
  std::array<float, 3> colour{1, 1, 1};
  double particleSize = 1;     ///< diameter
  double particleMass = 1;
  std::uint32_t firstId = 0;   ///< its particles have ids firstId .. firstId + count - 1
  std::uint32_t count = 0;
};

/// Per material (row of the interaction table): what the integrator needs.
struct MaterialInfo {
  float inverseMass = 1;
  float radius = 0.5f;  ///< distance kept from the container walls; for bodies, the largest particle radius
  bool body = false;    ///< a row of rigid-body particles (their motion comes from their bodies)
};

/// Everything that does not change during a run.
struct Model {
  double framesPerSecond = 24;
  int substeps = 8;
  std::int64_t frames = 120;
  Vec3 gravity{0, -9.81, 0};
  Integrator integrator = Integrator::SymplecticEuler;
  std::optional<Container> container;
  std::vector<FluidInfo> fluids;        ///< entity index = fluid index
  /// Rigid bodies: entity index = fluids.size() + body index; their particles' ids follow
  /// every fluid's.
  rigid::BodySet bodies;
  /// Rows of the interaction table: one per fluid (row = fluid index), then the bodies'
  /// rows (bodies with the same interactions share one).
  std::vector<MaterialInfo> materials;
  forces::InteractionTable table;
  /// Pair-list margin as a fraction of the longest cutoff: larger lists, rebuilt less
  /// often (docs/architecture.md, "The pair list"). For lists of pairs (the table
  /// kernel).
  double pairListSkin = 0.1;
  /// The same for lists of windows of 8 slots (the closed-form Lennard-Jones kernel,
  /// fluid::PairList::groups): that kernel's cost goes with its windows, about one per
  /// candidate range whatever the skin, not with its pairs, so a wider margin costs it
  /// little and saves list builds (docs/benchmarks.md, twenty-third session).
  double windowListSkin = 0.15;
  /// The pair list's second validity test (solver/list_guard.h): a list whose two
  /// largest displacements add up to the skin is kept while the particles moved
  /// together (a falling or flowing body of goo). Off: rebuilt at once (tests and
  /// benchmarks compare the two).
  bool listGuard = true;
  /// The blow-up check after every substep (docs/architecture.md, "Blow-up checks"): a
  /// particle or body whose speed would carry it further than this many interaction
  /// distances (its material's longest cutoff; with bodies, at least the contact reach)
  /// in one substep stops the run with BlowUpError, as does any
  /// non-finite position or velocity. 0 turns the speed part off.
  double maxTravelPerSubstep = 10;
  /// Adaptive substeps (`run --adaptive`): each frame's substep count is chosen from the
  /// state at its start (Simulation::chooseSubsteps), between `substeps` and
  /// `maxSubsteps`.
  bool adaptiveSubsteps = false;
  int maxSubsteps = 10000;

  /// Seconds per substep.
  [[nodiscard]] double dt() const { return 1.0 / (framesPerSecond * substeps); }
  /// Total particles over all fluids and bodies.
  [[nodiscard]] std::size_t particleCount() const;
};

/// Everything that changes during a run.
struct State {
  ParticleStore particles;
  std::vector<rigid::BodyState> bodies;  ///< one per Model::bodies.bodies
  std::vector<rigid::ContactMemory> contacts;  ///< the bodies' contact impulses of the last substep
  std::int64_t frame = 0;     ///< frames completed; the state is at time frame / fps
  bool forcesValid = false;   ///< store.f holds the forces of the current positions
};

}  // namespace softsub::solver
