// measureEnergy (run --stats, the LAMMPS comparison): analytic values for one pair and
// for gravity, a brute-force cross-check of the pair sum, and conservation under
// velocity Verlet that improves as the time step shrinks.
#include <gtest/gtest.h>

#include <cmath>

#include "forces/function.h"
#include "solver/energy.h"
#include "solver/simulation.h"
#include "support/scenarios.h"

namespace softsub::solver {
namespace {

using scenarios::ljModel;

// The unshifted 12-6 potential at the cutoff (forces::potential reports U unshifted, as
// LAMMPS's lj/cut does by default).
double shift(double rc) {
  const double s6 = std::pow(1.0 / rc, 6);
  return 4.0 * (s6 * s6 - s6);
}

State lattice(int n, float spacing, float speed, Model& m) {
  State s;
  std::uint32_t id = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k, ++id) {
        const int q = static_cast<int>(id);  // signed: the velocity pattern has negative values
        const float jitter = 0.03f * static_cast<float>((q * 37) % 11) / 11.0f;
        s.particles.add(spacing * i + jitter, spacing * j - jitter, spacing * k + 0.5f * jitter,
                        speed * static_cast<float>((q * 7) % 5 - 2), speed * static_cast<float>((q * 3) % 5 - 2),
                        speed * static_cast<float>((q * 11) % 5 - 2), 0, 0);
        s.particles.id.back() = id;
      }
  m.fluids[0].count = id;
  return s;
}

TEST(Energy, OnePairIsTheShiftedLennardJonesPotential) {
  const double rc = 2.5;
  Model m = ljModel(rc);
  for (const double r : {0.95, 1.12246, 1.5, 2.2}) {
    State s;
    s.particles.add(0, 0, 0, 0, 0, 0, 0, 0);
    s.particles.add(static_cast<float>(r), 0, 0, 0, 0, 0, 0, 0);
    s.particles.id = {0, 1};
    m.fluids[0].count = 2;
    const EnergyReport e = measureEnergy(m, s);
    const forces::LennardJonesForce lj{1, 1, rc};
    // The table's integral against the analytic potential shifted to 0 at the cutoff
    // (LAMMPS's lj/cut with pair_modify shift yes).
    const double r32 = static_cast<double>(static_cast<float>(r));
    EXPECT_NEAR(e.pair, forces::potential(lj, r32) - shift(rc), 2e-4) << "r = " << r;
    EXPECT_EQ(e.kinetic, 0.0);
    EXPECT_EQ(e.gravity, 0.0);
  }
}

TEST(Energy, KineticAndGravityAreTheTextbookSums) {
  Model m = ljModel(2.5);
  m.gravity = Vec3(0, -9.81, 0);
  m.materials[0].inverseMass = 0.5f;  // mass 2
  State s;
  s.particles.add(0, 3, 0, 1, 2, 2, 0, 0);     // speed 3, height 3
  s.particles.add(10, -1, 0, 0, 0, 0.5f, 0, 0);  // far apart: no pair
  s.particles.id = {0, 1};
  m.fluids[0].count = 2;
  const EnergyReport e = measureEnergy(m, s);
  EXPECT_NEAR(e.kinetic, 0.5 * 2 * 9 + 0.5 * 2 * 0.25, 1e-12);
  EXPECT_NEAR(e.gravity, 2 * 9.81 * 3 + 2 * 9.81 * -1, 1e-9);
  EXPECT_EQ(e.pair, 0.0);
  EXPECT_NEAR(e.total(), e.kinetic + e.gravity, 1e-12);
}

TEST(Energy, PairSumMatchesABruteForceSumOverAllPairs) {
  const double rc = 2.0;
  Model m = ljModel(rc);
  const State s = lattice(6, 1.1f, 0.0f, m);
  const EnergyReport e = measureEnergy(m, s);
  double brute = 0;
  const ParticleStore& p = s.particles;
  const forces::LennardJonesForce lj{1, 1, rc};
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      const double dx = double(p.px[j]) - p.px[i], dy = double(p.py[j]) - p.py[i], dz = double(p.pz[j]) - p.pz[i];
      const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
      if (r < rc) brute += forces::potential(lj, r) - shift(rc);
    }
  EXPECT_NEAR(e.pair, brute, 1e-4 * std::abs(brute)) << "brute " << brute;
  EXPECT_LT(e.pair, 0.0) << "a lattice near the minimum is bound";
}

// The largest |E(t) - E(0)| over `frames` frames at `substeps` per frame.
double drift(int substeps, int frames) {
  Model m = ljModel(2.5);
  m.framesPerSecond = 10;
  m.substeps = substeps;
  Simulation sim(m, lattice(5, 1.12f, 0.3f, m));
  const double e0 = measureEnergy(m, sim.state()).total();
  double worst = 0;
  for (int f = 0; f < frames; ++f) {
    sim.advanceFrame();
    worst = std::max(worst, std::abs(measureEnergy(m, sim.state()).total() - e0));
  }
  return worst;
}

TEST(Energy, VelocityVerletConservesItAndBetterWithSmallerSteps) {
  // With the potential of the sampled force itself, only the integrator's error is left:
  // second order, so halving the step cuts the drift by about four.
  const double coarse = drift(20, 4), fine = drift(40, 4);
  EXPECT_LT(fine, 0.6 * coarse) << "coarse " << coarse << ", fine " << fine;
  EXPECT_LT(fine, 0.01 * 125) << "per particle drift too large";
}

TEST(Energy, MeasuringDoesNotChangeTheRun) {
  Model m = ljModel(2.5);
  m.substeps = 8;
  auto run = [&](bool measure) {
    Simulation sim(m, lattice(5, 1.12f, 0.3f, m));
    for (int f = 0; f < 3; ++f) {
      if (measure) (void)measureEnergy(m, sim.state());
      sim.advanceFrame();
    }
    return sim.snapshot();
  };
  const FrameSnapshot a = run(false), b = run(true);
  EXPECT_EQ(a.fluids[0].positions, b.fluids[0].positions);
  EXPECT_EQ(a.fluids[0].velocities, b.fluids[0].velocities);
}

}  // namespace
}  // namespace softsub::solver
