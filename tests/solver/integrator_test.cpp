// Free fall and one bounce against each integrator's exact discrete answer.
#include <gtest/gtest.h>

#include <cmath>

#include "solver/simulation.h"

namespace softsub::solver {
namespace {

// One lone particle (no neighbours), gravity only; optionally a floor.
Model loneParticleModel(Integrator integrator, bool floor, double restitution) {
  Model m;
  m.framesPerSecond = 24;
  m.substeps = 8;
  m.gravity = Vec3(0, -9.81, 0);
  m.integrator = integrator;
  m.fluids.push_back({"drop", {1, 1, 1}, 0.5, 1.0, 0, 1});
  m.materials.push_back({1.0f, 0.25f});
  m.table = forces::InteractionTable(1);
  m.table.set(0, 0, {forces::Linear{1, 1, 0, 1}, 0, 0});
  if (floor) {
    Container c;
    c.lo = {-100, 0, -100};
    c.hi = {100, 100, 100};
    c.restitution = restitution;
    c.friction = 0;
    m.container = c;
  }
  return m;
}

State loneParticle(double y0, double v0) {
  State s;
  s.particles.add(0, static_cast<float>(y0), 0, 0, static_cast<float>(v0), 0, 0, 0);
  return s;
}

// Closed forms of n steps under constant acceleration g from (y0, v0):
//   every scheme: v_n = v0 + n g dt
//   symplectic Euler: y_n = y0 + n v0 dt + g dt^2 n(n+1)/2
//   explicit Euler:   y_n = y0 + n v0 dt + g dt^2 n(n-1)/2
//   velocity Verlet:  y_n = y0 + n v0 dt + g dt^2 n^2/2
double exactY(Integrator in, double y0, double v0, double g, double dt, double n) {
  const double k = in == Integrator::SymplecticEuler ? n * (n + 1) / 2
                   : in == Integrator::ExplicitEuler ? n * (n - 1) / 2
                                                     : n * n / 2;
  return y0 + n * v0 * dt + g * dt * dt * k;
}

class EachIntegrator : public ::testing::TestWithParam<Integrator> {};

TEST_P(EachIntegrator, FreeFallMatchesTheDiscreteSolution) {
  const Model m = loneParticleModel(GetParam(), false, 0);
  Simulation sim(m, loneParticle(50, 2));
  const double dt = m.dt(), g = -9.81;
  for (int n = 1; n <= 96; ++n) {
    sim.step();
    const bool frameEnd = n % m.substeps == 0;
    if (frameEnd) sim.finishFrame();
    const ParticleStore& p = sim.state().particles;
    // Velocity Verlet runs in leapfrog form inside a frame: between two of its substeps
    // the velocity is the half-step one, v0 + (n - 1/2) g dt; at the frame's end v_n.
    const double kicks = GetParam() == Integrator::VelocityVerlet && !frameEnd ? n - 0.5 : n;
    ASSERT_NEAR(p.vy[0], 2 + kicks * g * dt, 1e-5) << n;
    ASSERT_NEAR(p.py[0], exactY(GetParam(), 50, 2, g, dt, n), 2e-5 * 50) << n;
  }
}

// A frame ended after fewer substeps than the scene's (the viewer after an edit between
// two substeps continues in a new simulation, whose count starts again) still ends with
// whole-step velocities; so does a state taken mid-frame through levelVelocities().
TEST_P(EachIntegrator, FinishFrameLevelsVelocitiesAfterAnyNumberOfSubsteps) {
  const Model m = loneParticleModel(GetParam(), false, 0);
  const double dt = m.dt(), g = -9.81;
  for (int n = 1; n < m.substeps; ++n) {
    Simulation sim(m, loneParticle(50, 2)), copy(m, loneParticle(50, 2));
    for (int k = 0; k < n; ++k) {
      sim.step();
      copy.step();
    }
    sim.finishFrame();
    EXPECT_NEAR(sim.state().particles.vy[0], 2 + n * g * dt, 1e-5) << n;
    EXPECT_NEAR(sim.state().particles.py[0], exactY(GetParam(), 50, 2, g, dt, n), 2e-5 * 50) << n;
    copy.levelVelocities();
    EXPECT_EQ(copy.state().particles.vy[0], sim.state().particles.vy[0]) << n;
    copy.levelVelocities();  // once only
    EXPECT_EQ(copy.state().particles.vy[0], sim.state().particles.vy[0]) << n;
  }
}

TEST_P(EachIntegrator, OneBounceMatchesTheDiscreteSolution) {
  // Dropped from rest at y0: the first step whose position goes below the radius puts
  // the particle on the floor with velocity -e v; from there it is free flight again.
  const double e = 0.6, r = 0.25, y0 = 3, g = -9.81;
  const Model m = loneParticleModel(GetParam(), true, e);
  const double dt = m.dt();
  int contact = 0;
  for (int n = 1; n < 100000; ++n)
    if (exactY(GetParam(), y0, 0, g, dt, n) < r) { contact = n; break; }
  ASSERT_GT(contact, 0);
  Simulation sim(m, loneParticle(y0, 0));
  for (int n = 1; n <= contact; ++n) sim.step();
  const ParticleStore& p = sim.state().particles;
  // Velocity just before the contact: what the scheme had at step `contact`.
  const double vBefore = GetParam() == Integrator::VelocityVerlet
                             ? (contact - 0.5) * g * dt   // the half-step velocity hits the wall
                             : (GetParam() == Integrator::SymplecticEuler ? contact * g * dt
                                                                          : contact * g * dt);
  ASSERT_FLOAT_EQ(p.py[0], static_cast<float>(r));
  // After the wall: explicit Euler has already added this step's gravity after the move.
  double vAfter;
  if (GetParam() == Integrator::VelocityVerlet) vAfter = -e * vBefore + 0.5 * g * dt;
  else if (GetParam() == Integrator::ExplicitEuler) vAfter = -e * vBefore;
  else vAfter = -e * vBefore;
  ASSERT_NEAR(p.vy[0], vAfter, 1e-4) << "contact step " << contact;
  ASSERT_GT(p.vy[0], 0.0f);
  // Then free flight from (r, vAfter) until the next contact.
  for (int k = 1; k <= contact / 2; ++k) {
    sim.step();
    const double expected = GetParam() == Integrator::VelocityVerlet
                                ? r + k * vAfter * dt + g * dt * dt * k * k / 2
                                : exactY(GetParam(), r, vAfter, g, dt, k);
    ASSERT_NEAR(sim.state().particles.py[0], expected, 1e-4) << "step " << k << " after the bounce";
  }
  // Restitution took energy out: the apex is e^2 of the drop height, to first order.
  double apex = 0;
  for (int k = 0; k < 4 * contact; ++k) {
    sim.step();
    apex = std::max(apex, static_cast<double>(sim.state().particles.py[0]));
  }
  EXPECT_NEAR((apex - r) / (y0 - r), e * e, 0.06);
}

INSTANTIATE_TEST_SUITE_P(Integrators, EachIntegrator,
                         ::testing::Values(Integrator::ExplicitEuler, Integrator::SymplecticEuler,
                                           Integrator::VelocityVerlet),
                         [](const auto& p) {
                           switch (p.param) {
                             case Integrator::ExplicitEuler: return std::string("ExplicitEuler");
                             case Integrator::SymplecticEuler: return std::string("SymplecticEuler");
                             default: return std::string("VelocityVerlet");
                           }
                         });

}  // namespace
}  // namespace softsub::solver
