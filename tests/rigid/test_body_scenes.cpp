// Rigid bodies made of particles, compiled from scene descriptions and stepped by the
// full solver: rebound, rest, sliding friction, momentum, and two-way fluid coupling.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "support/bodies.h"

namespace softsub::scenarios {
namespace {

using scene::ObjectShape;

scene::SceneDesc floorScene(double restitution, double friction) {
  scene::SceneDesc d;
  scene::EnvironmentDesc env;
  env.width = env.depth = 10;
  env.height = 20;
  env.normalAttenuation = restitution;
  env.tangentAttenuation = friction;
  d.environment = env;
  return d;
}

// Height of the centre of mass at which the body's lowest particle touches the floor.
double touchHeight(const BodyRun& run, std::size_t b) {
  const rigid::BodySet& set = run.compiled.model.bodies;
  const rigid::BodyInfo& info = run.info(b);
  double lowest = 0;
  for (std::uint32_t k = info.firstId - set.firstId; k < info.firstId - set.firstId + info.count; ++k)
    lowest = std::min(lowest, static_cast<double>(set.oy[k]));
  return -lowest + info.particleRadius;
}

TEST(BodyScenes, ABallReboundsToRestitutionSquaredOfItsHeight) {
  for (const double e : {0.5, 0.8}) {
    scene::SceneDesc d = floorScene(e, 0.1);
    scene::ObjectDesc ball = primitiveObject("ball", ObjectShape::Sphere, {0.5}, 0.1, Vec3(0, 3, 0));
    ball.normalAttenuation = e;  // the mean of ball and floor is e
    d.objects.push_back(ball);
    BodyRun run(d);
    const double contact = touchHeight(run, 0);
    const double drop = run.body(0).position.y() - contact;
    double apex = 0;
    bool bounced = false;
    for (int k = 0; k < 8 * 24 * 3 && !(bounced && run.body(0).velocity.y() < 0); ++k) {
      run.sim->step();
      if (run.body(0).velocity.y() > 0) bounced = true;
      if (bounced) apex = std::max(apex, run.body(0).position.y() - contact);
    }
    ASSERT_TRUE(bounced);
    EXPECT_NEAR(apex / drop, e * e, 0.05 * e * e) << "e = " << e << ", drop " << drop << ", apex " << apex;
    // Straight down, straight up: no spin, no sideways drift beyond 1% of the drop.
    EXPECT_LT(std::abs(run.body(0).position.x()), 0.01 * drop);
    EXPECT_LT(std::abs(run.body(0).position.z()), 0.01 * drop);
    EXPECT_LT(rigid::angularVelocity(run.info(0), run.body(0)).norm(), 0.05);
  }
}

TEST(BodyScenes, ABoxRestingOnTheFloorForTenSecondsStaysPut) {
  scene::SceneDesc d = floorScene(0.5, 0.5);
  d.simulation.frames = 240;
  scene::ObjectDesc box = primitiveObject("box", ObjectShape::Box, {1, 1, 1}, 0.1, Vec3(0.3, 0, -0.2));
  d.objects.push_back(box);
  BodyRun probe(d);
  d.objects[0].initialPosition.y() = touchHeight(probe, 0);  // resting on the floor
  BodyRun run(d);
  const Vec3 start = run.body(0).position;
  double worst = 0;
  for (int f = 0; f < 240; ++f) {
    run.sim->advanceFrame();
    // The farthest any corner moved: translation plus rotation times the half diagonal.
    const double turned = Eigen::AngleAxisd(run.body(0).orientation).angle();
    worst = std::max(worst, (run.body(0).position - start).norm() + turned * std::sqrt(0.75));
  }
  EXPECT_LT(worst, 0.01) << "moved " << worst << " (1% of the box's size is 0.01)";
}

TEST(BodyScenes, ASlidingBoxStopsAtTheCoulombDistance) {
  const double mu = 0.3;
  scene::SceneDesc d = floorScene(0.0, mu);
  scene::ObjectDesc box = primitiveObject("box", ObjectShape::Box, {1, 0.5, 1}, 0.1, Vec3(-3, 0, 0));
  box.tangentAttenuation = mu;
  box.normalAttenuation = 0.0;
  box.initialLinearVelocity = Vec3(3, 0, 0);
  d.objects.push_back(box);
  BodyRun probe(d);
  d.objects[0].initialPosition.y() = touchHeight(probe, 0);
  BodyRun run(d);
  for (int f = 0; f < 48; ++f) {
    run.sim->advanceFrame();
  }
  const double expected = 3.0 * 3.0 / (2 * mu * 9.81);
  EXPECT_NEAR(run.body(0).position.x() + 3, expected, 0.1 * expected);
  EXPECT_LT(run.body(0).velocity.norm(), 1e-3) << run.body(0).velocity.transpose() << " w "
      << rigid::angularVelocity(run.info(0), run.body(0)).transpose();
}

TEST(BodyScenes, TwoBodiesCollidingInFreeSpaceConserveMomentum) {
  scene::SceneDesc d;
  d.simulation.gravity = Vec3::Zero();
  scene::ObjectDesc a = primitiveObject("a", ObjectShape::Box, {1, 2, 1}, 0.2, Vec3(-1.5, 0.3, 0));
  a.initialLinearVelocity = Vec3(2, 0, 0.1);
  a.initialAngularVelocity = Vec3(30, 0, 45);
  a.mass = 2;
  scene::ObjectDesc b = primitiveObject("b", ObjectShape::Sphere, {0.7}, 0.2, Vec3(1, -0.4, 0.1));
  b.initialLinearVelocity = Vec3(-1, 0.2, 0);
  b.tangentAttenuation = 0.5;
  d.objects = {a, b};
  BodyRun run(d);
  auto momenta = [&] {
    Vec3 p = Vec3::Zero(), l = Vec3::Zero();
    for (std::size_t k = 0; k < 2; ++k) {
      const Vec3 mv = run.info(k).mass * run.body(k).velocity;
      p += mv;
      l += run.body(k).position.cross(mv) + run.body(k).angularMomentum;
    }
    return std::pair{p, l};
  };
  const auto [p0, l0] = momenta();
  const Vec3 va0 = run.body(0).velocity;
  for (int f = 0; f < 24; ++f) run.sim->advanceFrame();
  ASSERT_GT((run.body(0).velocity - va0).norm(), 0.5) << "the bodies never met";
  const auto [p1, l1] = momenta();
  EXPECT_LT((p1 - p0).norm(), 1e-4 * p0.norm());
  EXPECT_LT((l1 - l0).norm(), 1e-4 * l0.norm());
}

// A fluid blob flying into a free body: the fluid pushes the body, the body pushes the
// fluid, and their total momentum is what it was (no gravity, no walls).
TEST(BodyScenes, FluidAndBodyPushEachOtherAndConserveMomentum) {
  scene::SceneDesc d;
  d.simulation.gravity = Vec3::Zero();
  scene::FluidDesc goo;
  goo.name = "goo";
  goo.initialSpeed = Vec3(4, 0, 0);
  scene::FillDesc fill;
  fill.shape = scene::FillShape::Box;
  fill.min = Vec3(-6, -1.5, -1.5);
  fill.max = Vec3(-3, 1.5, 1.5);
  fill.spacing = 1;
  goo.fills.push_back(fill);
  d.fluids.push_back(goo);
  scene::ObjectDesc box = primitiveObject("box", ObjectShape::Box, {2, 2, 2}, 0.5, Vec3(0, 0.4, 0));
  box.mass = 20;
  d.objects.push_back(box);
  BodyRun run(d);
  auto momentum = [&] {
    const FrameSnapshot snap = run.sim->snapshot();
    Vec3 p = run.info(0).mass * run.body(0).velocity;
    for (std::size_t k = 0; k < snap.fluids[0].count(); ++k)
      p += Vec3(snap.fluids[0].velocities[3 * k], snap.fluids[0].velocities[3 * k + 1],
                snap.fluids[0].velocities[3 * k + 2]);  // particle mass 1
    return p;
  };
  const Vec3 p0 = momentum();
  for (int f = 0; f < 24; ++f) run.sim->advanceFrame();
  EXPECT_GT(run.body(0).velocity.x(), 0.3) << "the fluid did not push the body";
  const Vec3 p1 = momentum();
  EXPECT_LT((p1 - p0).norm(), 1e-4 * p0.norm()) << p0.transpose() << " vs " << p1.transpose();
}

// Goo poured on a static post never ends inside it.
TEST(BodyScenes, FluidNeverEndsInsideAStaticBody) {
  scene::SceneDesc d = floorScene(0.3, 0.3);
  scene::FluidDesc goo;
  goo.name = "goo";
  scene::FillDesc fill;
  fill.min = Vec3(-1.5, 4, -1.5);
  fill.max = Vec3(1.5, 8, 1.5);
  fill.spacing = 1;
  goo.fills.push_back(fill);
  d.fluids.push_back(goo);
  scene::ObjectDesc post = primitiveObject("post", ObjectShape::Box, {2, 3, 2}, 0.5, Vec3(0, 1.5, 0));
  post.isDynamic = false;
  d.objects.push_back(post);
  BodyRun run(d);
  for (int f = 0; f < 48; ++f) {
    run.sim->advanceFrame();
    const FrameSnapshot snap = run.sim->snapshot();
    const std::vector<float>& p = snap.fluids[0].positions;
    for (std::size_t k = 0; k < snap.fluids[0].count(); ++k) {
      const bool inside = std::abs(p[3 * k]) < 1 && p[3 * k + 1] < 3 && std::abs(p[3 * k + 2]) < 1;
      ASSERT_FALSE(inside) << "frame " << f + 1 << ": particle " << k << " at " << p[3 * k] << " "
                           << p[3 * k + 1] << " " << p[3 * k + 2];
    }
  }
}

}  // namespace
}  // namespace softsub::scenarios
