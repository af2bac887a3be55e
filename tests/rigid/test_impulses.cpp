// The impulse solver on hand-built bodies of one particle each, against the seed's
// closed-form impulse (report 2.3.2.c-d).
#include <gtest/gtest.h>

#include <cmath>

#include "rigid/solver.h"

namespace softsub::rigid {
namespace {

// Two one-particle bodies: A's particle sits off its centre of mass by `offsetA`.
struct TwoBodies {
  BodySet set;
  std::vector<BodyState> states;
  std::vector<ContactMemory> memory;
  ParticleStore store;
  RigidSolver solver;

  TwoBodies(const Vec3& offsetA, double massA, const Vec3& inertiaA, double massB) {
    BodyInfo a;
    a.name = "a";
    a.mass = massA;
    a.inverseMass = 1 / massA;
    a.inverseInertia = inertiaA.cwiseInverse().asDiagonal();
    a.particleRadius = 0.5;
    a.firstId = 0;
    a.count = 1;
    BodyInfo b = a;
    b.name = "b";
    b.mass = massB;
    b.inverseMass = 1 / massB;
    b.inverseInertia = Mat3::Identity();
    b.firstId = 1;
    set.bodies = {a, b};
    set.ox = {static_cast<float>(offsetA.x()), 0};
    set.oy = {static_cast<float>(offsetA.y()), 0};
    set.oz = {static_cast<float>(offsetA.z()), 0};
    states.resize(2);
    store.add(0, 0, 0, 0, 0, 0, 0, 0);
    store.add(0, 0, 0, 0, 0, 0, 0, 1);
    solver.findBodySlots(set, store);
  }

  void step(double dt) {
    solver.writeParticles(set, states, store);
    std::vector<SlotPair> pairs{{0, 1}};
    const std::vector<float> none;
    solver.step(set, states, memory, store, pairs, none, nullptr, nullptr, Vec3::Zero(), dt, dt);
  }
};

TEST(Impulses, OffCentreImpactGivesTheSeedsImpulseAndAngularVelocity) {
  const Vec3 offset(0, 0.5, 0);
  const double mA = 2, mB = 1, e = 0.6;
  const Vec3 inertia(0.3, 0.4, 0.5);
  TwoBodies w(offset, mA, inertia, mB);
  for (BodyInfo& b : w.set.bodies) {
    b.restitution = e;
    b.friction = 0;
  }
  // B's particle overlaps A's by 0.1 on the x axis, moving at -x.
  w.states[1].position = Vec3(0.9, 0.5, 0);
  w.states[1].velocity = Vec3(-1, 0, 0);
  w.step(1e-4);

  // Contact point between the two particle centres; normal from B to A.
  const Vec3 n(-1, 0, 0);
  const Vec3 point(0.45, 0.5, 0);
  const Vec3 ra = point - Vec3::Zero();
  const Vec3 rn = ra.cross(n);
  const Mat3 invI = inertia.cwiseInverse().asDiagonal();
  const double vrel = (Vec3::Zero() - Vec3(-1, 0, 0)).dot(n);
  const double j = -(1 + e) * vrel / (1 / mA + 1 / mB + (invI * rn).cross(ra).dot(n));
  const Vec3 wA = invI * ra.cross(j * n);
  EXPECT_NEAR(w.states[0].velocity.x(), -j / mA, 1e-9);
  EXPECT_NEAR(w.states[1].velocity.x(), -1 + j / mB, 1e-9);
  const Vec3 omega = angularVelocity(w.set.bodies[0], w.states[0]);
  EXPECT_NEAR(omega.z(), wA.z(), 1e-9);
  EXPECT_GT(std::abs(omega.z()), 0.1);  // a real spin, not a rounding residue
  EXPECT_NEAR(omega.x(), 0, 1e-12);
  // The contact point's normal velocities obey restitution: separation = e * approach.
  const Vec3 vA = w.states[0].velocity + omega.cross(ra);
  const double after = (vA - w.states[1].velocity).dot(n);
  EXPECT_NEAR(after, -e * vrel, 1e-9);
}

TEST(Impulses, MomentumIsConservedWithFriction) {
  TwoBodies w(Vec3(0.1, 0.4, -0.2), 3, Vec3(0.2, 0.7, 0.5), 1.5);
  for (BodyInfo& b : w.set.bodies) {
    b.restitution = 0.3;
    b.friction = 0.8;
  }
  w.states[0].velocity = Vec3(0.2, 0, 0.1);
  w.states[0].angularMomentum = Vec3(0.05, -0.1, 0.3);
  // Touching within the slop: the interpenetration fix (which moves bodies without
  // momentum, and so changes the angular momentum x × m v) stays out of it.
  w.states[1].position = Vec3(0.1, 0.4, -0.2) + Vec3(0.996, 0, 0);
  w.states[1].velocity = Vec3(-2, 0.5, 0.7);
  auto momenta = [&] {
    Vec3 p = Vec3::Zero(), l = Vec3::Zero();
    for (std::size_t b = 0; b < 2; ++b) {
      const Vec3 mv = w.set.bodies[b].mass * w.states[b].velocity;
      p += mv;
      l += w.states[b].position.cross(mv) + w.states[b].angularMomentum;
    }
    return std::pair{p, l};
  };
  const auto [p0, l0] = momenta();
  for (int k = 0; k < 50; ++k) w.step(1e-3);
  ASSERT_FALSE(w.solver.contacts().empty() && w.states[0].velocity.isApprox(Vec3(0.2, 0, 0.1)));
  const auto [p1, l1] = momenta();
  EXPECT_LT((p1 - p0).norm(), 1e-9 * p0.norm());
  EXPECT_LT((l1 - l0).norm(), 1e-9 * (l0.norm() + 1));
}

TEST(Impulses, FrictionStaysInsideTheCoulombCone) {
  TwoBodies w(Vec3::Zero(), 1, Vec3(1, 1, 1), 1);
  for (BodyInfo& b : w.set.bodies) {
    b.restitution = 0;
    b.friction = 0.2;
  }
  // A grazing hit: mostly tangential.
  w.states[1].position = Vec3(0.95, 0, 0);
  w.states[1].velocity = Vec3(-0.1, 3, 0);
  w.step(1e-4);
  ASSERT_EQ(w.solver.contacts().size(), 1U);
  const Contact& c = w.solver.contacts()[0];
  EXPECT_GT(c.lambdaN, 0);
  EXPECT_LE(std::hypot(c.lambdaT1, c.lambdaT2), 0.2 * c.lambdaN * (1 + 1e-12));
  EXPECT_GT(std::hypot(c.lambdaT1, c.lambdaT2), 0.19 * c.lambdaN);  // sliding: on the cone
}

TEST(Impulses, SeparatingBodiesAreLeftAlone) {
  TwoBodies w(Vec3::Zero(), 1, Vec3(1, 1, 1), 1);
  w.states[1].position = Vec3(0.9, 0, 0);
  w.states[1].velocity = Vec3(1, 0, 0);  // already moving apart
  w.step(1e-4);
  EXPECT_NEAR(w.states[1].velocity.x(), 1, 1e-12);
  EXPECT_NEAR(w.states[0].velocity.norm(), 0, 1e-12);
}

}  // namespace
}  // namespace softsub::rigid
