// The warnings compile() gives about a scene's initial particles (a fluid's or an
// object's outside the container, a fluid particle exactly where another one is, a
// ParticleSize far from the spacing) and about default interactions at another scale.
// Only a scene that has them gets them.
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "scene/compile.h"
#include "scene/reader.h"
#include "scene_test_util.h"

namespace softsub::scene {
namespace {

using testing::sceneWith;

const std::string kBox = "<Environment><Width>10</Width><Height>10</Height><Depth>10</Depth></Environment>\n";

std::string fill(const std::string& min, const std::string& max) {
  return "<Fill><Shape>box</Shape><Min>" + min + "</Min><Max>" + max + "</Max><Spacing>1</Spacing></Fill>";
}

// The same as fill() with OutsideObjects.
std::string carvedFill(const std::string& min, const std::string& max) {
  return "<Fill><Shape>box</Shape><Min>" + min + "</Min><Max>" + max +
         "</Max><Spacing>1</Spacing><OutsideObjects>true</OutsideObjects></Fill>";
}

// A dynamic 4 x 4 x 4 box standing on the floor at the origin.
const std::string kCrate =
    "<Object><Name>crate</Name><Shape>box</Shape><Size>4 4 4</Size><InitialPosition>0 2 "
    "0</InitialPosition></Object>";

std::vector<std::string> warningsOf(const std::string& body) {
  return compile(readSceneText(sceneWith(body), "t.scene")).warnings;
}

TEST(CompileWarnings, NoneForParticlesApartAndInside) {
  EXPECT_TRUE(warningsOf(kBox + "<Fluid><Name>a</Name>" + fill("-2 0 -2", "2 2 2") + "</Fluid>").empty());
  // Without a container nothing is outside.
  EXPECT_TRUE(warningsOf("<Fluid><Name>a</Name>" + fill("20 0 0", "22 2 2") + "</Fluid>").empty());
}

TEST(CompileWarnings, CountsTheParticlesOfEachFluidOutsideTheContainer) {
  // Cell centres x = 3.5 .. 7.5 at spacing 1: 5.5, 6.5 and 7.5 lie beyond the wall at 5.
  const std::vector<std::string> w = warningsOf(kBox + "<Fluid><Name>in</Name>" + fill("-1 0 -1", "1 1 1") +
                                                "</Fluid><Fluid><Name>out</Name>" + fill("3 0 0", "8 1 1") + "</Fluid>");
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("Fluid 'out': 3 of 5 particles start outside the container"), std::string::npos) << w[0];
  EXPECT_NE(w[0].find("y [0, open top]"), std::string::npos) << w[0];
  // Above an open top is not outside; above a closed one is.
  EXPECT_TRUE(warningsOf(kBox + "<Fluid><Name>a</Name>" + fill("0 12 0", "1 15 1") + "</Fluid>").empty());
  const std::string closed =
      "<Environment><Width>10</Width><Height>10</Height><Depth>10</Depth><Closed>true</Closed></Environment>\n";
  const std::vector<std::string> lid = warningsOf(closed + "<Fluid><Name>a</Name>" + fill("0 8 0", "1 14 1") + "</Fluid>");
  ASSERT_EQ(lid.size(), 1u);  // y = 8.5 .. 13.5 under a lid at 10
  EXPECT_NE(lid[0].find("Fluid 'a': 4 of 6 particles start outside"), std::string::npos) << lid[0];
}

// "Object 'name': K of N particles ..." -> {K, N}; {-1, -1} when the line is not one.
std::pair<long, long> objectCounts(const std::string& line, const std::string& name) {
  const std::string head = "Object '" + name + "': ";
  if (line.rfind(head, 0) != 0) return {-1, -1};
  long k = -1, n = -1;
  if (std::sscanf(line.c_str() + head.size(), "%ld of %ld particles start outside the container", &k, &n) != 2)
    return {-1, -1};
  return {k, n};
}

std::string object(const std::string& name, const std::string& position, bool dynamic) {
  return "<Object><Name>" + name + "</Name><Shape>box</Shape><Size>2 2 2</Size><ParticleSize>0.5</ParticleSize>"
         "<InitialPosition>" + position + "</InitialPosition><IsDynamic>" + (dynamic ? "true" : "false") +
         "</IsDynamic></Object>";
}

// The walls keep a fluid's centres half its ParticleSize in: a fill flush with the walls
// at a spacing below the size starts its outer layers inside that margin, and the first
// substep moves them into their neighbours at once (a total energy of 976 became 31,392
// in a frame; a review). Counted apart from the particles outside the box, and only past
// a tenth of the size, so a fill at its own ParticleSize stays silent.
TEST(CompileWarnings, CountsTheParticlesThatStartWithinTheWallsMargin) {
  const std::string box6 = "<Environment><Width>6</Width><Height>6</Height><Depth>6</Depth></Environment>\n";
  const auto flush = [&](const std::string& size, const std::string& spacing) {
    return warningsOf(box6 + "<Fluid><Name>w</Name><ParticleSize>" + size +
                      "</ParticleSize><FiniteDistance>" + spacing +
                      "</FiniteDistance><InteractionDistance>1.5</InteractionDistance>" +
                      "<Fill><Shape>box</Shape><Min>-3 0 -3</Min><Max>3 3 3</Max><Spacing>" + spacing +
                      "</Spacing></Fill></Fluid>");
  };
  // Spacing 0.5 in a 6-wide box: 12 x 6 x 12 points, centres 0.25 from the walls; with
  // ParticleSize 1 the walls keep them 0.5 in. Every point of the outer shell (the open
  // top's layer excepted) is in the margin: 864 - 10 x 5 x 10 = 364.
  const std::vector<std::string> w = flush("1", "0.5");
  ASSERT_EQ(w.size(), 1u) << fmt::format("{}", fmt::join(w, "\n"));
  EXPECT_NE(w[0].find("Fluid 'w': 364 of 864 particles start nearer the container's walls than half their "
                      "ParticleSize 1"),
            std::string::npos)
      << w[0];
  EXPECT_NE(w[0].find("(by up to 0.25)"), std::string::npos) << w[0];
  // At its own ParticleSize, or a little above it, the fill is where the walls keep it.
  EXPECT_TRUE(flush("0.5", "0.5").empty());
  EXPECT_TRUE(flush("0.55", "0.5").empty());
  // Moved half a ParticleSize in, the same fill is calm and unwarned.
  EXPECT_TRUE(
      warningsOf(box6 + "<Fluid><Name>w</Name><FiniteDistance>0.5</FiniteDistance>"
                        "<InteractionDistance>1.5</InteractionDistance><Fill><Shape>box</Shape>"
                        "<Min>-2.5 0.5 -2.5</Min><Max>2.5 3.5 2.5</Max><Spacing>0.5</Spacing></Fill></Fluid>")
          .empty());
}

// A fluid whose own force is zero at or past its cutoff only pushes: a ball with
// FiniteDistance 2 and the default InteractionDistance 1.5 flew apart without a word (a
// review). Not when a <Pair> of the fluid with itself replaces that function.
TEST(CompileWarnings, NamesAFiniteDistanceNotBelowTheInteractionDistance) {
  const auto ball = [](const std::string& params, const std::string& pairs) {
    return warningsOf(
        "<Fluid><Name>a</Name>" + params +
        "<Fill><Shape>sphere</Shape><Center>0 3 0</Center><Radius>2</Radius><Spacing>2</Spacing>"
        "</Fill></Fluid>" +
        pairs);
  };
  const std::vector<std::string> w = ball("<FiniteDistance>2</FiniteDistance>", "");
  ASSERT_EQ(w.size(), 1u) << fmt::format("{}", fmt::join(w, "\n"));
  EXPECT_NE(w[0].find("Fluid 'a' (line "), std::string::npos) << w[0];
  EXPECT_NE(w[0].find("FiniteDistance 2 is not below InteractionDistance 1.5"), std::string::npos) << w[0];
  EXPECT_NE(w[0].find("(3)"), std::string::npos) << w[0];
  EXPECT_EQ(ball("<FiniteDistance>1.5</FiniteDistance>", "").size(), 1u);  // equal: no attraction either
  EXPECT_TRUE(
      ball("<FiniteDistance>2</FiniteDistance><InteractionDistance>3</InteractionDistance>", "").empty());
  // A Pair replacing the function: no word of FiniteDistance (the Pair only pushes, so
  // its fill, 2 apart, is told it swells to its cutoff 3).
  const std::vector<std::string> paired =
      ball("<FiniteDistance>2</FiniteDistance>",
           "<Interactions><Pair><A>a</A><B>a</B><Linear><AtZero>5</AtZero><Cutoff>3</Cutoff><Min>0</Min>"
           "<Max>5</Max></Linear></Pair></Interactions>");
  ASSERT_EQ(paired.size(), 1u) << fmt::format("{}", fmt::join(paired, "\n"));
  EXPECT_EQ(paired[0].find("FiniteDistance 2"), std::string::npos) << paired[0];
  EXPECT_NE(paired[0].find("its own <Pair> (line 2) holds such a lattice at rest about 3 apart"),
            std::string::npos)
      << paired[0];
}

TEST(CompileWarnings, CountsTheParticlesOfEachObjectOutsideTheContainer) {
  // The container spans x [-5, 5]: a body centred inside has none outside, one centred
  // on the wall about half, one beyond it all; a static one is told it stays there.
  EXPECT_TRUE(warningsOf(kBox + object("inside", "0 3 0", true)).empty());
  const std::vector<std::string> w = warningsOf(kBox + object("half", "5 3 0", true) + object("beyond", "9 3 0", true) +
                                                object("fixed", "0 3 -5", false));
  ASSERT_EQ(w.size(), 3u);
  const auto half = objectCounts(w[0], "half");
  EXPECT_GT(half.first, 0) << w[0];
  EXPECT_LT(half.first, half.second) << w[0];
  EXPECT_GE(2 * half.first, half.second * 3 / 10) << "about half of the body: " << w[0];
  EXPECT_LE(2 * half.first, half.second * 17 / 10) << "about half of the body: " << w[0];
  EXPECT_NE(w[0].find("push the body back inside"), std::string::npos) << w[0];
  const auto beyond = objectCounts(w[1], "beyond");
  EXPECT_GT(beyond.first, 0) << w[1];
  EXPECT_EQ(beyond.first, beyond.second) << "all of it: " << w[1];
  EXPECT_EQ(beyond.second, half.second) << "the same body";
  const auto fixed = objectCounts(w[2], "fixed");
  EXPECT_GT(fixed.first, 0) << w[2];
  EXPECT_NE(w[2].find("a static body never moves"), std::string::npos) << w[2];
  // Without a container nothing is outside.
  EXPECT_TRUE(warningsOf(object("far", "100 3 0", true)).empty());
  // A body wider than the container (a mesh in other units) cannot be put back by the
  // walls: said so, with its width; one just inside its width is told the usual.
  const auto wide = [](double x) {
    return fmt::format(
        "<Object><Name>slab</Name><Shape>box</Shape><Size>{} 1 2</Size><ParticleSize>0.5</ParticleSize>"
        "<InitialPosition>0 3 0</InitialPosition></Object>",
        x);
  };
  const std::vector<std::string> big = warningsOf(kBox + wide(12));
  ASSERT_EQ(big.size(), 1u);
  EXPECT_NE(big[0].find("Object 'slab': its particles span 12 in x, more than the container's 10; the walls "
                        "push it in with a jolt"),
            std::string::npos)
      << big[0];
  // Wider by less than a particle: all its particles' centres inside, their surfaces not
  // (a review: no warning up to 10.5 wide in 10, and the box climbed and tilted).
  const std::vector<std::string> bit = warningsOf(kBox + wide(10.4));
  ASSERT_EQ(bit.size(), 1u);
  EXPECT_NE(bit[0].find("Object 'slab': its particles span 10.5 in x, more than the container's 10"),
            std::string::npos)
      << bit[0];
  const std::vector<std::string> fits = warningsOf(kBox + wide(9.5) + object("beyond", "9 3 0", true));
  ASSERT_EQ(fits.size(), 1u) << fmt::format("{}", fmt::join(fits, "\n"));
  EXPECT_NE(fits[0].find("push the body back inside"), std::string::npos) << fits[0];
}

// A cutoff so long that the table's capped pieces no longer follow the function's shape
// is named with how far the force strays; 500 times the length scale is not (a review:
// InteractionDistance 1e6 made a fluid repel everywhere).
TEST(CompileWarnings, NamesAFunctionTooLongForItsTable) {
  const auto scene = [](const char* distance) {
    return std::string("<Fluid><Name>goo</Name><InteractionDistance>") + distance + "</InteractionDistance>" +
           fill("-2 1 -2", "2 5 2") + "</Fluid>";
  };
  EXPECT_TRUE(warningsOf(scene("500")).empty());
  const std::vector<std::string> w = warningsOf(scene("1e6"));
  ASSERT_EQ(w.size(), 1u) << fmt::format("{}", fmt::join(w, "\n"));
  EXPECT_NE(w[0].find("Fluid 'goo': its own function reaches 1e+06, 1e+06 times its length scale 1"),
            std::string::npos)
      << w[0];
  EXPECT_NE(w[0].find("the force table's 262144 pieces are 3.81 long"), std::string::npos) << w[0];
  // A <Pair> with an object names the object (it said "the objects").
  const std::vector<std::string> pair =
      warningsOf("<Fluid><Name>goo</Name>" + fill("-2 1 -2", "2 5 2") +
                 "</Fluid><Object><Name>post</Name><Shape>box</Shape><Size>1 1 1</Size><InitialPosition>0 8 "
                 "0</InitialPosition>"
                 "</Object><Interactions><Pair><A>goo</A><B>post</B><LennardJones><Cutoff>1e6</Cutoff></"
                 "LennardJones></Pair>"
                 "</Interactions>");
  ASSERT_EQ(pair.size(), 1u) << fmt::format("{}", fmt::join(pair, "\n"));
  EXPECT_NE(pair[0].find("Interactions: the function between fluid 'goo' and object 'post' reaches 1e+06"),
            std::string::npos)
      << pair[0];
}

// Fluid/object drag past what single-precision forces can balance is named; strong but
// sane drag is not.
TEST(CompileWarnings, NamesAFluidObjectDragPastWhatFloatsCanBalance) {
  const auto scene = [](const char* damping) {
    return std::string(
               "<Fluid><Name>goo</Name><Particles>0 1.2 0</Particles></Fluid>"
               "<Object><Name>plate</Name><Shape>box</Shape><Size>4 1 4</Size></Object>"
               "<Interactions><FluidObject><Linear><Cutoff>1.5</Cutoff></Linear><Damping>") +
           damping + "</Damping></FluidObject></Interactions>";
  };
  EXPECT_TRUE(warningsOf(scene("1e5")).empty());
  // A light dynamic body decides as a light particle would (a review: a plate of mass 0.01
  // under a particle of mass 1, Damping 1e5, gained 54% momentum without a word).
  const std::string light = std::string(
      "<Fluid><Name>goo</Name><Particles>0 1.2 0</Particles></Fluid>"
      "<Object><Name>plate</Name><Shape>box</Shape><Size>4 1 4</Size><Mass>0.01</Mass>"
      "</Object><Interactions><FluidObject><Linear><Cutoff>1.5</Cutoff></Linear>"
      "<Damping>1e5</Damping></FluidObject></Interactions>");
  const std::vector<std::string> lw = warningsOf(light);
  ASSERT_EQ(lw.size(), 1u);
  EXPECT_NE(lw[0].find("the lighter mass 0.01) is 5.21e+04 times"), std::string::npos) << lw[0];
  const std::vector<std::string> w = warningsOf(scene("1e8"));
  ASSERT_EQ(w.size(), 1u) << fmt::format("{}", fmt::join(w, "\n"));
  EXPECT_NE(
      w[0].find(
          "the fluid/object drag between fluid 'goo' and object 'plate' (Damping 1e+08, RelativeVelocity 2; "
          "the lighter mass 1) is 5.21e+05 times what one substep"),
      std::string::npos)
      << w[0];
}

// Velocities given to a static object would be dropped without a word: each such object
// is named with its line and what is not used; a dynamic one, or a static one at rest,
// is not.
TEST(CompileWarnings, NamesTheVelocitiesOfAStaticObject) {
  const std::string body =
      "<Object><Name>belt</Name><Shape>box</Shape><Size>4 1 4</Size><IsDynamic>false</IsDynamic>"
      "<InitialLinearVelocity>5 0 0</InitialLinearVelocity></Object>\n"
      "<Object><Name>wheel</Name><Shape>sphere</Shape><Size>1</Size><InitialPosition>9 0 0</InitialPosition>"
      "<IsDynamic>false</IsDynamic><InitialAngularVelocity>0 90 0</InitialAngularVelocity></Object>\n"
      "<Object><Name>ball</Name><Shape>sphere</Shape><Size>1</Size><InitialPosition>-9 0 0</InitialPosition>"
      "<InitialLinearVelocity>5 0 0</InitialLinearVelocity></Object>\n"
      "<Object><Name>post</Name><Shape>box</Shape><Size>1 1 1</Size><InitialPosition>0 0 9</InitialPosition>"
      "<IsDynamic>false</IsDynamic></Object>";
  const std::vector<std::string> w = warningsOf(body);
  ASSERT_EQ(w.size(), 2u) << fmt::format("{}", fmt::join(w, "\n"));
  EXPECT_NE(
      w[0].find("Object 'belt' (line 2) is static (IsDynamic false): its InitialLinearVelocity is not used"),
      std::string::npos)
      << w[0];
  EXPECT_NE(
      w[1].find(
          "Object 'wheel' (line 3) is static (IsDynamic false): its InitialAngularVelocity is not used"),
      std::string::npos)
      << w[1];
}

// Fluid placed inside a closed object stays there (a body keeps only its two outer
// layers of particles): each fluid with particles inside each object is counted, at the
// object's initial pose (turned, placed), with the object's line; fluid beside it or in
// an open mesh's shell (no inside) is not.
TEST(CompileWarnings, CountsTheFluidParticlesThatStartInsideAnObject) {
  // A 3 x 3 x 3 box at (0.25, 2.25, 0.1) in a fill whose particles sit at the cell
  // centres -3.5 .. 3.5 (x, z) and 0.5 .. 3.5 (y), at rest and turned 30 and 45 degrees about y;
  // a second fluid far away. No particle lies on a face, so inside is not a matter of
  // rounding: the count is checked against a brute-force test in the box's own axes.
  const std::string fluids = "<Fluid><Name>goo</Name>" + fill("-4 0 -4", "4 4 4") +
                             "</Fluid>\n<Fluid><Name>far</Name>" + fill("20 0 20", "21 1 21") + "</Fluid>\n";
  const Vec3 centre(0.25, 2.25, 0.1);
  for (const double turn : {0.0, 30.0, 45.0}) {
    SCOPED_TRACE(turn);
    const std::vector<std::string> w = warningsOf(
        fluids + fmt::format("<Object><Name>crate</Name><Shape>box</Shape><Size>3 3 3</Size>"
                             "<ParticleSize>0.5</ParticleSize><InitialPosition>{} {} {}</InitialPosition>"
                             "<InitialRotation>0 {} 0</InitialRotation></Object>",
                             centre.x(), centre.y(), centre.z(), turn));
    int inside = 0;
    const double c = std::cos(turn * std::numbers::pi / 180), s = std::sin(turn * std::numbers::pi / 180);
    for (double x = -3.5; x < 4; ++x)
      for (double y = 0.5; y < 4; ++y)
        for (double z = -3.5; z < 4; ++z) {
          const Vec3 d = Vec3(x, y, z) - centre;
          const Vec3 own(c * d.x() - s * d.z(), d.y(), s * d.x() + c * d.z());  // turned back about y
          ASSERT_GT(std::abs(own.cwiseAbs().maxCoeff() - 1.5), 1e-3) << "a particle on a face";
          if (own.cwiseAbs().maxCoeff() < 1.5) ++inside;
        }
    ASSERT_GT(inside, 0);
    ASSERT_EQ(w.size(), 1u) << fmt::format("{}", fmt::join(w, "\n"));
    EXPECT_NE(w[0].find(fmt::format("Object 'crate' (line 4): {} particle(s) of fluid 'goo' start inside it",
                                    inside)),
              std::string::npos)
        << w[0];
  }
  // Beside the box, or with an open mesh object (a surface of particles, no inside): none.
  EXPECT_TRUE(warningsOf(fluids + "<Object><Name>crate</Name><Shape>box</Shape><Size>3 3 3</Size>"
                                  "<InitialPosition>0 8 0</InitialPosition></Object>")
                  .empty());
}

// A fill with OutsideObjects leaves out its points inside closed objects, or overlapping
// an object's particles, at the objects' initial poses: the same box as above, turned 0,
// 30 and 45 degrees, and a second object (a ball) in the same fill; the fluid's particles
// of radius 0.2. Each point is checked against brute force: inside the crate (in its own
// axes; its voxels match it, as 3 is a whole number of its particles, and no point lies
// within 1e-3 of a face), inside the ball (no point within 0.3 of its surface, farther
// than its voxels reach past it), or closer to one of the two objects' particles than
// the two radii (every particle, from the compiled model). The rest of the fluid
// (explicit positions, a fill without the tag) keeps every point, and only what it keeps
// inside the crate is said to start inside it.
TEST(CompileFills, OutsideObjectsLeavesOutThePointsInsideObjects) {
  const Vec3 centre(0.25, 2.25, 0.1), ball(-2, 2, 2);
  const double radius = 1.3, fluidRadius = 0.2;
  for (const double turn : {0.0, 30.0, 45.0}) {
    SCOPED_TRACE(turn);
    const std::string text = sceneWith(
        "<Fluid><Name>goo</Name><ParticleSize>0.4</ParticleSize><Particles>0.25 2.25 0.1</Particles>" +
        carvedFill("-4 0 -4", "4 4 4") + fill("-1 1 -1", "1 3 1") + "</Fluid>\n" +
        fmt::format(
            "<Object><Name>crate</Name><Shape>box</Shape><Size>3 3 3</Size>"
            "<ParticleSize>0.5</ParticleSize><InitialPosition>{} {} {}</InitialPosition>"
            "<InitialRotation>0 {} 0</InitialRotation></Object>\n"
            "<Object><Name>ball</Name><Shape>sphere</Shape><Size>{}</Size><ParticleSize>0.25</ParticleSize>"
            "<InitialPosition>{} {} {}</InitialPosition><IsDynamic>false</IsDynamic></Object>",
            centre.x(), centre.y(), centre.z(), turn, radius, ball.x(), ball.y(), ball.z()));
    const Compiled c = compile(readSceneText(text, "t.scene"));
    const double co = std::cos(turn * std::numbers::pi / 180), si = std::sin(turn * std::numbers::pi / 180);
    const auto inCrate = [&](const Vec3& p) {
      const Vec3 d = p - centre;
      const Vec3 own(co * d.x() - si * d.z(), d.y(), si * d.x() + co * d.z());  // turned back about y
      EXPECT_GT(std::abs(own.cwiseAbs().maxCoeff() - 1.5), 1e-3) << "a point on a face";
      return own.cwiseAbs().maxCoeff() < 1.5;
    };
    const auto inBall = [&](const Vec3& p) {
      EXPECT_GT(std::abs((p - ball).norm() - radius), 0.3) << "a point near the sphere";
      return (p - ball).norm() < radius;
    };
    // The objects' particles where the compiled model puts them.
    std::vector<std::pair<Vec3, double>> bodyParticles;
    const rigid::BodySet& set = c.model.bodies;
    for (std::size_t b = 0; b < set.bodies.size(); ++b) {
      const rigid::BodyInfo& info = set.bodies[b];
      const rigid::BodyState& pose = c.state.bodies[b];
      for (std::uint32_t k = info.firstId - set.firstId; k < info.firstId - set.firstId + info.count; ++k)
        bodyParticles.emplace_back(pose.position + pose.orientation * Vec3(set.ox[k], set.oy[k], set.oz[k]),
                                   info.particleRadius);
    }
    const auto overlaps = [&](const Vec3& p) {
      bool any = false;
      for (const auto& [q, r] : bodyParticles) {
        const double gap = (q - p).norm() - (fluidRadius + r);
        EXPECT_GT(std::abs(gap), 1e-4) << "a point just touching a particle";
        any = any || gap < 0;
      }
      return any;
    };
    std::vector<Vec3> expected = {centre};  // the explicit position, inside the crate, kept
    int dropped = 0, byOverlapOnly = 0;
    for (double z = -3.5; z < 4; ++z)
      for (double y = 0.5; y < 4; ++y)
        for (double x = -3.5; x < 4; ++x) {
          const bool in = inCrate({x, y, z}) || inBall({x, y, z}), near = overlaps({x, y, z});
          if (in || near) ++dropped;
          else expected.emplace_back(x, y, z);
          if (near && !in) ++byOverlapOnly;
        }
    for (double z = -0.5; z < 1; ++z)
      for (double y = 1.5; y < 3; ++y)
        for (double x = -0.5; x < 1; ++x) expected.emplace_back(x, y, z);  // the plain fill, kept
    ASSERT_GT(dropped, 27);
    const ParticleStore& s = c.state.particles;
    ASSERT_EQ(c.model.fluids.at(0).count, expected.size()) << byOverlapOnly << " dropped for overlap alone";
    EXPECT_EQ(c.leftOutInsideObjects, std::vector<std::size_t>{static_cast<std::size_t>(dropped)});
    for (std::size_t i = 0; i < expected.size(); ++i)
      ASSERT_EQ(Vec3(s.px[i], s.py[i], s.pz[i]), expected[i].cast<float>().cast<double>()) << i;
    // The points kept inside the crate, the explicit one and the plain fill's, are the only
    // fluid said to start inside an object.
    const auto keptInCrate = std::count_if(expected.begin(), expected.end(), inCrate);
    ASSERT_EQ(keptInCrate, 9);
    ASSERT_EQ(c.warnings.size(), 1u) << fmt::format("{}", fmt::join(c.warnings, "\n"));
    EXPECT_NE(c.warnings[0].find("Object 'crate' (line 3): 9 particle(s) of fluid 'goo' start inside it"),
              std::string::npos)
        << c.warnings[0];
  }
}

// A box whose size is not a whole number of its particles (2.7 at 0.5): its lattice of
// 5 a side is centred in the box, its particles' outer surfaces at +-1.25, and the fill
// is left out where those particles are, on both sides alike (tested from the mesh's
// corner, points 0.2 inside the high side's particles were kept and then called inside
// it: a review). No kept point lies within the particles' extent, and none is said to
// start inside the box.
TEST(CompileFills, OutsideObjectsFollowsALatticeCentredInItsBox) {
  const Compiled c = compile(readSceneText(
      sceneWith(
          "<Fluid><Name>w</Name><ParticleSize>0.1</ParticleSize><Fill><Shape>box</Shape><Min>-2 -2 "
          "-0.05</Min>"
          "<Max>2 2 0.05</Max><Spacing>0.1</Spacing><OutsideObjects>true</OutsideObjects></Fill></Fluid>"
          "<Object><Name>b</Name><Shape>box</Shape><Size>2.7 2.7 2.7</Size><ParticleSize>0.5</ParticleSize>"
          "<IsDynamic>false</IsDynamic></Object>"),
      "t.scene"));
  const ParticleStore& s = c.state.particles;
  double low = -10, high = 10;  // the nearest kept points on the x axis, either side
  for (std::size_t i = 0; i < c.model.fluids[0].count; ++i) {
    const Vec3 p(s.px[i], s.py[i], s.pz[i]);
    EXPECT_GE(p.cwiseAbs().head<2>().maxCoeff(), 1.25 - 1e-5)
        << "kept within the particles: " << p.transpose();
    if (std::abs(p.y()) < 0.06) {
      if (p.x() < 0) low = std::max(low, p.x());
      else high = std::min(high, p.x());
    }
  }
  EXPECT_NEAR(low, -high, 1e-5) << "the same margin on both sides";
  for (const std::string& w : c.warnings) EXPECT_EQ(w.find("start inside it"), std::string::npos) << w;
}

// The "start inside it" advice fits where the particles came from: a fill without
// OutsideObjects is told to use it; explicit positions alone (every fill carved) are told
// they are never left out.
TEST(CompileFills, TheStartInsideAdviceFitsTheParticlesSource) {
  const std::string carved = carvedFill("-3 0 -3", "3 1 3");
  const auto insideWarnings = [](const std::vector<std::string>& all) {
    std::vector<std::string> out;
    for (const std::string& w : all)
      if (w.find("start inside it") != std::string::npos) out.push_back(w);
    return out;
  };
  const std::vector<std::string> explicitOnly = insideWarnings(
      warningsOf("<Fluid><Name>goo</Name><Particles>0 2 0</Particles>" + carved + "</Fluid>\n" + kCrate));
  ASSERT_EQ(explicitOnly.size(), 1u) << fmt::format("{}", fmt::join(explicitOnly, "\n"));
  EXPECT_NE(explicitOnly[0].find("they are explicit positions, which are never left out"), std::string::npos)
      << explicitOnly[0];
  const std::vector<std::string> plain = insideWarnings(
      warningsOf("<Fluid><Name>goo</Name>" + fill("-1 1 -1", "1 3 1") + carved + "</Fluid>\n" + kCrate));
  ASSERT_EQ(plain.size(), 1u) << fmt::format("{}", fmt::join(plain, "\n"));
  EXPECT_NE(plain[0].find("give the fluid's fills <OutsideObjects>true</OutsideObjects>"), std::string::npos)
      << plain[0];
}

// A fill whose every point lies inside an object adds nothing: a warning names it, and a
// fluid left with no particle at all is an error at its line.
TEST(CompileFills, AFillLeftEmptyByOutsideObjectsIsNamed) {
  const std::string crate = kCrate;
  const std::string inner = carvedFill("-1 1 -1", "1 3 1");
  const std::vector<std::string> w =
      warningsOf("<Fluid><Name>goo</Name>" + fill("6 0 6", "7 1 7") + inner + "</Fluid>\n" + crate);
  ASSERT_EQ(w.size(), 1u) << fmt::format("{}", fmt::join(w, "\n"));
  EXPECT_NE(w[0].find("Fluid 'goo'/Fill[2] (line 2): all 8 of its points lie inside objects"),
            std::string::npos)
      << w[0];
  try {
    (void)compile(
        readSceneText(sceneWith("<Fluid><Name>goo</Name>" + inner + "</Fluid>\n" + crate), "t.scene"));
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("t.scene:2: Fluid 'goo': "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("every point of the fluid's fills lies inside an object"),
              std::string::npos)
        << e.what();
  }
}

// Objects that start inside each other: the particles of one that lie more than about
// half a particle inside another's closed volume, per pair where one of the two moves. A
// crate inside a hollow box (all its particles), one sunk half into it, and one turned
// so that an edge goes in are named; boxes resting face to face (a stack) are not,
// nor are two static objects.
TEST(CompileWarnings, NamesObjectsThatStartInsideEachOther) {
  const auto object = [](const std::string& name, double size, const Vec3& at, double turn,
                         bool dynamic = true) {
    return fmt::format(
        "<Object><Name>{}</Name><Shape>box</Shape><Size>{} {} {}</Size><ParticleSize>0.25</ParticleSize>"
        "<InitialPosition>{} {} {}</InitialPosition><InitialRotation>0 0 {}</InitialRotation>"
        "<IsDynamic>{}</IsDynamic></Object>\n",
        name, size, size, size, at.x(), at.y(), at.z(), turn, dynamic ? "true" : "false");
  };
  const std::string big = object("big", 4, Vec3(0, 2, 0), 0);
  {
    const std::string text = sceneWith(big + object("small", 1, Vec3(0, 2, 0), 0));
    const Compiled c = compile(readSceneText(text, "t.scene"));
    ASSERT_EQ(c.warnings.size(), 1u) << fmt::format("{}", fmt::join(c.warnings, "\n"));
    EXPECT_NE(
        c.warnings[0].find(fmt::format("Objects 'big' (line 2) and 'small' (line 3) start inside each other "
                                       "({0} of the {0} particle(s) of 'small' lie inside 'big'):",
                                       c.model.bodies.bodies[1].count)),
        std::string::npos)
        << c.warnings[0];
  }
  // Sunk half into the big one's side (x from 1.5 to 2.5, the big box ends at 2), and a
  // cube turned 45 degrees about z, its lower edge 0.6 into the big one's top.
  for (const std::string& other :
       {object("half", 1, Vec3(2, 2, 0), 0), object("edge", 1, Vec3(0, 4 + std::sqrt(0.5) - 0.6, 0), 45)}) {
    const std::vector<std::string> w = warningsOf(big + other);
    ASSERT_EQ(w.size(), 1u) << other;
    EXPECT_NE(w[0].find("Objects 'big' (line 2) and "), std::string::npos) << w[0];
    EXPECT_NE(w[0].find("lie inside 'big'"), std::string::npos) << w[0];
    EXPECT_EQ(w[0].find("(0 of "), std::string::npos) << w[0];
  }
  // Face to face, a stack of three; beside each other; two static ones one in the other.
  EXPECT_TRUE(warningsOf(big + object("on", 1, Vec3(0, 4.5, 0), 0) + object("top", 1, Vec3(0, 5.5, 0), 0) +
                         object("beside", 2, Vec3(3, 1, 0), 0))
                  .empty());
  EXPECT_TRUE(
      warningsOf(object("a", 4, Vec3(0, 2, 0), 0, false) + object("b", 1, Vec3(0, 2, 0), 0, false)).empty());
}

// ParticleSize (default 1, absolute) against the particles' own spacing: a scene in
// centimetres that leaves it out gets told, one that sets it does not; and a container
// narrower than a particle (its walls keep centres half a particle in) is named.
TEST(CompileWarnings, NamesAParticleSizeFarFromTheSpacing) {
  const std::string centimetres = "<Environment><Width>0.2</Width><Height>0.3</Height><Depth>0.2</Depth></Environment>";
  const std::string cube = "<Fill><Shape>box</Shape><Min>-0.05 0.005 -0.05</Min><Max>0.05 0.05 0.05</Max>"
                           "<Spacing>0.011</Spacing></Fill>";
  const std::vector<std::string> left = warningsOf(centimetres + "<Fluid><Name>goo</Name>" + cube + "</Fluid>");
  ASSERT_EQ(left.size(), 3u);
  EXPECT_NE(left[0].find("Fluid 'goo': ParticleSize 1 is 90.9 times the spacing of its particles (0.011)"),
            std::string::npos)
      << left[0];
  EXPECT_NE(left[1].find("Fluid 'goo': the container is 0.2 across, narrower than its ParticleSize 1"),
            std::string::npos)
      << left[1];
  // Its force's distances are a unit's too: the fill would fly apart.
  EXPECT_NE(left[2].find(
                "Fluid 'goo': the fill at line 2 has Spacing 0.011, but this fluid's own force holds such a "
                "lattice at rest about 0.958 apart, so it swells to over a thousand times its volume"),
            std::string::npos)
      << left[2];
  EXPECT_TRUE(warningsOf(centimetres +
                         "<Fluid><Name>goo</Name><ParticleSize>0.01</ParticleSize><FiniteDistance>0.011</"
                         "FiniteDistance><InteractionDistance>0.0165</InteractionDistance>" +
                         cube + "</Fluid>")
                  .empty());
  // Far too small is as wrong: the walls let particles overlap them.
  const std::vector<std::string> tiny = warningsOf(kBox + "<Fluid><Name>a</Name><ParticleSize>0.1</ParticleSize>" +
                                                   fill("0 0 0", "2 2 2") + "</Fluid>");
  ASSERT_EQ(tiny.size(), 1u);
  EXPECT_NE(tiny[0].find("ParticleSize 0.1 is 0.1 times the spacing of its particles (1)"), std::string::npos)
      << tiny[0];
}

// The seed's fluid/fluid and fluid/object defaults are absolute (cutoffs 1 and 1.5):
// fluids in centimetres that leave them out are pushed apart from a unit away, fluids a
// hundred times larger pass through each other; both are named once, and a scene that
// gives the function (or a Pair) in its own units is not.
TEST(CompileWarnings, NamesTheDefaultInteractionsAtAnotherScale) {
  const auto fluid = [](const std::string& name, double s, double x) {
    return fmt::format(
        "<Fluid><Name>{}</Name><ParticleSize>{}</ParticleSize><FiniteDistance>{}</FiniteDistance>"
        "<InteractionDistance>{}</InteractionDistance><Fill><Shape>box</Shape><Min>{} 0 0</Min>"
        "<Max>{} {} {}</Max><Spacing>{}</Spacing></Fill></Fluid>",
        name, s, s, 1.5 * s, x * s, (x + 3) * s, 3 * s, 3 * s, s);
  };
  const std::string cm = fluid("a", 0.01, -8) + fluid("b", 0.01, 5);
  const std::vector<std::string> small = warningsOf(cm);
  ASSERT_EQ(small.size(), 1u);
  EXPECT_NE(
      small[0].find("Interactions: fluids 'a' and 'b' (reach 0.015) meet through the default fluid/fluid "
                    "function"),
      std::string::npos)
      << small[0];
  EXPECT_NE(small[0].find("pushes them apart from much further than they reach"), std::string::npos)
      << small[0];
  const std::vector<std::string> large = warningsOf(fluid("a", 100, -8) + fluid("b", 100, 5));
  ASSERT_EQ(large.size(), 1u);
  EXPECT_NE(large[0].find("hardly acts, and they pass through each other"), std::string::npos) << large[0];
  // Given in the scene's units, as FluidFluid or as a Pair: no warning.
  const std::string linear =
      "<Linear><AtZero>0.05</AtZero><Cutoff>0.01</Cutoff><Min>0</Min><Max>0.05</Max></Linear>";
  EXPECT_TRUE(
      warningsOf(cm + "<Interactions><FluidFluid>" + linear + "</FluidFluid></Interactions>").empty());
  EXPECT_TRUE(
      warningsOf(cm + "<Interactions><Pair><A>a</A><B>b</B>" + linear + "</Pair></Interactions>").empty());
  // At the seed's own scale nothing is said.
  EXPECT_TRUE(warningsOf(fluid("a", 1, -8) + fluid("b", 1, 5)).empty());
  // The fluid/object default (cutoff 1.5) against a centimetre fluid, and its override.
  const std::string ball =
      "<Object><Name>ball</Name><Shape>sphere</Shape><Size>0.05</Size>"
      "<ParticleSize>0.01</ParticleSize><InitialPosition>0 0.2 0</InitialPosition></Object>";
  const std::vector<std::string> object = warningsOf(fluid("a", 0.01, -8) + ball);
  ASSERT_EQ(object.size(), 1u);
  EXPECT_NE(object[0].find("Interactions: fluid 'a' (reach 0.015) meets object 'ball' through the default "
                           "fluid/object function"),
            std::string::npos)
      << object[0];
  EXPECT_TRUE(warningsOf(fluid("a", 0.01, -8) + ball + "<Interactions><FluidObject>" + linear +
                         "</FluidObject></Interactions>")
                  .empty());
}

TEST(CompileWarnings, CountsParticlesThatSitExactlyOnAnother) {
  // The same fill twice: each of its 8 points twice; and across fluids.
  const std::vector<std::string> twice = warningsOf(kBox + "<Fluid><Name>a</Name>" + fill("0 0 0", "2 2 2") +
                                                    fill("0 0 0", "2 2 2") + "</Fluid>");
  ASSERT_EQ(twice.size(), 1u);
  EXPECT_NE(twice[0].find("8 particles sit exactly where another one does"), std::string::npos) << twice[0];
  const std::vector<std::string> across = warningsOf(kBox + "<Fluid><Name>a</Name><Particles>1 1 1  1 1 2</Particles>"
                                                     "</Fluid><Fluid><Name>b</Name><Particles>1 1 1</Particles></Fluid>");
  ASSERT_EQ(across.size(), 1u);
  EXPECT_NE(across[0].find("1 particle sits exactly"), std::string::npos) << across[0];
}

}  // namespace
}  // namespace softsub::scene

namespace softsub::scene {
namespace {

// The rest spacing of a cubic fill, against what can be worked out by hand: a force
// whose cutoff leaves only the 6 nearest neighbours in reach rests where it is zero
// (the seed's shape: at FiniteDistance); with the next shells in reach their pull puts
// the rest below it; a force that only pushes swells the lattice to its cutoff, one
// that only pulls has no rest; a lattice at rest, or out of reach, goes nowhere.
TEST(CubicRestSpacing, IsWhereTheNeighboursForcesBalance) {
  // Cutoff 1.3: at spacings near 1 the second shell (1.41) is out of reach.
  const forces::PairFunction nearOnly = forces::LennardJones{30, 1, -20, 400, 1.3};
  const std::optional<double> nearest = cubicRestSpacing(nearOnly, 0.9);
  ASSERT_TRUE(nearest.has_value());
  EXPECT_NEAR(*nearest, 1.0, 1e-9);
  EXPECT_NEAR(cubicRestSpacing(nearOnly, 1.05).value_or(0), 1.0, 1e-9);  // from above too
  EXPECT_FALSE(cubicRestSpacing(nearOnly, 1.0).has_value());             // at rest already
  EXPECT_FALSE(cubicRestSpacing(nearOnly, 1.3).has_value());             // out of each other's reach
  // It scales with the distances.
  const std::optional<double> scaled =
      cubicRestSpacing(forces::LennardJones{30, 0.01, -20, 400, 0.013}, 0.009);
  ASSERT_TRUE(scaled.has_value());
  EXPECT_NEAR(*scaled, 0.01, 1e-11);
  // A cutoff 4.5 times FiniteDistance (a review: the search began at a quarter of the
  // cutoff, above the rest, and found none): still found, below 1.
  const std::optional<double> wide = cubicRestSpacing(forces::LennardJones{30, 1, -20, 400, 4.5}, 1.1);
  ASSERT_TRUE(wide.has_value());
  EXPECT_GT(*wide, 0.8);
  EXPECT_LT(*wide, 1.0);
  // Filled far above its rest (a review: at 2.5 it was told it collapses).
  EXPECT_NEAR(cubicRestSpacing(forces::LennardJones{30, 1, -20, 400, 4.5}, 2.5).value_or(0), *wide, 1e-6);
  // No attraction (MinimumForce 0): it swells to where its particles stop pushing, s.
  EXPECT_NEAR(cubicRestSpacing(forces::LennardJones{30, 1, 0, 400, 1.5}, 0.8).value_or(0), 1.0, 1e-6);
  // The default fluid (cutoff 1.5): 12 second neighbours at 1.35-1.41 pull it in. The
  // sum of r F(r) at the rest is 0 by the formula, computed here on its own.
  const forces::PairFunction seed = forces::LennardJones{30, 1, -20, 400, 1.5};
  const std::optional<double> rest = cubicRestSpacing(seed, 1.0);
  ASSERT_TRUE(rest.has_value());
  EXPECT_LT(*rest, 0.99);
  EXPECT_GT(*rest, 0.9);
  const auto virial = [&](double a) {
    return 6 * a * forces::evaluate(seed, a) +
           12 * std::sqrt(2.0) * a * forces::evaluate(seed, std::sqrt(2.0) * a);
  };
  EXPECT_GT(virial(*rest - 1e-6), 0);  // the third shell (1.73 a) is beyond 1.5 here
  EXPECT_LT(virial(*rest + 1e-6), 0);
  // Only pushing: swells to the cutoff. Only pulling: no rest, and the push is negative.
  EXPECT_NEAR(cubicRestSpacing(forces::Linear{5, 1, 0, 5}, 0.5).value_or(0), 1.0, 1e-6);
  const forces::PairFunction pull = forces::Linear{-5, 1, -5, 0};
  EXPECT_FALSE(cubicRestSpacing(pull, 0.5).has_value());
  EXPECT_LT(cubicVirial(pull, 0.5), 0);
}

// A fill far from its fluid's rest spacing is named with the volume it will gain or
// lose (the jelly example's cube at 1.12 lost 41% in mid-air in a review); one at the
// rest spacing, or one whose fluid's own function a Pair replaces with one resting at
// the fill's spacing, is not.
TEST(CompileWarnings, NamesAFillFarFromItsFluidsRestSpacing) {
  const std::string jelly =
      "<Fluid><Name>jelly</Name><InteractionDistance>2</InteractionDistance>"
      "<Amplitude>150</Amplitude><MinimumForce>-150</MinimumForce>"
      "<MaximumForce>2000</MaximumForce><ParticleSize>{0}</ParticleSize>"
      "<Fill><Shape>box</Shape><Min>-3 1 -3</Min><Max>3 7 3</Max><Spacing>{0}</Spacing>"
      "</Fill></Fluid>";
  const std::vector<std::string> w = warningsOf(kBox + fmt::format(fmt::runtime(jelly), 1.12));
  ASSERT_EQ(w.size(), 1u) << fmt::format("{}", fmt::join(w, "\n"));
  EXPECT_NE(
      w[0].find(
          "Fluid 'jelly': the fill at line 3 has Spacing 1.12, but this fluid's own force holds such a "
          "lattice at rest about 0.945 apart, so it shrinks by about 40% in volume in its first frames; "
          "fill at Spacing 0.945, or scale FiniteDistance and InteractionDistance by 1.19"),
      std::string::npos)
      << w[0];
  EXPECT_TRUE(warningsOf(kBox + fmt::format(fmt::runtime(jelly), 0.945)).empty());
  // Swelling: the mud of a review, filled at 0.8.
  const std::vector<std::string> mud =
      warningsOf(kBox +
                 "<Fluid><Name>mud</Name><Amplitude>20</Amplitude><MinimumForce>-6</MinimumForce>"
                 "<ParticleSize>0.8</ParticleSize><Fill><Shape>box</Shape><Min>-3 0 -3</Min><Max>3 2 3</Max>"
                 "<Spacing>0.8</Spacing></Fill></Fluid>");
  ASSERT_EQ(mud.size(), 1u) << fmt::format("{}", fmt::join(mud, "\n"));
  // Far above its rest, with a long reach: shrinks (it was told it collapses).
  const std::vector<std::string> wide = warningsOf(
      kBox +
      "<Fluid><Name>w</Name><InteractionDistance>4.5</InteractionDistance><ParticleSize>2.5</ParticleSize>"
      "<Fill><Shape>box</Shape><Min>-5 0 -5</Min><Max>5 5 5</Max><Spacing>2.5</Spacing></Fill></Fluid>");
  ASSERT_EQ(wide.size(), 1u) << fmt::format("{}", fmt::join(wide, "\n"));
  EXPECT_NE(wide[0].find("at rest about 0.924 apart, so it shrinks to about 0.05"), std::string::npos)
      << wide[0];
  EXPECT_NE(mud[0].find("so it swells by about 80% in volume"), std::string::npos) << mud[0];
  // A Pair of the fluid with itself replaces the function the rest is worked out from:
  // the jelly's shape scaled by 1.185 rests at 1.12.
  EXPECT_TRUE(
      warningsOf(kBox + fmt::format(fmt::runtime(jelly), 1.12) +
                 "<Interactions><Pair><A>jelly</A><B>jelly</B><LennardJones><Amplitude>150</Amplitude>"
                 "<FiniteDistance>1.185</FiniteDistance><Min>-150</Min><Max>2000</Max>"
                 "<Cutoff>2.37</Cutoff></LennardJones></Pair></Interactions>")
          .empty());
}

}  // namespace
}  // namespace softsub::scene
