// Rigid bodies made of particles, compiled from scene descriptions and stepped by the
// full solver: rebound, rest, sliding friction, momentum, and two-way fluid coupling.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <unistd.h>

#include <filesystem>
#include <functional>

#include <Eigen/Eigenvalues>
#include <fmt/format.h>

#include "geometry/mass_properties.h"
#include "geometry/primitives.h"
#include "scene/reader.h"
#include "solver/energy.h"
#include "support/bodies.h"
#include "support/mesh_files.h"
#include "support/meshes.h"

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

// 18 mud particles dropped 0.5 to 1.7 onto a pallet of mass 2 made of 1,600 particles of
// 0.25 (a review's scene); `pallet` is added to the pallet's element, `interactions`
// after it.
std::string mudOnAPallet(const std::string& pallet, const std::string& interactions) {
  return std::string(R"(<Scene version="1"><Environment><Width>20</Width><Height>24</Height><Depth>14</Depth>
         <NormalAttenuation>0.2</NormalAttenuation><TangentAttenuation>0.6</TangentAttenuation></Environment>
         <Fluid><Name>mud</Name><Amplitude>20</Amplitude><MinimumForce>-6</MinimumForce><Viscosity>6</Viscosity>
         <Fill><Shape>box</Shape><Min>0 1.0 -2.4</Min><Max>1.6 2.2 -0.8</Max><Spacing>0.8</Spacing></Fill></Fluid>
         <Object><Name>pallet</Name><Shape>box</Shape><Size>10 0.5 5</Size><ParticleSize>0.25</ParticleSize>
         <InitialPosition>0 0.25 0</InitialPosition><Mass>2</Mass>)") +
         pallet + "</Object>" + interactions + "</Scene>";
}

// The highest total energy at the start and at the end of each of `frames` frames;
// `each` is called after each frame.
double highestTotal(BodyRun& run, int frames, const std::function<void()>& each = {}) {
  double most = solver::measureEnergy(run.compiled.model, run.sim->state()).total();
  for (int f = 0; f < frames; ++f) {
    run.sim->advanceFrame();
    most = std::max(most, solver::measureEnergy(run.compiled.model, run.sim->state()).total());
    if (each) each();
  }
  return most;
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

// A box carrying mud is struck by another (no gravity, no walls): momentum is kept. The
// fluid follows what its bodies did in the whole substep, contact impulses included;
// with the contacts seeing the struck box's own mass only, the mud was carried along for
// free: the total went 10 -> 16 at the default drag and 10 -> 39 at Damping 4 and
// RelativeVelocity 10 (a black-box review, twenty-ninth session). The contacts now see a
// dragging body's mobility with the fluid's inertia.
TEST(BodyScenes, AMudCoveredBoxStruckByAnotherKeepsTheMomentum) {
  for (const char* terms : {"",
                            "<FluidObject><Linear><Cutoff>1.5</Cutoff></Linear><Damping>4</Damping>"
                            "<RelativeVelocity>10</RelativeVelocity></FluidObject>"}) {
    SCOPED_TRACE(*terms ? "strong drag" : "default drag");
    const scene::SceneDesc d = scene::readSceneText(
        std::string(
            R"(<Scene version="1"><Simulation><FramesPerSecond>192</FramesPerSecond><Substeps>1</Substeps>
           <Gravity>0 0 0</Gravity></Simulation>
           <Fluid><Name>mud</Name><Amplitude>20</Amplitude><MinimumForce>-6</MinimumForce><Viscosity>2</Viscosity>
           <Fill><Shape>box</Shape><Min>-1.5 1.5 -1.5</Min><Max>1.5 3.5 1.5</Max><Spacing>1</Spacing></Fill></Fluid>
           <Object><Name>target</Name><Shape>box</Shape><Size>3 2 3</Size><ParticleSize>0.25</ParticleSize>
           <InitialPosition>0 0 0</InitialPosition><Mass>1</Mass></Object>
           <Object><Name>hammer</Name><Shape>box</Shape><Size>2 2 2</Size><ParticleSize>0.5</ParticleSize>
           <InitialPosition>-6 0 0</InitialPosition><InitialLinearVelocity>10 0 0</InitialLinearVelocity>
           <Mass>1</Mass></Object><Interactions>)") +
            terms + "</Interactions></Scene>",
        "hammer.scene");
    BodyRun run(d);
    auto momentum = [&] {
      const FrameSnapshot snap = run.sim->snapshot();
      Vec3 p = run.body(0).velocity + run.body(1).velocity;  // masses 1
      for (std::size_t k = 0; k < snap.fluids[0].count(); ++k)
        p += Vec3(snap.fluids[0].velocities[3 * k], snap.fluids[0].velocities[3 * k + 1],
                  snap.fluids[0].velocities[3 * k + 2]);  // particle mass 1
      return p;
    };
    const Vec3 p0 = momentum();
    ASSERT_NEAR(p0.x(), 10, 1e-9);
    for (int f = 0; f < 96; ++f) run.sim->advanceFrame();
    EXPECT_GT(run.body(0).velocity.x(), 0.3) << "the target was struck";
    // A particle dragging both boxes at once couples their solves, which hold each other
    // still: what that leaves out is a few per cent under strong drag.
    EXPECT_LT((momentum() - p0).norm(), (*terms ? 0.15 : 0.01) * p0.norm()) << momentum().transpose();
  }
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

// Bodies resting on bodies (warm-started contacts, docs/architecture.md "Rigid bodies",
// step 4). Each contact starts its sweeps from the impulse it ended the last substep
// with; starting from zero, twenty sweeps a substep did not carry these loads: the six
// boxes crept (the top one 0.74 in 5 s) and fell at 30 s, the staggered wall walked out
// of its plane (0.75 in 10 s) and fell at 15 s, and the crate of mass 100 sank through
// the plank of mass 1 within 5 s.

// How far each body got from `start` (the largest distance) and turned (radians).
struct Still {
  double moved = 0, turned = 0;
};
Still stillness(const BodyRun& run, const std::vector<rigid::BodyState>& start) {
  Still s;
  for (std::size_t b = 0; b < start.size(); ++b) {
    s.moved = std::max(s.moved, (run.body(b).position - start[b].position).norm());
    s.turned = std::max(s.turned, run.body(b).orientation.angularDistance(start[b].orientation));
  }
  return s;
}

TEST(BodyScenes, ASixBoxStackAndAStaggeredWallStandStill) {
  for (const bool wall : {false, true}) {
    scene::SceneDesc d = floorScene(0.5, 0.1);
    d.environment->width = d.environment->depth = 20;
    if (wall) {  // six rows of bricks 2 x 1 x 1, each row half a brick on from the one below
      for (int row = 0; row < 6; ++row)
        for (int k = 0; k < 3 - row % 2; ++k)
          d.objects.push_back(primitiveObject(fmt::format("brick{}_{}", row, k), ObjectShape::Box, {2, 1, 1},
                                              0.25, Vec3(2.0 * k - 2 + (row % 2), 0.5 + row, 0)));
    } else {
      for (int k = 0; k < 6; ++k)
        d.objects.push_back(
            primitiveObject(fmt::format("box{}", k), ObjectShape::Box, {2, 1, 2}, 0.25, Vec3(0, 0.5 + k, 0)));
    }
    BodyRun run(d);
    for (int f = 0; f < 24; ++f) run.sim->advanceFrame();  // settle into the slop
    const std::vector<rigid::BodyState> settled = run.sim->state().bodies;
    for (int f = 0; f < 9 * 24; ++f) run.sim->advanceFrame();
    const Still s = stillness(run, settled);
    EXPECT_LT(s.moved, 0.01) << (wall ? "wall" : "stack");
    EXPECT_LT(s.turned, 0.005) << (wall ? "wall" : "stack");
    EXPECT_FALSE(run.sim->state().contacts.empty()) << "the resting contacts are remembered";
  }
}

// Mass ratios of 1,000 and more sank through even with the warm start (the sweeps do
// not carry the floor's push up through the light plank in time): shock propagation
// (RigidSolver::propagateShock) holds them.
TEST(BodyScenes, AHeavyCrateRestsOnALightPlank) {
  for (const double mass : {10.0, 100.0, 1000.0, 10000.0}) {
    scene::SceneDesc d = floorScene(0.5, 0.1);
    scene::ObjectDesc plank = primitiveObject("plank", ObjectShape::Box, {4, 1, 4}, 0.25, Vec3(0, 0.5, 0));
    plank.mass = 1;
    scene::ObjectDesc crate = primitiveObject("crate", ObjectShape::Box, {1, 1, 1}, 0.25, Vec3(0, 1.5, 0));
    crate.mass = mass;
    d.objects = {plank, crate};
    BodyRun run(d);
    for (int f = 0; f < 24; ++f) run.sim->advanceFrame();
    const std::vector<rigid::BodyState> settled = run.sim->state().bodies;
    EXPECT_NEAR(settled[1].position.y(), 1.5, 0.02) << "mass " << mass << ": it rests on the plank";
    for (int f = 0; f < 4 * 24; ++f) run.sim->advanceFrame();
    const Still s = stillness(run, settled);
    EXPECT_LT(s.moved, 0.005) << "mass " << mass;
    EXPECT_LT(s.turned, 0.005) << "mass " << mass;
  }
}

// Shock propagation on a tower of a heavy box on light ones: the pass also ran on the
// overlap fix's pseudo-velocities, and there it lifted the heavy box with what the sweeps
// had pushed the light one under it up by: a box of mass 10,000 on two of mass 1 rose,
// the total went up 38% and the tower blew apart (a review, twenty-ninth session). On
// velocities alone nothing gains energy. (The heavy box still squeezes two light ones
// out from under it, 2 to 5 units aside: one level of light bodies is what the pass
// holds, AHeavyCrateRestsOnALightPlank.)
TEST(BodyScenes, AHeavyBoxOnLightOnesGainsNoEnergy) {
  for (const double middle : {1.0, 100.0}) {
    SCOPED_TRACE(fmt::format("masses 1, {}, 10000", middle));
    scene::SceneDesc d = floorScene(0.5, 0.1);
    const double masses[3] = {1, middle, 10000};
    for (int k = 0; k < 3; ++k) {
      scene::ObjectDesc box =
          primitiveObject(fmt::format("b{}", k), ObjectShape::Box, {2, 1, 2}, 0.25, Vec3(0, 0.5 + k, 0));
      box.mass = masses[k];
      d.objects.push_back(box);
    }
    BodyRun run(d);
    const double start = solver::measureEnergy(run.compiled.model, run.sim->state()).total();
    EXPECT_LE(highestTotal(run, 48), start);
  }
}

// A heavy box dropped flat with restitution 0 onto a light one on the floor lands and
// stays: it does not bounce, and nothing gains energy. With the warm start outside the
// energy check (its first form) the big stopping impulse was applied again on the next
// substep as a warm start, and the sweeps, slow to converge at a mass ratio of 50, did
// not take it back: the box bounced 0.81 and the total rose by 413 in a frame (a review,
// twenty-eighth session); on five light boxes by 859. The energy check now scales the
// warm starts with the impact targets. What the overlap fix lifts the heavy box back by
// (it sank into the light one at the impact) is allowed, as in the floor test above.
TEST(BodyScenes, AHeavyBoxDroppedOnALightOneLandsWithoutBouncing) {
  for (const int under : {1, 5}) {
    SCOPED_TRACE(fmt::format("{} light box(es)", under));
    std::string objects;
    for (int k = 0; k < under; ++k)
      objects += fmt::format(
          "<Object><Name>light{}</Name><Shape>box</Shape><Size>2 1 2</Size><ParticleSize>0.5</ParticleSize>"
          "<InitialPosition>0 {} 0</InitialPosition><NormalAttenuation>0</NormalAttenuation></Object>",
          k, 0.5 + k);
    objects += fmt::format(
        "<Object><Name>heavy</Name><Shape>box</Shape><Size>2 1 2</Size><ParticleSize>0.5</ParticleSize>"
        "<InitialPosition>0 {} "
        "0</InitialPosition><Mass>50</Mass><NormalAttenuation>0</NormalAttenuation></Object>",
        under + 4.5);
    const scene::SceneDesc d = scene::readSceneText(
        "<Scene version=\"1\"><Environment><Width>40</Width><Height>40</Height><Depth>40</Depth>"
        "<NormalAttenuation>0</NormalAttenuation><TangentAttenuation>0.5</TangentAttenuation></Environment>" +
            objects + "</Scene>",
        "drop.scene");
    BodyRun run(d);
    const std::size_t heavy = static_cast<std::size_t>(under);
    double least = solver::measureEnergy(run.compiled.model, run.sim->state()).total(), rise = 0;
    double lowest = 1e300, highestAfter = -1e300;
    for (int f = 0; f < 48; ++f) {
      run.sim->advanceFrame();
      const double e = solver::measureEnergy(run.compiled.model, run.sim->state()).total();
      least = std::min(least, e);
      rise = std::max(rise, e - least);  // above the least it had had
      const double y = run.body(heavy).position.y();
      lowest = std::min(lowest, y);
      if (lowest < under + 0.6) highestAfter = std::max(highestAfter, y);  // landed
    }
    ASSERT_LT(lowest, under + 0.6) << "it landed on the light box(es)";
    EXPECT_GT(lowest, under + 0.3) << "it did not go through them";
    const double lift = 50 * 9.81 * 0.25;  // a particle radius
    EXPECT_LE(rise, lift);
    EXPECT_LT(highestAfter - lowest, 0.25) << "no bounce at restitution 0";
  }
}

// A light body of many fine particles under fluid: a pallet of mass 2 (1,600 particles
// of 0.25) and mud dropped 0.9 onto it. The fluid/object function's velocity terms, summed
// over every pair, drag the pallet at a rate far beyond 2 a substep; taken explicitly
// they threw it 20 units up in the first frame (the total 217 -> 1955; a review,
// twenty-eighth session). The body and the fluid take that drag implicitly, solved
// together: the pallet stays on the floor, nothing gains energy (the fluid's own slack
// aside), and momentum is kept (the previous test).
TEST(BodyScenes, ALightPalletUnderMudIsNotThrown) {
  BodyRun run(scene::readSceneText(mudOnAPallet("", ""), "mud.scene"));
  const double start = solver::measureEnergy(run.compiled.model, run.sim->state()).total();
  double highest = 0;
  const double most = highestTotal(run, 48, [&] { highest = std::max(highest, run.body(0).position.y()); });
  EXPECT_LT(highest, 0.3) << "the pallet stays on the floor (its centre at 0.25)";
  EXPECT_LE(most, start * 1.01) << "start " << start;
  EXPECT_LT(rigid::kineticEnergy(run.info(0), run.body(0)), 0.01);
}

// The other side of that drag: a mud particle lying on the same fine pallet has about
// 200 of its particles within reach, and with the fluid/object function's
// RelativeVelocity at 10 (or Damping at 4) their sum damped it explicitly at several
// times 2 a substep: it sped up and flung the mud (the total 212 -> 17,800 within half a
// second on a static pallet, 217 -> 20,900 on a dynamic one; a review, twenty-eighth
// session). Now the fluid particles' velocities take the drag implicitly too.
TEST(BodyScenes, MudOnAFinePalletWithStrongDragIsNotFlung) {
  for (const bool dynamic : {false, true}) {
    for (const char* terms : {"<Damping>0</Damping><RelativeVelocity>10</RelativeVelocity>",
                              "<Damping>4</Damping><RelativeVelocity>0</RelativeVelocity>"}) {
      SCOPED_TRACE(std::string(dynamic ? "dynamic pallet, " : "static pallet, ") + terms);
      const scene::SceneDesc d = scene::readSceneText(
          mudOnAPallet(
              dynamic ? "" : "<IsDynamic>false</IsDynamic>",
              std::string(
                  "<Interactions><FluidObject><Linear><AtZero>5</AtZero><Cutoff>1.5</Cutoff></Linear>") +
                  terms + "</FluidObject></Interactions>"),
          "mud.scene");
      BodyRun run(d);
      const double start = solver::measureEnergy(run.compiled.model, run.sim->state()).total();
      double fastest = 0;
      const double most = highestTotal(run, 24, [&] {
        const ParticleStore& p = run.sim->state().particles;
        for (std::size_t i = 0; i < p.size(); ++i)
          if (p.owner[i] < run.compiled.model.bodies.firstEntity)
            fastest = std::max(fastest, std::sqrt(double(p.vx[i]) * p.vx[i] + double(p.vy[i]) * p.vy[i] +
                                                  double(p.vz[i]) * p.vz[i]));
      });
      EXPECT_LE(most, start * 1.01) << "start " << start;
      EXPECT_LT(fastest, 8.0) << "a fall of 1.2 gives about 5";
      if (dynamic) {
        EXPECT_LT(run.body(0).position.y(), 0.3) << "the pallet stays on the floor";
      }
    }
  }
}

// Fluid arriving fast at a fine body with strong drag (a black-box review, twenty-ninth
// session): a mud particle thrown at 80 units/s onto a static pallet of particles 0.25
// (Damping 4, RelativeVelocity 10) left at 171 units/s, the total 3,222 -> 14,837; a
// blob at 10 units/s into a free box (Damping 40, RelativeVelocity 500, no gravity)
// sent the box off at 327 units/s, the total 1,153 -> 359,765. The implicit drag had
// been set up after the fluid moved, so a particle that had just come within reach was
// held by a drag its forces did not contain (and one that had just left, by none). Now
// it is set up where the forces were evaluated, for every integrator.
TEST(BodyScenes, FluidHittingAFineBodyWithStrongDragIsNotThrownBack) {
  for (const char* integrator : {"symplectic-euler", "velocity-verlet", "explicit-euler"}) {
    SCOPED_TRACE(integrator);
    const scene::SceneDesc drop = scene::readSceneText(
        std::string(R"(<Scene version="1"><Simulation><Substeps>8</Substeps><Integrator>)") + integrator +
            R"(</Integrator></Simulation><Environment/>
           <Fluid><Name>mud</Name><InitialSpeed>0 -80 0</InitialSpeed><Particles>0.0 2.2 0</Particles></Fluid>
           <Object><Name>pallet</Name><Shape>box</Shape><Size>8 0.5 4</Size><ParticleSize>0.25</ParticleSize>
           <InitialPosition>0 0.25 0</InitialPosition><IsDynamic>false</IsDynamic></Object>
           <Interactions><FluidObject><Linear><Cutoff>1.5</Cutoff></Linear><Damping>4</Damping>
           <RelativeVelocity>10</RelativeVelocity></FluidObject></Interactions></Scene>)",
        "drop.scene");
    BodyRun one(drop);
    const double start = solver::measureEnergy(one.compiled.model, one.sim->state()).total();
    EXPECT_LE(highestTotal(one, 24), start * 1.001) << "start " << start;
    const scene::SceneDesc blob = scene::readSceneText(
        std::string(
            R"(<Scene version="1"><Simulation><Substeps>8</Substeps><Gravity>0 0 0</Gravity><Integrator>)") +
            integrator + R"(</Integrator></Simulation>
           <Fluid><Name>goo</Name><Amplitude>20</Amplitude><MinimumForce>-6</MinimumForce><Viscosity>2</Viscosity>
           <InitialSpeed>10 0 0</InitialSpeed>
           <Fill><Shape>box</Shape><Min>-9 -1.5 -1.5</Min><Max>-6 1.5 1.5</Max><Spacing>1</Spacing></Fill></Fluid>
           <Object><Name>box</Name><Shape>box</Shape><Size>3 3 3</Size><ParticleSize>0.25</ParticleSize>
           <InitialPosition>0 0 0</InitialPosition><Mass>5</Mass></Object>
           <Interactions><FluidObject><Linear><Cutoff>1.5</Cutoff></Linear><Damping>40</Damping>
           <RelativeVelocity>500</RelativeVelocity></FluidObject></Interactions></Scene>)",
        "blob.scene");
    BodyRun run(blob);
    const double begin = solver::measureEnergy(run.compiled.model, run.sim->state()).total();
    EXPECT_LE(highestTotal(run, 48), begin * 1.001) << "start " << begin;
    EXPECT_LT(run.body(0).velocity.norm(), 10.0) << "the box takes at most the blob's speed";
  }
}

// Fluid resting on the floor beside a body, with a strong fluid/object Damping: the
// bodies' step corrects the fluid's explicit drag by a change of velocity, and the
// walls bounced the explicit velocity in between, so the change flung the particle: a
// particle at rest 0.5 from a static post went from a total of 80 to 2.8 million in
// the first frame (Damping 8), a ball in a puddle 429 -> 3.9 million (Damping 4,
// RelativeVelocity 10; a black-box review, thirtieth session). The walls now come after
// the bodies' step. Under each integrator, static and dynamic; then a heavy box sinking
// through syrup onto the floor.
TEST(BodyScenes, FluidOnTheFloorBesideABodyWithStrongDragStaysOnTheFloor) {
  for (const char* integrator : {"symplectic-euler", "velocity-verlet", "explicit-euler"})
    for (const char* dynamic : {"false", "true"}) {
      SCOPED_TRACE(fmt::format("{}, dynamic {}", integrator, dynamic));
      const scene::SceneDesc d = scene::readSceneText(
          fmt::format(R"(<Scene version="1"><Simulation><Integrator>{}</Integrator></Simulation>
             <Environment><Width>6</Width><Height>20</Height><Depth>6</Depth></Environment>
             <Fluid><Name>mud</Name><Particles>0 0.5 -1.5  0.8 0.5 -1.6  -0.7 0.5 -1.5</Particles></Fluid>
             <Object><Name>post</Name><Shape>box</Shape><Size>2 3 2</Size><ParticleSize>0.2</ParticleSize>
             <IsDynamic>{}</IsDynamic><InitialPosition>0 1.5 0</InitialPosition><Mass>20</Mass></Object>
             <Interactions><FluidObject><Linear><AtZero>5</AtZero><Cutoff>1.5</Cutoff></Linear>
             <Damping>8</Damping><RelativeVelocity>10</RelativeVelocity></FluidObject></Interactions></Scene>)",
                      integrator, dynamic),
          "floor.scene");
      BodyRun run(d);
      const double start = solver::measureEnergy(run.compiled.model, run.sim->state()).total();
      EXPECT_LE(highestTotal(run, 24), start * 1.001) << "start " << start;
      const ParticleStore& s = run.sim->state().particles;
      for (std::size_t i = 0; i < s.size(); ++i)
        if (s.material[i] == 0) {
          EXPECT_LT(s.py[i], 1.0f) << "slot " << i << " left the floor";
        }
    }
  // The same review's known problem of the twenty-ninth session, the same cause: a box of
  // mass 1,000 sinking through syrup onto the floor (Damping 4, RelativeVelocity 10)
  // flung syrup out from frame 25 on, the total 57,430 -> 8 million by frame 192.
  BodyRun sink(scene::readSceneText(
      R"(<Scene version="1"><Environment><Width>8</Width><Height>20</Height><Depth>8</Depth></Environment>
         <Fluid><Name>syrup</Name><Viscosity>12</Viscosity>
         <Fill><Shape>box</Shape><Min>-4 0 -4</Min><Max>4 4 4</Max><Spacing>1</Spacing></Fill></Fluid>
         <Object><Name>box</Name><Shape>box</Shape><Size>2 1 2</Size><ParticleSize>0.25</ParticleSize>
         <InitialPosition>0 6 0</InitialPosition><Mass>1000</Mass></Object>
         <Interactions><FluidObject><Linear><AtZero>5</AtZero><Cutoff>1.5</Cutoff></Linear><Damping>4</Damping>
         <RelativeVelocity>10</RelativeVelocity></FluidObject></Interactions></Scene>)",
      "sink.scene"));
  const double start = solver::measureEnergy(sink.compiled.model, sink.sim->state()).total();
  EXPECT_LE(highestTotal(sink, 48), start * 1.001) << "start " << start;
}

// A run's first substep under velocity Verlet: its opening half kick follows no closing
// one, and the bodies' drag correction took the fluid's whole dt kick as given: a plate
// of mass 10 sliding at 4 units/s under a particle with Damping 100 was sent backwards
// at 10.8 units/s with it in the first frame (a black-box review, thirtieth session).
// Under every integrator the momentum stays 40 and both move on forward together.
TEST(BodyScenes, APlateDraggingAParticleKeepsItsMomentumFromTheFirstSubstep) {
  for (const char* integrator : {"symplectic-euler", "velocity-verlet", "explicit-euler"}) {
    SCOPED_TRACE(integrator);
    BodyRun run(scene::readSceneText(
        fmt::format(
            R"(<Scene version="1"><Simulation><Gravity>0 0 0</Gravity><Integrator>{}</Integrator></Simulation>
           <Fluid><Name>goo</Name><Viscosity>0</Viscosity><Particles>0 1.2 0</Particles></Fluid>
           <Object><Name>plate</Name><Shape>box</Shape><Size>4 1 4</Size><ParticleSize>0.25</ParticleSize>
           <InitialPosition>-1 0 0</InitialPosition><InitialLinearVelocity>4 0 0</InitialLinearVelocity><Mass>10</Mass></Object>
           <Interactions><FluidObject><Linear><AtZero>5</AtZero><Cutoff>1.5</Cutoff></Linear>
           <Damping>100</Damping><RelativeVelocity>0</RelativeVelocity></FluidObject></Interactions></Scene>)",
            integrator),
        "plate.scene"));
    for (int f = 0; f < 2; ++f) {
      run.sim->advanceFrame();
      const ParticleStore& s = run.sim->state().particles;
      std::size_t i = 0;
      while (s.material[i] != 0) ++i;
      const double plate = run.body(0).velocity.x(), particle = s.vx[i];
      EXPECT_NEAR(10 * plate + particle, 40.0, 0.05) << "frame " << f + 1;
      EXPECT_NEAR(plate, 40.0 / 11, 0.05) << "frame " << f + 1;
      EXPECT_NEAR(particle, 40.0 / 11, 0.2) << "frame " << f + 1;
    }
  }
}

// Velocity Verlet's closing half kick at a frame's end takes the fluid's drag near a
// body implicitly too, and the next frame's first substep takes that back out of its own
// correction. One substep a frame (at 192 frames a second: the same step as 8 at 24),
// so that every substep ends a frame: a particle falling at 80 units/s onto a fine
// static pallet with strong drag is written, at every frame's end, between its fall and
// a gentle rebound (the explicit closing kick wrote it thrown back up at hundreds of
// units/s; taking the closing kick implicitly without the next substep knowing blew the
// run up at 4,779 units/s). The same at 8 substeps a frame, and the run is the same
// whichever frame it is resumed at (the correction is worked out again from the state).
TEST(BodyScenes, VelocityVerletFrameVelocitiesUnderStrongDragDoNotOvershoot) {
  for (const int substeps : {1, 8}) {
    SCOPED_TRACE(substeps);
    BodyRun run(
        scene::readSceneText(fmt::format(
                                 R"(<Scene version="1"><Simulation><Integrator>velocity-verlet</Integrator>
               <FramesPerSecond>{}</FramesPerSecond><Substeps>{}</Substeps></Simulation><Environment/>
               <Fluid><Name>mud</Name><InitialSpeed>0 -80 0</InitialSpeed><Particles>0.1 3.2 0</Particles></Fluid>
               <Object><Name>pallet</Name><Shape>box</Shape><Size>8 0.5 4</Size><ParticleSize>0.25</ParticleSize>
               <InitialPosition>0 0.25 0</InitialPosition><IsDynamic>false</IsDynamic></Object>
               <Interactions><FluidObject><Linear><Cutoff>1.5</Cutoff></Linear><Damping>40</Damping>
               </FluidObject></Interactions></Scene>)",
                                 192 / substeps, substeps),
                             "fall.scene"));
    const ParticleStore& s = run.sim->state().particles;
    std::size_t i = 0;
    float highest = -100;
    for (int f = 0; f < 48 / substeps; ++f) {
      run.sim->advanceFrame();
      while (s.material[i] != 0) i = (i + 1) % s.size();  // the store may be re-sorted
      highest = std::max(highest, s.vy[i]);
      EXPECT_GE(s.vy[i], -80.5f) << "frame " << f + 1;
      EXPECT_LE(s.vy[i], 5.0f) << "frame " << f + 1 << ": written as thrown back";
    }
    EXPECT_GT(highest, -10.0f) << "it was stopped";
  }
}

// Fluid squeezed between a heavy box and the floor is put out of the box after the
// container's walls have acted, so the walls cannot put it back up into the box: three
// particles on the floor under a box of mass 2,000 landing at 20 units/s. With the walls
// last, all three ended the first frame 0.3 inside the box (and a review's puddle kept 17
// particles in the box's hollow middle, against 9 before the walls moved).
TEST(BodyScenes, FluidSqueezedUnderAHeavyBoxStaysOutOfIt) {
  BodyRun run(scene::readSceneText(
      R"(<Scene version="1"><Environment><Width>10</Width><Height>10</Height><Depth>10</Depth></Environment>
         <Fluid><Name>goo</Name><ParticleSize>0.5</ParticleSize><InteractionDistance>0.75</InteractionDistance>
         <FiniteDistance>0.5</FiniteDistance><Particles>0.1 0.25 0.1  -0.6 0.25 0.3  0.5 0.25 -0.4</Particles></Fluid>
         <Object><Name>box</Name><Shape>box</Shape><Size>3 2 3</Size><ParticleSize>0.25</ParticleSize>
         <InitialPosition>0 2 0</InitialPosition><InitialLinearVelocity>0 -20 0</InitialLinearVelocity><Mass>2000</Mass></Object>
         <Interactions><FluidObject><Linear><AtZero>5</AtZero><Cutoff>0.75</Cutoff></Linear></FluidObject></Interactions>
         </Scene>)",
      "squeeze.scene"));
  for (int f = 0; f < 12; ++f) {
    run.sim->advanceFrame();
    const ParticleStore& s = run.sim->state().particles;
    const rigid::BodyState& box = run.body(0);
    for (std::size_t i = 0; i < s.size(); ++i) {
      if (s.material[i] != 0) continue;
      const Vec3 local = box.orientation.conjugate() * (Vec3(s.px[i], s.py[i], s.pz[i]) - box.position);
      const double depth =
          std::min({1.5 - std::abs(local.x()), 1.0 - std::abs(local.y()), 1.5 - std::abs(local.z())});
      EXPECT_LT(depth, 0.1) << "frame " << f + 1 << ": slot " << i << " inside the box at "
                            << local.transpose();
    }
  }
}

// A crate resting on a plank two of its particles thick, whose particles are 3.3 times
// finer: the crate's bottom particles reach the plank's bottom layer too (face contacts
// reach 1.5 radii beside the normal), whose face pointed down and pushed them into the
// plank: the crate moved 0.36 and tilted 9 degrees in the first frame and left a static
// shelf within 2 s, and on a dynamic plank the total rose 14 -> 23 (a review,
// twenty-eighth session). A face holds a contact only with a particle at most two
// particles' touching distance behind it.
TEST(BodyScenes, ACrateRestsOnAPlankTwoParticlesThick) {
  for (const bool shelf : {true, false}) {
    SCOPED_TRACE(shelf ? "static shelf" : "dynamic plank on the floor");
    scene::SceneDesc d = floorScene(0.5, 0.5);
    const double top = shelf ? 3.3 : 0.3;
    scene::ObjectDesc plank =
        primitiveObject("plank", ObjectShape::Box, {6, 0.3, 4}, 0.15, Vec3(0, top - 0.15, 0));
    plank.isDynamic = !shelf;
    scene::ObjectDesc crate =
        primitiveObject("crate", ObjectShape::Box, {2, 2, 2}, 0.5, Vec3(0.7, top + 1, 0));
    d.objects = {plank, crate};
    BodyRun run(d);
    const double start = solver::measureEnergy(run.compiled.model, run.sim->state()).total();
    const std::vector<rigid::BodyState> begin = run.sim->state().bodies;
    double most = start;
    for (int f = 0; f < 48; ++f) {
      run.sim->advanceFrame();
      most = std::max(most, solver::measureEnergy(run.compiled.model, run.sim->state()).total());
    }
    const Still s = stillness(run, begin);
    EXPECT_LT(s.moved, 0.01);
    EXPECT_LT(s.turned, 0.005);
    EXPECT_LE(most, start + 1e-6 * std::abs(start));
  }
}

// A box thrown straight down onto a static plank two of its particles thick (no
// gravity) bounces straight back with the restitution, at 40 to 80 units/s (it moves
// 0.7 to 1.4 times the plank's thickness a substep): the plank's bottom face holds no
// particle that did not come through it. It stuck to the plank and slid off before the
// twenty-eighth session, and spun away sideways under the first form of the rule (a
// turn of up to about a degree is left).
TEST(BodyScenes, AThrownBoxBouncesStraightOffAPlankTwoParticlesThick) {
  for (const double speed : {40.0, 60.0, 80.0}) {
    for (const double offset : {0.0, 0.41}) {
      scene::SceneDesc d = floorScene(0.5, 0.1);
      d.simulation.gravity = Vec3::Zero();
      d.environment->width = d.environment->depth = 30;
      d.environment->height = 40;
      scene::ObjectDesc plank = primitiveObject("plank", ObjectShape::Box, {8, 0.3, 8}, 0.15, Vec3(0, 10, 0));
      plank.isDynamic = false;
      scene::ObjectDesc box = primitiveObject("box", ObjectShape::Box, {2, 2, 2}, 0.5, Vec3(offset, 14, 0));
      box.initialLinearVelocity = Vec3(0, -speed, 0);
      d.objects = {plank, box};
      BodyRun run(d);
      for (int f = 0; f < 12; ++f) run.sim->advanceFrame();
      const Vec3 v = run.body(1).velocity;
      SCOPED_TRACE(
          fmt::format("thrown at {} with offset {}: leaves at {} {} {}", speed, offset, v.x(), v.y(), v.z()));
      EXPECT_NEAR(v.y(), 0.5 * speed, 0.05 * 0.5 * speed);
      EXPECT_LT(std::hypot(v.x(), v.z()), 0.01 * speed);
      EXPECT_LT(Eigen::AngleAxisd(run.body(1).orientation).angle(), 0.05);
    }
  }
}

}  // namespace
}  // namespace softsub::scenarios

namespace softsub::scenarios {
namespace {

// A box spinning freely (no gravity, no contact) about no principal axis keeps its
// kinetic energy and angular momentum. The turn once used the angular velocity at the
// start of each substep, and the energy grew 6.4% in 30 s at 8 substeps a frame; the
// turn is now rigid::turnFree's (Body.TurnFree... test it alone).
TEST(BodyScenes, AFreelySpinningBoxKeepsItsEnergyAndAngularMomentum) {
  scene::SceneDesc d;
  d.simulation.gravity = Vec3(0, 0, 0);
  scene::ObjectDesc o;
  o.name = "box";
  o.shape = ObjectShape::Box;
  o.size = {2, 1, 3};
  o.mass = 6;
  o.initialAngularVelocity = Vec3(90, 57.29578, 30);
  d.objects.push_back(o);
  BodyRun run(d);
  const double e0 = rigid::kineticEnergy(run.info(0), run.body(0));
  const Vec3 l0 = run.body(0).angularMomentum;
  for (int f = 0; f < 240; ++f) run.sim->advanceFrame();  // 10 s (the old turn: +2%)
  EXPECT_NEAR(rigid::kineticEnergy(run.info(0), run.body(0)), e0, 1e-5 * e0);
  EXPECT_TRUE(run.body(0).angularMomentum.isApprox(l0, 1e-12));
}

// A body thin along an axis has a principal moment of inertia near 0: a cylinder of
// radius 1e-30 had one of 5e-61, whose inverse overflowed the solver's floats and stopped
// the run at the first contact ("angular momentum is not finite"). Each moment is kept at
// least 1e-6 of the largest; a body within that bound keeps its inertia exactly.
TEST(BodyScenes, AThinBodysLeastMomentOfInertiaIsBoundedAndItRuns) {
  scene::SceneDesc d;
  d.environment = scene::EnvironmentDesc{};
  scene::ObjectDesc o;
  o.name = "rod";
  o.shape = ObjectShape::Cylinder;
  o.size = {1e-30, 4};
  o.mass = 2;
  o.initialPosition = Vec3(0, 3, 0);
  o.initialRotation = Vec3(0, 0, 30);
  d.objects.push_back(o);
  o.name = "thick";
  o.size = {0.5, 4};
  o.initialPosition = Vec3(3, 3, 0);
  d.objects.push_back(o);
  BodyRun run(d);
  const Mat3 rod = run.info(0).inverseInertia.inverse();
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(rod);
  const double perpendicular = 2.0 * 16.0 / 12.0;  // m (3 r^2 + h^2) / 12, r = 0
  EXPECT_NEAR(eig.eigenvalues().maxCoeff(), perpendicular, 1e-9 * perpendicular);
  EXPECT_NEAR(eig.eigenvalues().minCoeff(), 1e-6 * perpendicular, 1e-12 * perpendicular);
  EXPECT_TRUE(
      Mat3(run.info(1).inverseInertia.inverse()).isApprox(geometry::cylinderInertia(2, 0.5, 4), 1e-12));
  for (int f = 0; f < 24; ++f) run.sim->advanceFrame();  // falls, lands and topples: no blow-up
  EXPECT_TRUE(run.body(0).angularMomentum.allFinite());
  EXPECT_LT(run.body(0).position.y(), 3.0);
}

// A torus mesh object, scaled, turned and spinning: the body takes the mesh's exact mass
// properties, and at any frame the `.sim` transform (position of the mesh origin,
// rotation, scale) puts the mesh where the body's particles are.
TEST(BodyScenes, AMeshObjectsTransformPlacesItsMeshOnItsParticles) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("softsub_rigid_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const geometry::TriangleMesh torus = torusMesh(Vec3(0.5, 0.2, 0), 1.0, 0.35, 32, 16);
  std::string obj;
  for (const Vec3& v : torus.vertices) obj += "v " + std::to_string(v.x()) + " " + std::to_string(v.y()) + " " + std::to_string(v.z()) + "\n";
  for (const auto& t : torus.triangles) obj += "f " + std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + " " + std::to_string(t[2] + 1) + "\n";
  writeTextFile(dir / "torus.obj", obj);

  scene::SceneDesc d;
  d.baseDir = dir.string();
  d.simulation.gravity = Vec3(0, -2, 0);
  scene::ObjectDesc o;
  o.name = "ring";
  o.geometry = "torus.obj";
  o.uniformScale = 2;
  o.particleSize = 0.2;
  o.mass = 3;
  o.initialPosition = Vec3(1, 5, -2);
  o.initialRotation = Vec3(30, 45, 10);
  o.initialAngularVelocity = Vec3(90, 30, 0);
  o.initialLinearVelocity = Vec3(1, 0, 0);
  d.objects.push_back(o);
  BodyRun run(d);
  const rigid::BodyInfo& info = run.info(0);
  const geometry::MassProperties exact =
      geometry::meshMassProperties(run.compiled.objectMeshes[0], 3.0);  // unscaled mesh, same mass
  // Scaling by 2 multiplies the inertia by 4.
  EXPECT_TRUE(Mat3(info.inverseInertia.inverse()).isApprox(4 * exact.inertia, 1e-3));
  EXPECT_TRUE((-info.originInBody).isApprox(2 * exact.centerOfMass, 1e-3));
  EXPECT_GT(info.count, 100U);

  for (int f = 0; f < 12; ++f) {
    run.sim->advanceFrame();
    const FrameSnapshot snap = run.sim->snapshot();
    const ObjectSnapshot& pose = snap.objects.at(0);
    const Quat q(pose.rotation[0], pose.rotation[1], pose.rotation[2], pose.rotation[3]);
    const Vec3 origin(pose.position[0], pose.position[1], pose.position[2]);
    // Every particle, taken back into mesh coordinates, lies within a particle of the
    // mesh's surface or inside it: within the torus tube of radius 0.35 + particle size.
    const ParticleStore& s = run.sim->state().particles;
    for (std::size_t i = 0; i < s.size(); ++i) {
      const Vec3 v = q.conjugate() * (Vec3(s.px[i], s.py[i], s.pz[i]) - origin) / pose.uniformScale;
      const Vec3 c = v - Vec3(0.5, 0.2, 0);
      const double ring = std::hypot(c.x(), c.z()) - 1.0;
      ASSERT_LT(std::hypot(ring, c.y()), 0.35 + 0.1 + 1e-3) << "frame " << f + 1 << " particle " << i;
    }
  }
  std::filesystem::remove_all(dir);
}

// Three boxes stacked on the floor, each shifted by a quarter particle on the one below,
// stand where they were put. Bodies made of particles have bumpy faces; with the
// contact normals along the lines between particle centres each box slid into the
// hollows of the one below in the first second or two (half a particle sideways, a
// seventh of a particle down). The faces' normals hold them flat where they are: under
// 1 cm in the first second and in the next three (a tilt creeps to 0.4 degrees in ten
// seconds and stays there, the top box about 1 mm a second at first).
TEST(BodyScenes, AStackOfThreeBoxesStandsWhereItWasPut) {
  scene::SceneDesc d = floorScene(0.3, 0.6);
  for (int k = 0; k < 3; ++k)
    d.objects.push_back(primitiveObject("box" + std::to_string(k), ObjectShape::Box, {1, 1, 1}, 0.2, Vec3(0.05 * k, 0, 0)));
  BodyRun probe(d);
  const double h = touchHeight(probe, 0);  // centre height of a box on the floor
  for (int k = 0; k < 3; ++k) d.objects[k].initialPosition.y() = h + 2 * h * k;
  BodyRun run(d);
  std::vector<Vec3> start, settled;
  for (int k = 0; k < 3; ++k) start.push_back(run.body(k).position);
  for (int f = 0; f < 24; ++f) run.sim->advanceFrame();
  for (int k = 0; k < 3; ++k) EXPECT_LT((run.body(k).position - start[k]).norm(), 0.01) << "box " << k;
  for (int f = 0; f < 24; ++f) run.sim->advanceFrame();
  for (int k = 0; k < 3; ++k) settled.push_back(run.body(k).position);
  for (int f = 0; f < 3 * 24; ++f) run.sim->advanceFrame();
  for (int k = 0; k < 3; ++k) {
    EXPECT_LT((run.body(k).position - settled[k]).norm(), 0.01) << "box " << k << " moved "
                                                                 << (run.body(k).position - settled[k]).transpose();
    EXPECT_LT(Eigen::AngleAxisd(run.body(k).orientation).angle(), 0.02) << "box " << k;
  }
}

// A 2 x 1 x 2 box (mass 5, particle size 0.5) dropped flat from `top` onto a box of
// size `base` and mass `baseMass` standing on the floor (friction 0.1): where the two are
// after `frames` frames, and how far the upper one turned (radians).
struct Drop {
  Vec3 base, top;
  double turn = 0;
};
Drop dropBoxOnBox(const std::vector<double>& base, double baseMass, const Vec3& top, int frames) {
  scene::SceneDesc d = floorScene(0.5, 0.1);
  d.simulation.frames = frames;
  scene::ObjectDesc lower = primitiveObject("base", ObjectShape::Box, base, 0.5, Vec3(0, 0.5 * base.at(1), 0));
  lower.mass = baseMass;
  scene::ObjectDesc upper = primitiveObject("top", ObjectShape::Box, {2, 1, 2}, 0.5, top);
  upper.mass = 5;
  d.objects = {lower, upper};
  BodyRun run(d);
  for (int f = 0; f < frames; ++f) run.sim->advanceFrame();
  return {run.body(0).position, run.body(1).position, Eigen::AngleAxisd(run.body(1).orientation).angle()};
}

// A box dropped flat onto a wider one lands with its lattice off the lower one's by
// whatever its position makes it. Each of its particles touches a face, so the contact
// normals are the face's whatever the offset: it stays where it landed, flat, at the
// height an aligned box rests at. (With the normals along the lines between particle
// centres, every one leant the same way, and at friction 0.1 the box slid 0.65 to 1.5
// units off its mark.)
TEST(BodyScenes, ABoxDroppedFlatOnABoxStaysWhereItLandsWhateverTheLatticeOffset) {
  const Drop aligned = dropBoxOnBox({4, 2, 4}, 40, Vec3(0, 4, 0), 72);
  EXPECT_LT(aligned.turn, 1e-4);
  for (const Vec3& offset : {Vec3(0.1, 0, 0), Vec3(0.3, 0, 0), Vec3(0.6, 0, 0.15)}) {
    const Drop drop = dropBoxOnBox({4, 2, 4}, 40, Vec3(0, 4, 0) + offset, 72);
    const Vec3& at = drop.top;
    EXPECT_LT((Vec3(at.x(), 0, at.z()) - offset).norm(), 0.005) << "offset " << offset.transpose() << ": at "
                                                                 << at.transpose();
    EXPECT_NEAR(at.y(), aligned.top.y(), 0.005) << "offset " << offset.transpose();
    EXPECT_LT(drop.turn, 0.002) << "offset " << offset.transpose();
  }
}

// Two boxes of one size: the upper one dropped flat from a unit above the lower one,
// a little off its centre. Their edges' particles lie under two faces each, and a box's
// bottom edge on the lower box's top edge touches face to face (the two faces that meet
// opposite), so the upper box lands flat and stays on: it moves less than a quarter of
// its width (0.02-0.3 in these drops; the bounce of the landing still nudges it). With
// the edges' particles touching along the lines between centres it walked off the lower
// box in four of these five drops, and with no face normals at all in five.
TEST(BodyScenes, ABoxDroppedOnABoxOfItsOwnSizeStaysOnIt) {
  for (const Vec3& offset : {Vec3(0.1, 0, 0), Vec3(0.05, 0, 0), Vec3(-0.15, 0, 0.1), Vec3(0.2, 0, 0.05),
                             Vec3(0.3, 0, 0.2)}) {
    const Drop drop = dropBoxOnBox({2, 1, 2}, 5, Vec3(0, 3, 0) + offset, 96);
    const Vec3 at = drop.top - drop.base;
    EXPECT_LT((Vec3(at.x(), 0, at.z()) - offset).norm(), 0.5) << "offset " << offset.transpose() << ": at "
                                                               << at.transpose();
    EXPECT_NEAR(at.y(), 1.0, 0.02) << "offset " << offset.transpose();  // resting on it
    EXPECT_LT(drop.turn, 0.035) << "offset " << offset.transpose();
  }
}

// A ball thrown straight down onto a thin static plate bounces straight up with the set
// restitution, at speeds where it moves 0.25 to 1.6 of its radius a substep: the plate's
// particles are one layer, under both of its faces, and the ball's particles meet the
// face they came from even when a substep takes them past the plate's middle. (With the
// centre lines, it came back at e = 0.58 to 0.60 with 5 to 20 units/s sideways.)
TEST(BodyScenes, ABallBouncesStraightOffAThinPlateWithItsRestitution) {
  for (const double speed : {50.0, 150.0, 300.0}) {
    scene::SceneDesc d = floorScene(0.5, 0.1);
    d.environment->height = 60;
    scene::ObjectDesc plate = primitiveObject("plate", ObjectShape::Box, {8, 0.2, 8}, 0.5, Vec3(0, 5, 0));
    plate.isDynamic = false;
    scene::ObjectDesc ball = primitiveObject("ball", ObjectShape::Sphere, {1}, 0.25, Vec3(0, 12, 0));
    ball.initialLinearVelocity = Vec3(0, -speed, 0);
    d.objects = {plate, ball};
    BodyRun run(d);
    bool bounced = false;
    // Up, and clear of the plate (its top at 5.1, the ball's radius 1 and a particle).
    for (int k = 0; k < 8 * 24 && !(bounced && run.body(1).position.y() > 6.4); ++k) {
      run.sim->step();
      bounced = bounced || run.body(1).velocity.y() > 0;
    }
    ASSERT_TRUE(bounced) << speed;
    const Vec3 v = run.body(1).velocity;
    EXPECT_NEAR(v.y(), 0.5 * speed, 0.03 * 0.5 * speed) << "thrown at " << speed;
    EXPECT_LT(std::hypot(v.x(), v.z()), 0.002 * speed) << "thrown at " << speed << ": " << v.transpose();
  }
}

// Bodies that hit the floor never leave with more energy than they had. Three scenes a
// review found gaining (each reproduced before the fix):
// - a thin rod (0.02 x 0.02 x 2, particles of 0.1) dropped with the default
//   attenuations: it spins about its axis, whose moment is 5000 times smaller than the
//   others', and the turn by the angular velocity fed energy in (29 -> 332 in 3 s);
// - a spinning cone with restitution 1 and friction 1 (192 -> 466), and a tumbling slab
//   with restitution 0.9 (99 -> 164): each contact's impact target is met on its own,
//   and together they gained (the energy check in RigidSolver).
// The total (kinetic, rotational and gravity's) is checked after every frame. What the
// overlap fix may add is left: it lifts a body that sank into the floor at impact, by
// less than a particle radius (the slab: +0.27 at its first impact, 0.2 of a radius).
TEST(BodyScenes, BodiesHittingTheFloorNeverGainEnergy) {
  const std::string scenes[] = {
      R"(<Object><Name>rod</Name><Shape>box</Shape><Size>0.02 0.02 2</Size><ParticleSize>0.1</ParticleSize>
         <InitialPosition>0 3 0</InitialPosition><InitialRotation>30 10 0</InitialRotation></Object>)",
      R"(<Object><Name>cone</Name><Shape>cone</Shape><Size>1.96 0.95</Size><ParticleSize>0.56</ParticleSize>
         <InitialPosition>0 5 0</InitialPosition><InitialRotation>17 78 84</InitialRotation>
         <InitialAngularVelocity>686 714 -553</InitialAngularVelocity>
         <InitialLinearVelocity>-0.55 -0.38 4.71</InitialLinearVelocity>
         <NormalAttenuation>1</NormalAttenuation><TangentAttenuation>1</TangentAttenuation></Object>)",
      R"(<Object><Name>slab</Name><Shape>box</Shape><Size>1.85 2.87 0.26</Size><ParticleSize>0.28</ParticleSize>
         <InitialPosition>0 5 0</InitialPosition><InitialRotation>80 58 38</InitialRotation>
         <InitialAngularVelocity>493 511 -65</InitialAngularVelocity>
         <InitialLinearVelocity>-3.2 -4 2.6</InitialLinearVelocity>
         <NormalAttenuation>0.9</NormalAttenuation><TangentAttenuation>0.5</TangentAttenuation></Object>)",
  };
  const std::string walls[] = {
      "", "<NormalAttenuation>1</NormalAttenuation><TangentAttenuation>1</TangentAttenuation>",
      "<NormalAttenuation>0.9</NormalAttenuation><TangentAttenuation>0.5</TangentAttenuation>"};
  for (std::size_t k = 0; k < std::size(scenes); ++k) {
    const scene::SceneDesc d = scene::readSceneText(
        "<Scene version=\"1\"><Environment>" + walls[k] + "</Environment>" + scenes[k] + "</Scene>",
        "impact.scene");
    BodyRun run(d);
    SCOPED_TRACE(d.objects.at(0).name);
    const double start = solver::measureEnergy(run.compiled.model, run.sim->state()).total();
    double most = start;
    int bounces = 0;
    bool falling = true;
    for (int f = 0; f < 72; ++f) {
      run.sim->advanceFrame();
      most = std::max(most, solver::measureEnergy(run.compiled.model, run.sim->state()).total());
      const bool nowFalling = run.body(0).velocity.y() < 0;
      bounces += falling && !nowFalling;
      falling = nowFalling;
    }
    EXPECT_GE(bounces, 1);  // it did hit the floor
    const double lift = run.info(0).mass * 9.81 * run.info(0).particleRadius;
    EXPECT_LE(most, start + lift) << "start " << start;
  }
}

// Restitution 1 and no friction keeps the energy: bodies bounce on for as long as the
// shot lasts, neither dying down nor gaining. Two spheres meeting head-on in free space
// leave with their speeds (the energy check once cut e = 1 to 31/32 for a gain of
// rounding's size: 6% a collision); a ball and a tumbling box bouncing on the floor
// for 20 s stay within 1.5% of their start (the box gained 21% in 34 s, the ball lost
// 6% a bounce, then gained 0.4 of its 49 a bounce: the substep's gravity was bounced
// back with the approach, and the overlap fix's lift added to the bounce).
TEST(BodyScenes, RestitutionOneWithoutFrictionKeepsTheEnergy) {
  const std::string elastic =
      "<NormalAttenuation>1</NormalAttenuation><TangentAttenuation>0</TangentAttenuation>";
  {
    const scene::SceneDesc d = scene::readSceneText(
        "<Scene version=\"1\"><Simulation><Gravity>0 0 0</Gravity></Simulation>"
        "<Object><Name>a</Name><Shape>sphere</Shape><Size>1</Size><InitialPosition>-4 5 0</InitialPosition>"
        "<InitialLinearVelocity>5 0 0</InitialLinearVelocity>" +
            elastic +
            "</Object>"
            "<Object><Name>b</Name><Shape>sphere</Shape><Size>1</Size><InitialPosition>4 5 "
            "0</InitialPosition>"
            "<InitialLinearVelocity>-5 0 0</InitialLinearVelocity>" +
            elastic + "</Object></Scene>",
        "spheres.scene");
    BodyRun run(d);
    for (int f = 0; f < 48; ++f) run.sim->advanceFrame();
    EXPECT_NEAR(run.body(0).velocity.x(), -5.0, 5e-5);  // the check settles within 1e-6 of the energy
    EXPECT_NEAR(run.body(1).velocity.x(), 5.0, 5e-5);
  }
  const std::string bodies[] = {
      "<Object><Name>ball</Name><Shape>sphere</Shape><Size>1</Size><InitialPosition>0 5 0</InitialPosition>" +
          elastic + "</Object>",
      "<Object><Name>box</Name><Shape>box</Shape><Size>2 1 1.5</Size><ParticleSize>0.2</ParticleSize>"
      "<InitialPosition>0 4 0</InitialPosition><InitialRotation>15 25 35</InitialRotation>" +
          elastic + "</Object>",
  };
  for (const std::string& body : bodies) {
    const scene::SceneDesc d = scene::readSceneText(
        "<Scene version=\"1\"><Environment>" + elastic + "</Environment>" + body + "</Scene>",
        "bounce.scene");
    BodyRun run(d);
    SCOPED_TRACE(d.objects.at(0).name);
    const double start = solver::measureEnergy(run.compiled.model, run.sim->state()).total();
    double most = start, least = start;
    for (int f = 0; f < 480; ++f) {
      run.sim->advanceFrame();
      const double e = solver::measureEnergy(run.compiled.model, run.sim->state()).total();
      most = std::max(most, e);
      least = std::min(least, e);
    }
    EXPECT_LE(most, 1.015 * start);
    EXPECT_GE(least, 0.985 * start);
  }
}

}  // namespace
}  // namespace softsub::scenarios
