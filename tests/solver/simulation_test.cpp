// Conservation laws, determinism, id order and blow-up detection of the stepper.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "core/error.h"
#include "fluid/pair_forces.h"
#include "solver/frame_loop.h"
#include "solver/simulation.h"
#include "support/force_check.h"
#include "support/scenarios.h"
#include "support/state_bytes.h"

namespace softsub::solver {
namespace {

// Two fluids with every velocity term switched on; no gravity, no walls.
Model twoFluids() {
  Model m;
  m.gravity = Vec3::Zero();
  m.integrator = Integrator::SymplecticEuler;
  m.fluids.push_back({"a", {1, 0, 0}, 1, 1.0, 0, 0});
  m.fluids.push_back({"b", {0, 0, 1}, 1, 2.5, 0, 0});
  m.materials.push_back({1.0f, 0.5f});
  m.materials.push_back({1.0f / 2.5f, 0.5f});
  m.table = forces::InteractionTable(2);
  fluid::FluidParams p;
  p.viscosity = 0.8;
  m.table.set(0, 0, {fluid::ownFunction(p), p.viscosity, 0});
  m.table.set(1, 1, {forces::LennardJones{10, 0.9, -5, 100, 1.4}, 0.3, 0});
  m.table.set(0, 1, {forces::Linear{5, 1, 0, 5}, 0.2, 1.0});
  return m;
}

State cloudState(std::size_t n, std::uint32_t seed, Model& m, float half = 6) {
  State s;
  s.particles = scenarios::randomCloud(n, -half, half, 1.5f, 2, seed);
  std::uint32_t counts[2] = {0, 0};
  for (std::size_t i = 0; i < s.particles.size(); ++i) ++counts[s.particles.material[i]];
  m.fluids[0].count = counts[0];
  m.fluids[1].firstId = counts[0];
  m.fluids[1].count = counts[1];
  // Ids must be grouped per fluid: give material 0 the first ids.
  std::uint32_t next[2] = {0, counts[0]};
  for (std::size_t i = 0; i < s.particles.size(); ++i) s.particles.id[i] = next[s.particles.material[i]]++;
  return s;
}

std::array<double, 3> momentum(const Model& m, const ParticleStore& p) {
  std::array<double, 3> q{0, 0, 0};
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double mass = 1.0 / m.materials[p.material[i]].inverseMass;
    q[0] += mass * p.vx[i]; q[1] += mass * p.vy[i]; q[2] += mass * p.vz[i];
  }
  return q;
}

TEST(Simulation, MomentumConservedWithoutGravityOrWalls) {
  for (Integrator in : {Integrator::ExplicitEuler, Integrator::SymplecticEuler, Integrator::VelocityVerlet}) {
    Model m = twoFluids();
    m.integrator = in;
    Simulation sim(m, cloudState(2000, 9, m));
    const auto q0 = momentum(m, sim.state().particles);
    double scale = 0;
    for (std::size_t i = 0; i < sim.state().particles.size(); ++i)
      scale += std::abs(sim.state().particles.vx[i]) + std::abs(sim.state().particles.vy[i]);
    for (int k = 0; k < 3; ++k) sim.advanceFrame();
    const auto q1 = momentum(m, sim.state().particles);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(q1[a], q0[a], 2e-6 * scale) << "axis " << a;
  }
}

// 27 argon atoms of the true Lennard-Jones force (cutoff 2.5) on a 3 x 3 x 3 lattice,
// moving a little; velocity Verlet, no gravity, no walls.
Model ljCluster(State& s, const forces::LennardJonesForce& lj) {
  Model m;
  m.gravity = Vec3::Zero();
  m.integrator = Integrator::VelocityVerlet;
  m.framesPerSecond = 24;
  m.substeps = 200;
  m.fluids.push_back({"argon", {1, 1, 1}, 1, 1, 0, 27});
  m.materials.push_back({1.0f, 0.5f});
  m.table = forces::InteractionTable(1);
  m.table.set(0, 0, {lj, 0, 0});
  for (int i = 0; i < 27; ++i)
    s.particles.add(1.15f * (i % 3), 1.15f * ((i / 3) % 3), 1.15f * (i / 9), 0.1f * ((i * 7) % 5 - 2),
                    0.1f * ((i * 3) % 5 - 2), 0.1f * ((i * 11) % 5 - 2), 0, 0);
  return m;
}

TEST(Simulation, VelocityVerletConservesEnergyOfATrueLennardJonesCluster) {
  const forces::LennardJonesForce lj{1, 1, 2.5};
  State s;
  const Model m = ljCluster(s, lj);
  auto energy = [&](const ParticleStore& p) {
    double e = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      e += 0.5 * (p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i]);
      for (std::size_t j = i + 1; j < p.size(); ++j) {
        const double dx = p.px[j] - p.px[i], dy = p.py[j] - p.py[i], dz = p.pz[j] - p.pz[i];
        e += forces::potential(lj, std::sqrt(dx * dx + dy * dy + dz * dz));
      }
    }
    return e;
  };
  Simulation sim(m, s);
  const double e0 = energy(sim.state().particles);
  double worst = 0;
  for (int f = 0; f < 24; ++f) {
    sim.advanceFrame();
    worst = std::max(worst, std::abs(energy(sim.state().particles) - e0));
  }
  // The cutoff makes U jump by U(rc) ~ 0.016 eps per pair crossing; the integrator and
  // the float tables add far less.
  EXPECT_LT(worst, 0.05 * std::abs(e0)) << "E0 = " << e0;
}

// The list's margin follows the kernel: Model::windowListSkin of the cutoff where the
// list holds windows for the closed-form kernel (one fluid of the true Lennard-Jones
// force), Model::pairListSkin elsewhere (the table kernel: two fluids; the
// closed form switched off).
TEST(Simulation, ListSkinFollowsTheKernel) {
  State s;
  Model lj = ljCluster(s, forces::LennardJonesForce{1, 1, 2.5});
  ASSERT_TRUE(fluid::PairList::groups(lj.table, s.particles.size(), {}));
  EXPECT_FLOAT_EQ(Simulation(lj, s).listSkin(), static_cast<float>(lj.windowListSkin) * 2.5f);
  lj.windowListSkin = 0.3;
  EXPECT_FLOAT_EQ(Simulation(lj, s).listSkin(), 0.75f);
  lj.table.set(0, 0, {forces::LennardJones{10, 0.9, -5, 100, 2.5}, 0, 0});  // a tabled function
  ASSERT_FALSE(fluid::PairList::groups(lj.table, s.particles.size(), {}));
  EXPECT_FLOAT_EQ(Simulation(lj, s).listSkin(), static_cast<float>(lj.pairListSkin) * 2.5f);

  Model two = twoFluids();
  const State cloud = cloudState(300, 4, two);
  EXPECT_FLOAT_EQ(Simulation(two, cloud).listSkin(),
                  static_cast<float>(two.pairListSkin) * static_cast<float>(two.table.maxCutoff()));
  EXPECT_NE(two.pairListSkin, two.windowListSkin);
}

// prepare() does velocity Verlet's first force evaluation ahead (what `bench lammps`
// leaves out of its time) and changes nothing else: the substeps that follow are bitwise
// those without it. The Euler schemes have nothing to prepare.
TEST(Simulation, PrepareComputesTheFirstForcesAheadAndChangesNothingElse) {
  for (const Integrator integrator : {Integrator::VelocityVerlet, Integrator::SymplecticEuler}) {
    Model model;
    State state;
    scenarios::fluidBlock(800, 0.9, model, state);
    model.integrator = integrator;
    Simulation prepared(model, state), plain(model, std::move(state));
    prepared.prepare();
    EXPECT_EQ(prepared.listBuilds(), integrator == Integrator::VelocityVerlet ? 1 : 0);
    EXPECT_EQ(prepared.state().forcesValid, integrator == Integrator::VelocityVerlet);
    for (int k = 0; k < 10; ++k) {
      prepared.step();
      plain.step();
    }
    EXPECT_EQ(prepared.state().particles.px, plain.state().particles.px);
    EXPECT_EQ(prepared.state().particles.vy, plain.state().particles.vy);
    EXPECT_EQ(prepared.listBuilds(), plain.listBuilds());
  }
}

TEST(Simulation, RerunsAreBitwiseIdentical) {
  auto run = [] {
    Model m = twoFluids();
    m.gravity = Vec3(0, -9.81, 0);
    Container c;
    c.lo = {-6, -6, -6};
    c.hi = {6, 6, 6};
    m.container = c;
    Simulation sim(m, cloudState(3000, 4, m));
    for (int f = 0; f < 4; ++f) sim.advanceFrame();
    return sim.snapshot();
  };
  const FrameSnapshot a = run(), b = run();
  ASSERT_EQ(a.fluids.size(), b.fluids.size());
  for (std::size_t f = 0; f < a.fluids.size(); ++f) {
    ASSERT_EQ(a.fluids[f].positions.size(), b.fluids[f].positions.size());
    EXPECT_EQ(0, std::memcmp(a.fluids[f].positions.data(), b.fluids[f].positions.data(),
                             a.fluids[f].positions.size() * sizeof(float)));
    EXPECT_EQ(0, std::memcmp(a.fluids[f].velocities.data(), b.fluids[f].velocities.data(),
                             a.fluids[f].velocities.size() * sizeof(float)));
  }
}

TEST(Simulation, SnapshotIsInStableIdOrderWhateverTheSorting) {
  Model m = twoFluids();
  m.table = forces::InteractionTable(2);  // no interactions: particles fly straight
  m.table.set(0, 0, {forces::Linear{0, 0.5, 0, 0}, 0, 0});
  State s = cloudState(500, 3, m);
  std::vector<std::array<float, 6>> initial(s.particles.size());
  for (std::size_t i = 0; i < s.particles.size(); ++i)
    initial[s.particles.id[i]] = {s.particles.px[i], s.particles.py[i], s.particles.pz[i],
                                  s.particles.vx[i], s.particles.vy[i], s.particles.vz[i]};
  Simulation sim(m, s);
  sim.advanceFrame();  // sorts the store by cell
  const FrameSnapshot snap = sim.snapshot();
  const double t = 1.0 / 24;
  std::uint32_t expectedId = 0;
  for (const FluidSnapshot& f : snap.fluids)
    for (std::size_t k = 0; k < f.count(); ++k, ++expectedId) {
      ASSERT_EQ(f.ids[k], expectedId);
      for (int a = 0; a < 3; ++a)
        ASSERT_NEAR(f.positions[3 * k + a], initial[expectedId][a] + t * initial[expectedId][3 + a], 1e-4);
    }
  EXPECT_EQ(snap.frame, 1);
  EXPECT_DOUBLE_EQ(snap.time, t);
}

TEST(Simulation, PairListNeverMissesAPairWhileParticlesMove) {
  // Position-only forces and velocity Verlet: after each step the store holds the
  // forces of the current positions, computed from a pair list that may be several
  // substeps old. They must equal a brute-force sum over all pairs.
  Model m = twoFluids();
  m.integrator = Integrator::VelocityVerlet;
  m.table = forces::InteractionTable(2);
  m.table.set(0, 0, {forces::Linear{3, 1.0, 0, 3}, 0, 0});
  m.table.set(1, 1, {forces::LennardJones{2, 0.9, -1, 20, 1.4}, 0, 0});
  m.table.set(0, 1, {forces::Linear{5, 1.2, 0, 5}, 0, 0});
  State s = cloudState(1500, 8, m);
  for (std::size_t i = 0; i < s.particles.size(); ++i) s.particles.vx[i] *= 6.0f;  // fast
  Simulation sim(m, s);
  for (int k = 0; k < 40; ++k) {
    sim.step();
    ASSERT_LT(testing::relativeForceError(m.table, sim.state().particles), 1e-3) << "step " << k;
  }
  EXPECT_GT(sim.listBuilds(), 2) << "the test must cross list rebuilds";
  EXPECT_LT(sim.listBuilds(), 40) << "the list must be reused between rebuilds";
}

TEST(Simulation, WallsKeepEveryParticleInsideTheContainer) {
  Model m;
  State s;
  scenarios::fluidBlock(3000, 1.0, m, s);
  m.container->lo = {-8, 0, -8};
  m.container->hi = {8, 30, 8};
  m.container->closed = true;
  for (std::size_t i = 0; i < s.particles.size(); ++i) s.particles.vx[i] = 40.0f * ((i % 3) - 1.0f);
  Simulation sim(m, s);
  for (int f = 0; f < 12; ++f) {
    sim.advanceFrame();
    const ParticleStore& p = sim.state().particles;
    for (std::size_t i = 0; i < p.size(); ++i) {
      ASSERT_GE(p.px[i], -7.5f); ASSERT_LE(p.px[i], 7.5f);
      ASSERT_GE(p.py[i], 0.5f);  ASSERT_LE(p.py[i], 29.5f);
      ASSERT_GE(p.pz[i], -7.5f); ASSERT_LE(p.pz[i], 7.5f);
    }
  }
}

// One particle sliding on the floor of a big container at speed v0 along x.
Model slider(int substeps, double friction, double restitution) {
  Model m;
  m.substeps = substeps;
  m.fluids.push_back({"puck", {1, 1, 1}, 1, 1, 0, 1});
  m.materials.push_back({1.0f, 0.5f});
  m.table = forces::InteractionTable(1);
  m.table.set(0, 0, {forces::Linear{0, 1, 0, 0}, 0, 0});
  Container c;
  c.lo = {-1000, 0, -1000};
  c.hi = {1000, 100, 1000};
  c.friction = friction;
  c.restitution = restitution;
  m.container = c;
  return m;
}

TEST(Walls, SlidingFrictionIsCoulombAndIndependentOfSubsteps) {
  // Resting contact: the normal impulses carry the weight, so friction decelerates the
  // slider at mu * g. Distance after 1 s from 5 units/s: 5 - mu g / 2.
  const double mu = 0.05, g = 9.81;
  for (int substeps : {4, 8, 32}) {
    const Model m = slider(substeps, mu, 0.2);
    State s;
    s.particles.add(0, 0.5f, 0, 5, 0, 0, 0, 0);
    Simulation sim(m, s);
    for (int f = 0; f < 24; ++f) sim.advanceFrame();
    EXPECT_NEAR(sim.state().particles.px[0], 5 - mu * g / 2, 0.03) << substeps << " substeps";
    EXPECT_NEAR(sim.state().particles.py[0], 0.5f, 1e-3) << "stays on the floor";
  }
}

// A particle at rest on the floor stays at rest with a velocity of 0: it once bounced
// off at e times what gravity gave it each substep, so a resting particle carried an
// upward velocity into the caches (motion blur would smear it). A drop still bounces.
TEST(Walls, AParticleRestingOnTheFloorHasNoVelocityAndADropStillBounces) {
  for (const Integrator integrator : {Integrator::SymplecticEuler, Integrator::VelocityVerlet}) {
    Model m = slider(8, 0.1, 0.5);
    m.integrator = integrator;
    State s;
    s.particles.add(0, 0.5f, 0, 0, 0, 0, 0, 0);  // on the floor
    s.particles.add(0, 3.0f, 5, 0, 0, 0, 0, 0);  // 2.5 above it
    Simulation sim(m, s);
    double highestAfterBounce = 0;
    bool fell = false;
    for (int f = 0; f < 24; ++f) {
      sim.advanceFrame();
      const ParticleStore& p = sim.state().particles;
      const std::size_t rest = p.px[0] < 2.5f ? 0 : 1, drop = 1 - rest;
      EXPECT_EQ(p.py[rest], 0.5f);
      // Verlet's closing half kick adds g dt / 2 after the walls.
      EXPECT_LE(std::abs(p.vy[rest]),
                integrator == Integrator::VelocityVerlet ? 0.5 * 9.81 * sim.dt() + 1e-6 : 0.0);
      fell = fell || p.vy[drop] > 0;
      if (fell) highestAfterBounce = std::max(highestAfterBounce, static_cast<double>(p.py[drop]));
    }
    // Dropped 2.5 onto the floor at e = 0.5: it rises about 0.25 * 2.5 again.
    EXPECT_NEAR(highestAfterBounce, 0.5 + 0.25 * 2.5, 0.1) << static_cast<int>(integrator);
  }
}

TEST(Walls, ImpactScalesTangentialVelocityByOneMinusFriction) {
  // Head-on enough that the Coulomb cap does not bind: v_t -> (1 - mu) v_t, v_n -> -e v_n.
  Model m = slider(8, 0.3, 0.5);
  m.gravity = Vec3::Zero();
  State s;
  s.particles.add(0, 0.55f, 0, 3, -10, 4, 0, 0);  // reaches the floor (y = 0.5) this step
  Simulation sim(m, s);
  sim.step();
  const ParticleStore& p = sim.state().particles;
  EXPECT_FLOAT_EQ(p.py[0], 0.5f);
  EXPECT_NEAR(p.vy[0], 5.0, 1e-5);
  EXPECT_NEAR(p.vx[0], 0.7 * 3, 1e-5);
  EXPECT_NEAR(p.vz[0], 0.7 * 4, 1e-5);
}

TEST(Walls, OpenTopLetsParticlesOutAClosedOneDoesNot) {
  for (bool closed : {false, true}) {
    Model m = slider(8, 0, 1);
    m.gravity = Vec3::Zero();
    m.container->hi = {1000, 10, 1000};
    m.container->closed = closed;
    State s;
    s.particles.add(0, 5, 0, 0, 150, 0, 0, 0);  // 12.5 units in two frames
    Simulation sim(m, s);
    sim.advanceFrame();
    sim.advanceFrame();
    if (closed) {
      EXPECT_LE(sim.state().particles.py[0], 9.5f);
      EXPECT_LT(sim.state().particles.vy[0], 0.0f) << "bounced off the lid";
    } else {
      EXPECT_GT(sim.state().particles.py[0], 10.0f) << "left through the open top";
    }
  }
}

/// The message of the BlowUpError one frame raises ("" when none).
std::string blowUpMessage(Simulation& sim) {
  try {
    sim.advanceFrame();
  } catch (const BlowUpError& e) {
    return e.what();
  }
  return {};
}

TEST(Simulation, BlowUpIsReportedWithFrameFluidAndParticle) {
  Model m = twoFluids();
  State s = cloudState(50, 1, m);
  s.particles.vy[7] = std::numeric_limits<float>::quiet_NaN();
  const std::uint32_t id = s.particles.id[7];
  Simulation sim(m, s);
  const std::string msg = blowUpMessage(sim);
  ASSERT_FALSE(msg.empty()) << "expected BlowUpError";
  EXPECT_NE(msg.find("frame 1"), std::string::npos) << msg;
  EXPECT_NE(msg.find("particle id " + std::to_string(id)), std::string::npos) << msg;
  EXPECT_NE(msg.find("is nan"), std::string::npos) << msg;
  EXPECT_NE(msg.find("forces too stiff for the time step: raise Substeps or use --adaptive"), std::string::npos)
      << msg;
  // With adaptive substeps on, the remedy does not suggest turning them on.
  m.adaptiveSubsteps = true;
  m.maxSubsteps = 40;
  Simulation adaptive(m, s);
  const std::string a = blowUpMessage(adaptive);
  EXPECT_EQ(a.find("use --adaptive"), std::string::npos) << a;
  EXPECT_NE(a.find("--max-substeps (now 40)"), std::string::npos) << a;
}

// A finite speed whose square overflows float is named as it is (a review: "speed is
// inf units/s" for 1e20).
TEST(Simulation, AnAbsurdButFiniteSpeedIsNamedAsItIs) {
  Model m = twoFluids();
  m.container.reset();
  State s = cloudState(10, 1, m);
  s.particles.vy[3] = 1e20f;
  Simulation sim(m, s);
  const std::string msg = blowUpMessage(sim);
  EXPECT_NE(msg.find("speed is 1e+20 units/s"), std::string::npos) << msg;
}

TEST(Simulation, EverySubstepIsCheckedAndTheLowestBadIdIsNamed) {
  Model m = twoFluids();
  State s = cloudState(50, 1, m);
  // Finite but absurd speeds: far beyond maxTravelPerSubstep interaction distances.
  s.particles.vx[9] = 1e9f;
  s.particles.vz[4] = -1e9f;
  const std::uint32_t lowest = std::min(s.particles.id[9], s.particles.id[4]);
  Simulation sim(m, s);
  const std::string msg = blowUpMessage(sim);
  ASSERT_FALSE(msg.empty()) << "expected BlowUpError";
  EXPECT_NE(msg.find("frame 1, substep 1 of " + std::to_string(m.substeps)), std::string::npos) << msg;
  EXPECT_NE(msg.find("particle id " + std::to_string(lowest) + ":"), std::string::npos) << msg;
  EXPECT_NE(msg.find("speed is"), std::string::npos) << msg;
  EXPECT_NE(msg.find("fluid '"), std::string::npos) << msg;
  // A finite speed may be real (a long fall): the remedy says so, not only "too stiff".
  EXPECT_NE(msg.find("faster than the time step allows"), std::string::npos) << msg;
  EXPECT_NE(msg.find("--speed-limit"), std::string::npos) << msg;
  EXPECT_EQ(sim.state().frame, 0) << "the frame was not completed";
}

TEST(Simulation, TheSpeedCheckFollowsItsLimitAndCanBeTurnedOff) {
  Model m = twoFluids();
  State s = cloudState(50, 1, m);
  for (std::size_t i = 0; i < s.particles.size(); ++i) s.particles.vx[i] = s.particles.vy[i] = s.particles.vz[i] = 0;
  EXPECT_EQ(Simulation(m, s).travelPerSubstep(), 0.0) << "nothing moves";
  // A particle that covers 5 interaction distances a substep passes a limit of 10 and
  // fails one of 2.
  const double cutoff = std::sqrt(m.table.rowCutoff2(s.particles.material[0]));
  s.particles.vy[0] = static_cast<float>(5 * cutoff * m.framesPerSecond * m.substeps);
  Simulation moving(m, s);
  EXPECT_NEAR(moving.travelPerSubstep(), 5.0, 1e-3);
  m.maxTravelPerSubstep = 10;
  EXPECT_NO_THROW(Simulation(m, s).checkFinite());
  m.maxTravelPerSubstep = 2;
  EXPECT_THROW(Simulation(m, s).checkFinite(), BlowUpError);
  m.maxTravelPerSubstep = 0;  // off: only non-finite values fail
  s.particles.vy[0] = 1e30f;
  EXPECT_NO_THROW(Simulation(m, s).checkFinite());
  s.particles.vy[0] = std::numeric_limits<float>::infinity();
  EXPECT_THROW(Simulation(m, s).checkFinite(), BlowUpError);
}

// The sweep is built twice (baseline and AVX2, chosen with the pair kernels' copy,
// fluid::useSimd); both must give the same bits and the same verdicts for every
// integrator: two materials of different masses and reaches, gravity and closed walls
// from the first substep, 5,000 particles (two of the sweep's blocks, a partial run of
// 8), list rebuilds; then a speed limit that each copy must trip at the same substep,
// naming the same particle (the check reads the sweep's own scan).
TEST(Sweep, BaselineAndAvx2CopiesAreBitwiseTheSame) {
  struct Restore {
    fluid::Simd simd = fluid::simdInUse();
    ~Restore() { fluid::useSimd(simd); }
  } const restore;
  if (!fluid::useSimd(fluid::Simd::Avx2)) GTEST_SKIP() << "no AVX2 copy in this build or on this CPU";
  for (const Integrator integrator :
       {Integrator::SymplecticEuler, Integrator::ExplicitEuler, Integrator::VelocityVerlet}) {
    Model m = twoFluids();
    m.integrator = integrator;
    m.gravity = Vec3(0, -9.81, 0);
    Container box;
    box.lo = {-8.5, -8.5, -8.5};
    box.hi = {8.5, 8.5, 8.5};
    box.closed = true;
    m.container = box;
    const State s = cloudState(5000, 17, m, 8.0f);
    ASSERT_NE(std::sqrt(m.table.rowCutoff2(0)), std::sqrt(m.table.rowCutoff2(1)));  // two reaches
    Simulation baseline(m, s), avx2(m, s);
    for (int k = 0; k < 96; ++k) {
      ASSERT_TRUE(fluid::useSimd(fluid::Simd::Baseline));
      baseline.step();
      ASSERT_TRUE(fluid::useSimd(fluid::Simd::Avx2));
      avx2.step();
      ASSERT_TRUE(scenarios::stateBytes(baseline, true) == scenarios::stateBytes(avx2, true))
          << static_cast<int>(integrator) << ": differ after substep " << k + 1;
    }
    EXPECT_GT(avx2.listBuilds(), 1);
    // A limit above the first state's fastest travel, which gravity and the pairs soon pass.
    m.maxTravelPerSubstep = 1.2 * Simulation(m, s).travelPerSubstep();
    Simulation limitedBaseline(m, s), limitedAvx2(m, s);
    std::string onBaseline, onAvx2;
    for (int f = 0; f < 24 && onBaseline.empty() && onAvx2.empty(); ++f) {
      ASSERT_TRUE(fluid::useSimd(fluid::Simd::Baseline));
      onBaseline = blowUpMessage(limitedBaseline);
      ASSERT_TRUE(fluid::useSimd(fluid::Simd::Avx2));
      onAvx2 = blowUpMessage(limitedAvx2);
    }
    EXPECT_NE(onAvx2.find("speed is"), std::string::npos) << static_cast<int>(integrator) << ": " << onAvx2;
    EXPECT_EQ(onAvx2, onBaseline) << static_cast<int>(integrator);
  }
}

TEST(FrameLoop, ObserversSeeFrameZeroThenEveryFrameAndStopEarly) {
  struct Recorder : FrameObserver {
    std::vector<std::int64_t> frames;
    void onFrame(const FrameSnapshot& f) override { frames.push_back(f.frame); }
  } rec;
  Model m = twoFluids();
  Simulation sim(m, cloudState(100, 2, m));
  FrameObserver* obs[] = {&rec};
  std::vector<std::pair<std::int64_t, bool>> progress;  // frame, initial
  FrameLoopHooks hooks;
  hooks.onProgress = [&](const FrameProgress& p) {
    progress.emplace_back(p.frame, p.initial);
    EXPECT_EQ(p.lastFrame, 3);
    EXPECT_EQ(p.initial, p.frame == 0);
    EXPECT_GE(p.stepSeconds, 0);
    if (p.initial) {
      EXPECT_EQ(p.stepSeconds, 0);
    }
  };
  EXPECT_TRUE(runFrames(sim, 3, obs, hooks));
  EXPECT_EQ(rec.frames, (std::vector<std::int64_t>{0, 1, 2, 3}));
  // Frame 0 too, as written and not simulated (its surfaces can take long).
  EXPECT_EQ(progress,
            (std::vector<std::pair<std::int64_t, bool>>{{0, true}, {1, false}, {2, false}, {3, false}}));
  std::atomic<bool> stop{true};
  hooks.stop = &stop;
  EXPECT_FALSE(runFrames(sim, 6, obs, hooks));
  EXPECT_EQ(sim.state().frame, 3);
}

}  // namespace
}  // namespace softsub::solver
