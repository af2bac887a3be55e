#pragma once
/// The rigid-body stages of a substep (docs/architecture.md, "Rigid bodies"): forces of
/// the body particles → force and torque on each body; velocities; contacts between
/// bodies (overlapping particles of different bodies) and with the container walls,
/// resolved by impulses; interpenetration removed (the seed's stage 5); poses advanced;
/// fluid particles kept out of the bodies; body particles written back into the store.
#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/math.h"
#include "core/particle_store.h"
#include "forces/interaction_table.h"
#include "rigid/body.h"

namespace softsub::rigid {

/// Axis-aligned container walls: planes at lo and hi on x and z, a floor at lo.y, a lid
/// at hi.y when closed (solver::Container).
struct Walls {
  std::array<double, 3> lo{0, 0, 0};
  std::array<double, 3> hi{0, 0, 0};
  bool closed = false;      ///< lid at hi.y
  double restitution = 0.5; ///< the environment's NormalAttenuation: normal velocity after contact = -restitution * before
  double friction = 0.1;    ///< the environment's TangentAttenuation: impacts v_t *= (1 - friction); resting contact: Coulomb coefficient
};

/// Tuning of the contact solver (defaults are what scenes get).
struct ContactSettings {
  int velocityIterations = 20;   ///< sequential-impulse sweeps over the contacts
  int positionIterations = 6;    ///< sweeps of the interpenetration fix
  double correction = 0.3;       ///< fraction of the overlap removed per substep
  double slop = 0.02;            ///< overlap left alone, as a fraction of the particle radius
};

/// How far from the normal through a face particle another particle still touches that
/// face, in the face's particle radii (RigidSolver::faceContact).
inline constexpr double kFacePatch = 1.5;

/// The squared centre distance within which two body particles of radii ra and rb may
/// touch: ra + rb for two spheres, further where one lies over the other's flat face
/// beside the normal through it (kFacePatch). Pair lists of body rows reach this far.
[[nodiscard]] inline double faceReach2(double ra, double rb) {
  const double m = std::max(ra, rb);
  return (ra + rb) * (ra + rb) + kFacePatch * kFacePatch * m * m;
}

/// A contact between two bodies (b = -1: a wall) at one pair of touching particles.
struct Contact {
  std::int32_t a = 0, b = -1;  ///< body indices
  std::int32_t wall = -1;      ///< b = -1: the plane, 2 * axis + (0 low side, 1 high side)
  Vec3 normal{0, 1, 0};        ///< unit, from b towards a: the impulse on a is +lambda * normal
  Vec3 ra{0, 0, 0}, rb{0, 0, 0};  ///< contact point relative to each centre of mass
  double depth = 0;            ///< overlap of the two particles (or particle and wall)
  double slop = 0;             ///< overlap the interpenetration fix leaves alone
  double restitution = 0, friction = 0;
  // Solver state.
  Vec3 t1{1, 0, 0}, t2{0, 0, 1};
  double massN = 0, massT1 = 0, massT2 = 0;
  double targetN = 0, targetT1 = 0;
  double impactN = 0, impactT1 = 0;  ///< the impact law's targets, before an energy check scales them
  double lambdaN = 0, lambdaT1 = 0, lambdaT2 = 0, lambdaP = 0;
  double warmN = 0, warmT1 = 0, warmT2 = 0;  ///< where the impulses start: last substep's at this point
  /// What shock propagation added (RigidSolver::propagateShock).
  double shockN = 0, shockT1 = 0, shockT2 = 0;
};

/// Slots of a pair of particles of which at least one belongs to a body, of two
/// different owners.
using SlotPair = std::array<std::uint32_t, 2>;

/// How the fluid came by the kick of dt (f / m + g) that a step's drag correction
/// replaces (RigidSolver::step): the correction must take out exactly what was given.
enum class FluidKick {
  /// Explicitly, whole: one merged kick, or an explicit closing half and this opening half.
  Whole,
  /// Only the opening half: velocity Verlet's first substep of a run, no closing kick
  /// before it (taken as whole, a plate dragging a particle was sent backwards).
  OpeningHalf,
  /// A closing half taken implicitly with the bodies held (dragFluidHeld), then the
  /// explicit opening half: velocity Verlet's first substep of every later frame.
  AfterHeldHalf,
};

/// Steps every body; owns its work buffers (no allocation once warmed up).
class RigidSolver {
 public:
  /// Slots of every body particle in `store` (call after each reorder of the store).
  void findBodySlots(const BodySet& set, const ParticleStore& store);
  [[nodiscard]] std::span<const std::uint32_t> bodySlots() const { return bodySlots_; }

  /// Writes every body particle's position and velocity from its body's state.
  void writeParticles(const BodySet& set, const std::vector<BodyState>& states, ParticleStore& store);

  /// One substep of length dt for every body. `store.f` must hold the forces at the
  /// bodies' current poses; `pairs` lists (at least) every pair of particles within
  /// contact distance that involves a body; `materialInverseMass` gives, per material,
  /// the inverse mass of fluid particles. Fluid that ends inside a body is put out by
  /// keepFluidOut, called after the container's walls. `memory` holds the contact impulses of the last
  /// substep, which this one starts from, and receives this substep's (State::contacts).
  /// `table` (may be null) gives the fluid/object pairs' velocity terms, whose drag is
  /// taken implicitly on both sides: the bodies' free motion and the velocities of the
  /// fluid particles they touch. Those particles were kicked by dt (f / m + g) before
  /// this call, with `store.f` as it still is; their velocities are corrected, and their
  /// positions by `fluidDrift` times the correction (dt where the integrator drifted them
  /// after the kick, 0 where before). `fluidKick`: how the fluid came by that kick since
  /// its last correction (FluidKick).
  void step(const BodySet& set, std::vector<BodyState>& states, std::vector<ContactMemory>& memory,
            ParticleStore& store, std::span<const SlotPair> pairs, std::span<const float> materialInverseMass,
            const forces::InteractionTable* table, const Walls* walls, const Vec3& gravity, double dt,
            double fluidDrift, FluidKick fluidKick = FluidKick::Whole);

  /// After step() and the container's walls: fluid particles that came within a body
  /// are put back on its surface and lose their approaching velocity (the body takes the
  /// opposite impulse). Last, so that neither the walls nor anything else leaves fluid in
  /// a body: with the walls after it, fluid squeezed between a heavy box and the floor was
  /// put back up into the box (a box of mass 2,000 landing on a puddle kept 17 particles
  /// in its hollow middle). The walls come after step() for the drag (RigidSolver::step).
  void keepFluidOut(const BodySet& set, std::vector<BodyState>& states, ParticleStore& store,
                    std::span<const SlotPair> pairs, std::span<const float> materialInverseMass,
                    std::span<const float> materialRadius);

  /// The fluid/body drag's implicit system (gatherDrag) set up now, for the next step():
  /// call it where the forces in `store.f` were evaluated, before the fluid is kicked and
  /// moved, so that the drag the system takes implicitly is the one in those forces (set
  /// up after the fluid had moved, a fluid particle that had just come within reach of a
  /// fine body, or just left it, was given a drag its forces did not hold: thrown back
  /// faster than it came). Without this call, step() sets it up itself.
  void prepareDrag(const BodySet& set, const std::vector<BodyState>& states, const ParticleStore& store,
                   std::span<const SlotPair> pairs, std::span<const float> materialInverseMass,
                   const forces::InteractionTable& table, const Vec3& gravity, double dt);

  /// Velocity Verlet's closing half kick by `h` at a frame's end, the bodies held (they
  /// do not move in it): call it after the explicit kick of every fluid particle by the
  /// forces in `store.f`. Each fluid particle within reach of a body takes its drag
  /// implicitly, v0 + A⁻¹ e with A = m I + h D and e = h (f + m g), instead of
  /// v0 + e / m: taken explicitly, a strong drag overshot in the written frame (a
  /// particle written at -47 units/s while moving at +10, or at 1,879 while moving at
  /// 2.5, and a run stopped as blown up). The next step must be told
  /// (FluidKick::AfterHeldHalf), which takes this correction back out of its own: that
  /// step works it out again from the same positions and forces, so a checkpoint at the
  /// frame's end needs nothing more.
  void dragFluidHeld(const BodySet& set, const std::vector<BodyState>& states, ParticleStore& store,
                     std::span<const SlotPair> pairs, std::span<const float> materialInverseMass,
                     const forces::InteractionTable& table, const Vec3& gravity, double h);

  /// The contacts of the last step (tests, diagnostics).
  [[nodiscard]] std::span<const Contact> contacts() const { return contacts_; }

  ContactSettings settings;

 private:
  void gatherForces(const BodySet& set, const std::vector<BodyState>& states, const ParticleStore& store);
  /// The fluid/body drag's implicit system (solver.cpp): per dynamic body, the 6 x 6
  /// matrix C - dt sum G_fᵀ A_f⁻¹ G_f (drag_; dragged_ marks the bodies that have any)
  /// and the right side's sum G_fᵀ A_f⁻¹ e_f (dragRhs_); per fluid particle within reach
  /// of a body, A_f⁻¹, its explicit step e_f and its couplings (fluids_, couplings_).
  void gatherDrag(const BodySet& set, const std::vector<BodyState>& states, const ParticleStore& store,
                  std::span<const SlotPair> pairs, const forces::InteractionTable& table,
                  std::span<const float> materialInverseMass, const Vec3& gravity, double dt);
  /// The fluid particles' side: each one's velocity (and position, by `drift` times the
  /// change) from its explicit step to the implicit one, with the bodies' solved dq.
  void dragFluid(ParticleStore& store, std::span<const float> materialInverseMass, double dt, double drift,
                 FluidKick kick);
  void collectContacts(const BodySet& set, const ParticleStore& store, std::span<const SlotPair> pairs,
                       const Walls* walls, double dt);
  /// Contact c between slot i of body a and slot j of body b (d = x_i - x_j, r = |d|,
  /// c.normal and c.depth those of two spheres): a flat face's normal and depth instead
  /// where one lies under one (BodySet::faces).
  void faceContact(const BodySet& set, const ParticleStore& s, std::uint32_t i, std::uint32_t a, std::uint32_t j,
                   std::uint32_t b, const Vec3& d, double r, double dt, Contact& c) const;
  void reduceContacts();
  void prepareContacts(double dt, const Vec3& gravity);
  /// Each contact's starting impulses from the one of last substep's contacts (same
  /// bodies or wall) whose point on body a lies nearest, within its particle radius.
  void recallImpulses(const BodySet& set, std::span<const ContactMemory> memory, double dt);
  /// This substep's solved impulses into `memory`.
  void rememberImpulses(std::vector<ContactMemory>& memory, double dt) const;
  /// Sets every contact's impulses to its starting ones, times its island's scale, and applies them.
  void applyWarmStart();
  void solveVelocities();
  void solveVelocitiesWithoutGain(const Vec3& gravity);
  void solvePositions(double dt);
  /// After the sweeps: resting contacts level by level from the ground up, each one's
  /// lower body held still (solver.cpp).
  void propagateShock();
  /// True when a dynamic body took an impulse.
  bool pushFluidOut(const BodySet& set, std::vector<BodyState>& states, ParticleStore& store,
                    std::span<const SlotPair> pairs, std::span<const float> materialInverseMass,
                    std::span<const float> materialRadius);

  std::vector<std::uint32_t> bodySlots_;
  std::vector<Contact> contacts_;
  // Per body, during a step.
  std::vector<Vec3> force_, torque_;
  std::vector<Eigen::Matrix<double, 6, 6>> drag_;
  std::vector<Eigen::Matrix<double, 6, 1>>
      dragStep_;  ///< per dragged body: its substep's (dV, dw), contacts included
  std::vector<Eigen::Matrix<double, 6, 1>> dragRhs_;  ///< per dragged body: sum G_fᵀ A_f⁻¹ e_f
  bool dragReady_ = false;  ///< prepareDrag ran for the coming step
  /// Per body dragging fluid (dragged_): the inverse of M + dt (C - dt sum G_fᵀ A_f⁻¹ G_f),
  /// its mobility with the dragged fluid's inertia, which the contacts use.
  std::vector<Eigen::Matrix<double, 6, 6>> mobility_;
  std::vector<char> dragged_;
  // Per fluid particle within reach of a body's drag, during a step.
  struct FluidDrag {
    std::uint32_t slot = 0;
    std::int32_t first = -1;  ///< its first coupling in couplings_ (-1: static bodies only)
    Mat3 sum;                 ///< sum of D over its pairs, all bodies
    Mat3 inverse;             ///< A⁻¹ = (m I + dt sum)⁻¹
    Vec3 step;                ///< e = dt (f + m g), its explicit momentum step
  };
  struct Coupling {  ///< a fluid particle and a dynamic body it drags
    std::uint32_t body = 0;
    std::int32_t next = -1;         ///< the particle's next coupling
    Eigen::Matrix<double, 3, 6> g;  ///< sum of D J over their pairs
  };
  static constexpr std::uint32_t kNoRow = UINT32_MAX;
  std::vector<std::uint32_t> fluidRow_;  ///< per slot: its row in fluids_, kNoRow between steps
  std::vector<FluidDrag> fluids_;
  std::vector<Coupling> couplings_;
  std::vector<Vec3> pos_, vel_, omega_, pseudoVel_, pseudoOmega_;
  std::vector<Mat3> rot_, invInertia_;
  std::vector<double> invMass_;
  // The energy check (solveVelocitiesWithoutGain): each dynamic body's island (-1: static),
  // and per island its budget and the search for the scale of its impact targets.
  enum class Search : std::uint8_t { First, AtZero, Bracket, Final, Settled };
  struct Island {
    double kinetic = 0;                       ///< kinetic energy before the solve
    double budget = 0;                        ///< what it may have after: kinetic less the overlap fix's lift
    bool scalable = false;  ///< some contact has an impact target or a warm start (else nothing to scale)
    double scale = 1;                         ///< of the impact targets, in the last solve
    double lo = 0, hi = 1, gLo = 0, gHi = 0;  ///< the bracket and its energies less the budget
    std::int8_t side = 0;  ///< which end the last solve moved (-1 lo, 1 hi): the Illinois step
    Search search = Search::First;
  };
  std::vector<std::int32_t> islandRoot_, island_;
  std::vector<Island> islands_;
  std::vector<double> islandAfter_;
  std::vector<Vec3> startVel_, startOmega_;  ///< per body: velocities at the start of the substep
  std::vector<double> lift_;                 ///< per body: the height the overlap fix will lift it by
  std::vector<Vec3> savedVel_, savedOmega_;
  std::vector<char> recalled_;  ///< per memory entry: taken by a contact of this substep
  // propagateShock's work: per body its level (contacts from the ground, -1: none), the
  // breadth-first queue, the contacts by level, the body links; per island whether it
  // takes the pass.
  std::vector<std::int32_t> level_;
  std::vector<std::uint32_t> levelQueue_, levelStart_, levelOrder_, levelFill_;
  std::vector<std::array<std::uint32_t, 2>> levelLinks_;
  std::vector<char> shocked_;
};

}  // namespace softsub::rigid
