#pragma once
/// Will these settings blow up? A pure estimate, from the Model alone (plus, optionally,
/// the State to tell which objects share a material row), of whether explicit time
/// integration of each pair of materials in use is stable at the model's substep count,
/// and how many substeps would make it so. The viewer shows it as a hint while settings
/// are tweaked; docs/architecture.md ("Stability estimate") explains every factor.
///
/// The model problem is the fastest linear mode of a lattice of particles joined by the
/// pair's function: a stiffness k = max |dF/dr| and a damping (Viscosity and the
/// RelativeVelocity term), integrated by the model's integrator. Its amplification per
/// substep is computed exactly for that integrator; a mode that grows by more than a
/// factor 2 per second of simulated time counts as a blow-up.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "forces/interaction_table.h"
#include "solver/model.h"

namespace softsub::solver {

/// The most substeps minimumSubsteps looks at (the scene schema's limit on Substeps).
inline constexpr int kMaxStableSubsteps = 10000;

/// Springs (the function's slope, and the RelativeVelocity term, which act along the line
/// between two particles): the fastest mode of a close-packed lattice whose 12 nearest
/// neighbours all sit at the distance of maximum slope has omega^2 = 8 k / m, four times
/// the isolated pair's k / mu = 2 k / m (face-centred cubic, longitudinal mode at the X
/// point of the Brillouin zone).
inline constexpr double kLatticeSpringFactor = 4;
/// Viscosity (acts on every component of the relative velocity): the same mode damps at
/// 16 c / m, eight times the isolated pair's c / mu = 2 c / m (the graph Laplacian of the
/// fcc lattice has largest eigenvalue 16).
inline constexpr double kLatticeViscosityFactor = 8;

/// A verdict on a time step.
enum class StabilityVerdict : std::uint8_t {
  Stable,    ///< stable with a factor 2 to spare in the time step
  Marginal,  ///< stable, but half the substeps would not be
  Unstable   ///< expect a blow-up: the fastest mode grows, or the strongest force jumps a
             ///< particle across the whole interaction range in one substep
};

/// "stable", "marginal" or "unstable".
[[nodiscard]] std::string_view verdictName(StabilityVerdict verdict);

/// The estimate for one pair of materials (or one material with itself).
struct PairStability {
  std::string first;             ///< a fluid's name
  std::string second;            ///< a fluid's name, or the objects of a body row ("box, ball")
  std::size_t materialA = 0;     ///< row of the interaction table
  std::size_t materialB = 0;     ///< column of the interaction table
  double stiffness = 0;          ///< k = max |dF/dr| over the function's range, force/unit
  double reducedMass = 0;        ///< mu = m_a m_b / (m_a + m_b), mass
  double omegaDt = 0;            ///< sqrt(kLatticeSpringFactor k / mu) dt
  double dampingNumber = 0;      ///< (kLatticeViscosityFactor c + kLatticeSpringFactor k_rel) dt / mu
  /// The damping alone at the fastest rate of the particles' own neighbourhood
  /// (latticeDampingRate), times dt; 0 without a state.
  double latticeDampingNumber = 0;
  double travelNumber = 0;       ///< (max |F| / mu) dt^2 / cutoff: a push from rest in one substep, over the range
  double growthPerSecond = 1;    ///< amplification of the fastest mode over one second of simulated time
  StabilityVerdict verdict = StabilityVerdict::Stable;
  /// The smallest substep count (same frame rate) that makes this pair Stable; 0 when
  /// none up to kMaxStableSubsteps does.
  int minimumSubsteps = 1;
};

/// The estimate for every pair of materials in use.
struct StabilityReport {
  std::vector<PairStability> pairs;  ///< fluids with themselves, fluid/fluid, fluid/object rows
  std::size_t worst = 0;             ///< index of the pair that needs the most substeps (pairs.size() if none)
  StabilityVerdict verdict = StabilityVerdict::Stable;  ///< the worst verdict
  /// Substeps that make every pair Stable (the largest per-pair minimum); 0 when no count
  /// up to kMaxStableSubsteps does.
  int minimumSubsteps = 1;
  int substeps = 1;                  ///< the model's substeps the verdicts are for
  double dt = 0;                     ///< the model's dt, seconds
};

/// k = max |dF/dr| of a function over (r_lo, cutoff): exact for Linear and Curve,
/// sampled finely for the Lennard-Jones kinds. r_lo is 0, except for LennardJonesForce,
/// which is unbounded at r -> 0: from 0.9 sigma (where it already pushes with about
/// 140 epsilon / sigma; see docs/architecture.md).
[[nodiscard]] double maximumSlope(const forces::PairFunction& f);

/// max |F| over the same range as maximumSlope.
[[nodiscard]] double maximumForce(const forces::PairFunction& f);

/// The largest modulus of the eigenvalues of one substep of `integrator` applied to
/// x'' = -omega^2 x - gamma x', with omegaDt = omega dt and dampingNumber = gamma dt.
/// Velocity Verlet keeps the force of the last evaluation (with its half-step velocity).
[[nodiscard]] double amplificationPerStep(Integrator integrator, double omegaDt, double dampingNumber);

/// The fastest rate (1/s) at which a pair's velocity terms (`damping` on the relative
/// velocity, `relativeVelocity` on its component along the line between the two) damp a
/// mode of the particles of materials a and b where they sit in `s`: the largest
/// eigenvalue of M^-1/2 D M^-1/2 (D: the terms' operator over every a-b pair within
/// `cutoff`), by 60 Lanczos steps on the patch of the 3,000 a and b particles nearest the
/// most crowded of 64 sampled a particles. A lower bound that comes within a few
/// per cent for lattices (16 c / m for fcc with 12 neighbours, 36 c / m for simple cubic
/// with 26). inverseMass 0: particles that do not move (static bodies). 0 when no a
/// particle has a b neighbour.
[[nodiscard]] double latticeDampingRate(const ParticleStore& s, std::uint16_t a, std::uint16_t b, double damping,
                                        double relativeVelocity, double cutoff, double inverseMassA,
                                        double inverseMassB);

/// The estimate for one interaction between particles of masses massA and massB
/// (infinity: a static body) at `substeps` substeps per frame of framesPerSecond.
/// `latticeDamping` (latticeDampingRate, 1/s; 0: unknown) is checked as a mode of its own,
/// damping without spring: it grows once latticeDamping dt exceeds 2.
[[nodiscard]] PairStability assessInteraction(const forces::Interaction& interaction, double massA,
                                              double massB, double framesPerSecond, int substeps,
                                              Integrator integrator, double latticeDamping = 0);

/// The estimate for every pair in use in `model` at its substep count: each fluid with
/// itself, every two fluids, every fluid with every body row (with the lightest dynamic
/// body of the row as the other mass). `state` (optional) tells which objects share a
/// row; without it every body row is taken to hold every object.
[[nodiscard]] StabilityReport assessStability(const Model& model, const State* state = nullptr);

}  // namespace softsub::solver
