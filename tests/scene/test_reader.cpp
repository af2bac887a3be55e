// What the reader accepts: defaults, every value form, structure in any order, lines,
// the particle cap, and files.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <variant>

#include "scene/reader.h"
#include "scene_test_util.h"

namespace softsub::scene {
namespace {

using testing::readError;
using testing::sceneWith;
using testing::validFluid;

TEST(Reader, MissingOptionalElementsTakeDefaults) {
  const SceneDesc d = readSceneText(sceneWith(validFluid("water")), "t.scene");
  EXPECT_EQ(d.simulation, SimulationDesc{});
  EXPECT_EQ(d.camera, CameraDesc{});
  EXPECT_FALSE(d.environment.has_value());  // no <Environment>: no walls at all
  EXPECT_EQ(d.interactions, InteractionsDesc{});
  ASSERT_EQ(d.fluids.size(), 1U);
  EXPECT_EQ(d.fluids[0].name, "water");
  EXPECT_EQ(d.fluids[0].params, fluid::FluidParams{});
  EXPECT_EQ(d.fluids[0].initialSpeed, FluidDesc{}.initialSpeed);
  EXPECT_EQ(d.fluids[0].colour, FluidDesc{}.colour);
  EXPECT_TRUE(d.fluids[0].particles.empty());
  ASSERT_EQ(d.fluids[0].fills.size(), 1U);
  EXPECT_EQ(d.fluids[0].fills[0].spacing, FillDesc{}.spacing);
  EXPECT_EQ(d.fluids[0].fills[0].min, FillDesc{}.min);
}

TEST(Reader, SeedGlobalFluidFluidDefault) {
  const SceneDesc d = readSceneText(sceneWith(validFluid("water")), "t.scene");
  const auto* linear = std::get_if<forces::Linear>(&d.interactions.fluidFluid.function);
  ASSERT_NE(linear, nullptr);
  EXPECT_EQ(*linear, (forces::Linear{5, 1, 0, 5}));
  EXPECT_EQ(d.interactions.fluidFluid.damping, 0);
  EXPECT_EQ(d.interactions.fluidFluid.relativeVelocity, 0);
}

TEST(Reader, EmptyEnvironmentTakesItsDefaults) {
  const SceneDesc d = readSceneText(sceneWith("<Environment/>\n" + validFluid("w")), "t.scene");
  ASSERT_TRUE(d.environment.has_value());
  EXPECT_EQ(*d.environment, EnvironmentDesc{});
}

TEST(Reader, ReadsEveryField) {
  const std::string text = R"(<?xml version="1.0" encoding="UTF-8"?>
<!-- a comment before the root -->
<Scene version="1">
  <Simulation>
    <FramesPerSecond>30</FramesPerSecond>
    <Substeps>+4</Substeps>
    <Frames>10</Frames>
    <Gravity> 0
      -1.5e1   0 </Gravity>
    <Integrator>velocity-verlet</Integrator>
  </Simulation>
  <Camera><Eye>1 2 3</Eye><VerticalAngle>-10</VerticalAngle><HorizontalAngle>370</HorizontalAngle></Camera>
  <Environment>
    <Width>4</Width><Height>5</Height><Depth>6</Depth><Reflective>1</Reflective>
    <NormalAttenuation>0</NormalAttenuation><TangentAttenuation>1</TangentAttenuation>
    <Closed>true</Closed>
  </Environment>
  <Interactions>
    <Pair><A>oil</A><B>honey</B><LennardJones><Amplitude>2</Amplitude></LennardJones></Pair>
    <Pair><A>honey</A><B>honey</B><LennardJonesForce><Epsilon>0.5</Epsilon><Sigma>0.9</Sigma><Cutoff>2</Cutoff></LennardJonesForce><Damping>3</Damping></Pair>
    <FluidFluid><Curve><Points>0 4  0.5 1  1 0</Points></Curve><RelativeVelocity>0.25</RelativeVelocity></FluidFluid>
  </Interactions>
  <Fluid>
    <Name>honey</Name>
    <InteractionDistance>2</InteractionDistance><Amplitude>0</Amplitude>
    <FiniteDistance>0.8</FiniteDistance><MinimumForce>-5</MinimumForce>
    <MaximumForce>-5</MaximumForce><Viscosity>0</Viscosity><ParticleSize>0.5</ParticleSize>
    <ParticleMass>2</ParticleMass><InitialSpeed>0 -1 0</InitialSpeed><Colour>1 0 0.5</Colour>
    <NumberOfParticles>2</NumberOfParticles>
    <Particles><![CDATA[0 0 0]]>
      1 2 3</Particles>
  </Fluid>
  <Fluid>
    <Name>oil</Name>
    <Fill><Shape>sphere</Shape><Center>1 1 1</Center><Radius>2</Radius><Spacing>0.5</Spacing></Fill>
    <Fill><Spacing>0.25</Spacing><Shape>box</Shape><Min>-1 0 -1</Min><Max>1 1 1</Max></Fill>
  </Fluid>
</Scene>
)";
  const SceneDesc d = readSceneText(text, "t.scene");
  EXPECT_EQ(d.simulation.framesPerSecond, 30);
  EXPECT_EQ(d.simulation.substeps, 4);
  EXPECT_EQ(d.simulation.frames, 10);
  EXPECT_EQ(d.simulation.gravity, Vec3(0, -15, 0));
  EXPECT_EQ(d.simulation.integrator, Integrator::VelocityVerlet);
  EXPECT_EQ(d.camera.eye, Vec3(1, 2, 3));
  EXPECT_EQ(d.camera.verticalAngle, -10);
  EXPECT_EQ(d.camera.horizontalAngle, 370);
  ASSERT_TRUE(d.environment);
  EXPECT_EQ(*d.environment, (EnvironmentDesc{4, 5, 6, true, 0, 1, true}));

  ASSERT_EQ(d.fluids.size(), 2U);
  const FluidDesc& honey = d.fluids[0];
  EXPECT_EQ(honey.name, "honey");
  EXPECT_EQ(honey.params, (fluid::FluidParams{2, 0, 0.8, -5, -5, 0, 0.5, 2}));
  EXPECT_EQ(honey.initialSpeed, Vec3(0, -1, 0));
  EXPECT_EQ(honey.colour, Vec3(1, 0, 0.5));
  EXPECT_EQ(honey.particles, (std::vector<Vec3>{{0, 0, 0}, {1, 2, 3}}));
  EXPECT_TRUE(honey.fills.empty());
  EXPECT_EQ(honey.line, testing::lineOf(text, "<Name>honey") - 1);

  const FluidDesc& oil = d.fluids[1];
  ASSERT_EQ(oil.fills.size(), 2U);
  EXPECT_EQ(oil.fills[0].shape, FillShape::Sphere);
  EXPECT_EQ(oil.fills[0].center, Vec3(1, 1, 1));
  EXPECT_EQ(oil.fills[0].radius, 2);
  EXPECT_EQ(oil.fills[0].spacing, 0.5);
  EXPECT_EQ(oil.fills[0].line, testing::lineOf(text, "<Shape>sphere"));
  EXPECT_EQ(oil.fills[1].shape, FillShape::Box);
  EXPECT_EQ(oil.fills[1].min, Vec3(-1, 0, -1));
  EXPECT_EQ(oil.fills[1].max, Vec3(1, 1, 1));
  EXPECT_EQ(oil.fills[1].spacing, 0.25);

  const auto& ff = d.interactions.fluidFluid;
  EXPECT_EQ(ff.function, forces::PairFunction(forces::Curve{{0, 4, 0.5, 1, 1, 0}}));
  EXPECT_EQ(ff.damping, 0);
  EXPECT_EQ(ff.relativeVelocity, 0.25);
  ASSERT_EQ(d.interactions.pairs.size(), 2U);
  EXPECT_EQ(d.interactions.pairs[0].a, "oil");
  EXPECT_EQ(d.interactions.pairs[0].b, "honey");
  EXPECT_EQ(d.interactions.pairs[0].line, testing::lineOf(text, "<Pair><A>oil"));
  forces::LennardJones lj;  // missing function tags take the struct defaults
  lj.amplitude = 2;
  EXPECT_EQ(d.interactions.pairs[0].interaction.function, forces::PairFunction(lj));
  EXPECT_EQ(d.interactions.pairs[1].interaction,
            (InteractionDesc{forces::LennardJonesForce{0.5, 0.9, 2}, 3, 0}));
}

TEST(Reader, FunctionTagsDefaultToTheStruct) {
  const SceneDesc d = readSceneText(
      sceneWith(validFluid("w") +
                "<Interactions><FluidFluid><Linear><Cutoff>2</Cutoff></Linear></FluidFluid>"
                "</Interactions>"),
      "t.scene");
  forces::Linear expected;
  expected.cutoff = 2;
  EXPECT_EQ(d.interactions.fluidFluid.function, forces::PairFunction(expected));
}

TEST(Reader, PairOfAFluidWithItselfIsAllowed) {
  const SceneDesc d = readSceneText(
      sceneWith(validFluid("w") + "<Interactions><Pair><A>w</A><B>w</B><Linear/></Pair></Interactions>"),
      "t.scene");
  ASSERT_EQ(d.interactions.pairs.size(), 1U);
  EXPECT_EQ(d.interactions.pairs[0].a, d.interactions.pairs[0].b);
}

TEST(Reader, ExplicitParticlesWithoutCountAndFillsTogether) {
  const SceneDesc d = readSceneText(
      sceneWith("<Fluid><Name>w</Name><Particles>1 1 1</Particles>"
                "<Fill><Shape>box</Shape></Fill></Fluid>"),
      "t.scene");
  EXPECT_EQ(d.fluids[0].particles.size(), 1U);
  EXPECT_EQ(d.fluids[0].fills.size(), 1U);
}

TEST(Reader, NumberFormsAreLocaleIndependentAndStrict) {
  const auto fps = [](std::string_view v) {
    return readSceneText(sceneWith("<Simulation><FramesPerSecond>" + std::string(v) +
                                   "</FramesPerSecond></Simulation>" + validFluid("w")),
                         "t.scene")
        .simulation.framesPerSecond;
  };
  EXPECT_EQ(fps("24"), 24);
  EXPECT_EQ(fps(" 2.5e1 "), 25);
  EXPECT_EQ(fps("+12.5"), 12.5);
  EXPECT_EQ(fps(".5"), 0.5);
  EXPECT_EQ(fps("1000"), 1000);
  EXPECT_EQ(fps("0.1"), 0.1);  // correctly rounded, as std::from_chars guarantees
  for (const char* bad : {"0x10", "1..2", "--1", "+-1", "1e", "24 fps", ""}) {
    EXPECT_THROW(fps(bad), InputError) << bad;
  }
}

TEST(Reader, RealsUpToSinglePrecisionAreAccepted) {
  const SceneDesc d = readSceneText(
      sceneWith("<Simulation><Gravity>3.4e38 -3.4e38 1e-30</Gravity></Simulation>" + validFluid("w")),
      "t.scene");
  EXPECT_EQ(d.simulation.gravity, Vec3(3.4e38, -3.4e38, 1e-30));
  for (const char* big : {"3.41e38", "-3.41e38", "1e39", "1e300"}) {
    const InputError e = readError(
        sceneWith("<Simulation><Gravity>0 " + std::string(big) + " 0</Gravity></Simulation>"));
    EXPECT_EQ(e.problem(), "'" + std::string(big) + "' is too large for single precision") << e.what();
    EXPECT_EQ(e.allowed(), "|value| <= 3.4e38") << e.what();
  }
  // A bounded field names its own range first.
  const InputError fps =
      readError(sceneWith("<Simulation><FramesPerSecond>1e39</FramesPerSecond></Simulation>"));
  EXPECT_EQ(fps.problem(), "1e39 is out of range") << fps.what();
  EXPECT_EQ(fps.allowed(), "[0.001, 1000]") << fps.what();
}

TEST(Reader, UpToTheFluidCapIsAccepted) {
  std::string fluids;
  for (std::size_t i = 0; i < kMaxFluids; ++i)
    fluids += validFluid(std::string("f").append(std::to_string(i)));
  const SceneDesc d = readSceneText(sceneWith(fluids), "t.scene");
  EXPECT_EQ(d.fluids.size(), kMaxFluids);
  EXPECT_EQ(d.fluids.back().name, "f1023");
}

TEST(Reader, CommentsCdataAndBomAreFine) {
  const std::string text = "\xEF\xBB\xBF<Scene version=\"1\"><!-- c -->\n<Fluid><Name><![CDATA[w]]></Name>"
                           "<Particles>1 2 3<!-- between -->4 5 6</Particles></Fluid>\n</Scene>";
  const SceneDesc d = readSceneText(text, "t.scene");
  EXPECT_EQ(d.fluids[0].name, "w");
  EXPECT_EQ(d.fluids[0].particles.size(), 2U);
}

// CDATA sections are character data: they join the text beside them as they stand (a
// name or a number split across them keeps its characters). A comment is markup and
// reads as a space, so numbers on either side of it stay apart.
TEST(Reader, CdataJoinsTheTextBesideItAndACommentReadsAsASpace) {
  const SceneDesc d = readSceneText(
      sceneWith(
          "<Fluid><Name>ab<![CDATA[cd]]>ef</Name><Viscosity>2<![CDATA[.5]]></Viscosity>"
          "<ParticleMass><!-- kg -->3</ParticleMass><Particles>1 2 3<!-- row -->4 5 6<![CDATA[ 7]]>.5 8 9"
          "</Particles></Fluid>"),
      "t.scene");
  ASSERT_EQ(d.fluids.size(), 1u);
  EXPECT_EQ(d.fluids[0].name, "abcdef");
  EXPECT_EQ(d.fluids[0].params.viscosity, 2.5);
  EXPECT_EQ(d.fluids[0].params.particleMass, 3);
  ASSERT_EQ(d.fluids[0].particles.size(), 3u);
  EXPECT_EQ(d.fluids[0].particles[1].x(), 4);
  EXPECT_EQ(d.fluids[0].particles[2].x(), 7.5);
  EXPECT_EQ(d.fluids[0].particles[2].y(), 8);
  EXPECT_EQ(d.fluids[0].particles[2].z(), 9);
}

// A bad number inside a value of several pieces (text, comments, CDATA) is named on its
// own line, whichever piece it is in.
TEST(Reader, ABadNumberInAValueOfSeveralPiecesIsNamedOnItsLine) {
  const std::string fluid =
      "<Fluid><Name>w</Name><Particles>0 0 0 <!-- a\ncomment -->\n1 1 1\n"
      "<![CDATA[2 2 2\n3 3 3\n]]>4 4 4\nnan 5 5 <!--X-->\n</Particles></Fluid>";
  std::string text = sceneWith(fluid);
  const InputError e = readError(text);
  EXPECT_EQ(e.where().line, testing::lineOf(text, "nan")) << e.what();
  std::string inCdata = text;
  inCdata.replace(inCdata.find("3 3 3"), 5, "3 x 3");
  EXPECT_EQ(readError(inCdata).where().line, testing::lineOf(inCdata, "3 x 3")) << readError(inCdata).what();
}

TEST(Reader, LinesCountWithCrLfAndBom) {
  const std::string text =
      "\xEF\xBB\xBF<Scene>\r\n<Simulation>\r\n\r\n<Substeps>0</Substeps>\r\n</Simulation>\r\n</Scene>";
  const InputError e = readError(text);
  EXPECT_EQ(e.where().line, 4);
  EXPECT_EQ(e.where().element, "Simulation/Substeps");
}

TEST(Reader, VersionAttributeIsOptional) {
  EXPECT_NO_THROW(readSceneText("<Scene>" + validFluid("w") + "</Scene>", "t.scene"));
}

TEST(Reader, SceneWithoutFluidsIsValid) {
  const SceneDesc d = readSceneText("<Scene version=\"1\"/>", "t.scene");
  EXPECT_TRUE(d.fluids.empty());
}

TEST(Reader, ParticleCapCountsExplicitAndFillsAcrossFluids) {
  // 8 from the fill (2x2x2) + 2 explicit in 'a', 8 more in 'b': 18 in all.
  const std::string text = sceneWith(
      "<Fluid><Name>a</Name><Particles>0 0 0 1 1 1</Particles>"
      "<Fill><Shape>box</Shape><Max>2 2 2</Max></Fill></Fluid>\n" +
      validFluid("b"));
  EXPECT_NO_THROW(readSceneText(text, "t.scene", ReadOptions{18}));
  const InputError e = readError(text, ReadOptions{17});
  EXPECT_EQ(e.where().element, "Fluid 'b'");
  EXPECT_EQ(e.where().line, 3);
  EXPECT_NE(e.problem().find("makes 18 particles"), std::string::npos) << e.what();
  EXPECT_NE(e.problem().find("cap of 17"), std::string::npos) << e.what();
}

TEST(Reader, AstronomicalFillIsRefusedWithoutAllocating) {
  // 1e300 and 3e338 points per axis: saturates instead of overflowing, and nothing is
  // generated.
  const InputError e = readError(
      sceneWith("<Fluid><Name>w</Name><Fill><Shape>box</Shape><Max>1 1 1</Max>"
                "<Spacing>1e-300</Spacing></Fill>"
                "<Fill><Shape>sphere</Shape><Radius>3e38</Radius><Spacing>1e-300</Spacing></Fill>"
                "</Fluid>"));
  EXPECT_NE(e.problem().find("over 10^19"), std::string::npos) << e.what();
  EXPECT_NE(e.problem().find("cap of 20000000"), std::string::npos) << e.what();
}

TEST(Reader, InteractionsMayComeBeforeFluids) {
  const SceneDesc d = readSceneText(
      sceneWith("<Interactions><Pair><A>w</A><B>v</B><Linear/></Pair></Interactions>\n" +
                validFluid("w") + validFluid("v")),
      "t.scene");
  EXPECT_EQ(d.interactions.pairs.size(), 1U);
}

class ReaderFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("softsub_reader_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
            "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

TEST_F(ReaderFile, ReadsAFileAndNamesItInErrors) {
  const auto good = dir_ / "good.scene";
  std::ofstream(good) << sceneWith(validFluid("w"));
  EXPECT_EQ(readSceneFile(good.string()).fluids.size(), 1U);

  const auto bad = dir_ / "bad.scene";
  std::ofstream(bad) << "<Scene>\n<Oops/>\n</Scene>\n";
  try {
    readSceneFile(bad.string());
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, bad.string());
    EXPECT_EQ(e.where().line, 2);
  }
}

TEST_F(ReaderFile, UnreadableIsAnIoError) {
  EXPECT_THROW(readSceneFile((dir_ / "missing.scene").string()), IoError);
  EXPECT_THROW(readSceneFile(dir_.string()), IoError);
}

}  // namespace
}  // namespace softsub::scene
