// `softsub info` on each kind of file it knows, and on one it does not.
#include <algorithm>
#include <fstream>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "app_test_util.h"
#include "support/mesh_files.h"

namespace softsub::apptest {
namespace {

void expectContains(const std::string& text, const std::string& part) {
  EXPECT_NE(text.find(part), std::string::npos) << "'" << part << "' not in\n" << text;
}

/// Runs two-fluids for 2 frames into tmp/o and returns tmp/o.
fs::path runTwoFluids(const TempDir& tmp) {
  const RunResult r = runSoftsub(
      "run -q --frames 2 --out " + quote(tmp / "o") + " " + quote(examplesDir() / "two-fluids.scene"), tmp.path());
  EXPECT_EQ(r.code, 0) << r.err;
  return tmp / "o";
}

TEST(Info, SceneListsFluidsCountsParametersAndInteractions) {
  TempDir tmp;
  const RunResult r = runSoftsub("info " + quote(examplesDir() / "two-fluids.scene"), tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  expectContains(r.out, "48 frames at 24 fps");
  expectContains(r.out, "8 substeps");
  expectContains(r.out, "symplectic-euler");
  expectContains(r.out, "environment: box x [-7, 7]  y [0, 30]  z [-7, 7]");
  expectContains(r.out, "fluids: 2, 1,728 particles in all");
  expectContains(r.out, "syrup: 864 particles");
  expectContains(r.out, "oil: 864 particles");
  expectContains(r.out, "Viscosity 3");
  expectContains(r.out, "ParticleMass 0.5");
  expectContains(r.out, "pair syrup / oil: Linear (AtZero 60, Cutoff 1.6, Min 0, Max 60)");
  expectContains(r.out, "bounds x [");
}

TEST(Info, SceneListsObjectsTheirParticlesAndTheFluidObjectFunction) {
  TempDir tmp;
  const RunResult r = runSoftsub("info " + quote(examplesDir() / "interactions.scene"), tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  expectContains(r.out, "fluids: 2, 480 particles in all");  // body particles are not fluid
  expectContains(r.out, "objects: 3, ");
  expectContains(r.out, "table: box, ");
  expectContains(r.out, "particles of diameter 0.5, static, mass 1");
  expectContains(r.out, "ball: sphere, ");
  expectContains(r.out, "dynamic, mass 8");
  expectContains(r.out, "fluid/object: Linear (AtZero 5, Cutoff 1.5, Min 0, Max 5); Damping 0, RelativeVelocity 2");
  expectContains(r.out, "pair oil / box: Linear (AtZero 6, Cutoff 2");
}

// info shows the stability estimate (the viewer's hint) with the substeps it asks for:
// the same count run's warning gives for an unstable scene (a review found no way to
// see the estimate outside the viewer, where a scene sits in its marginal band).
TEST(Info, SceneShowsTheStabilityEstimateAndTheSubstepsItAsksFor) {
  TempDir tmp;
  std::string jelly = readFile(examplesDir() / "jelly-block.scene");
  jelly.replace(jelly.find("<Substeps>24</Substeps>"), 23, "<Substeps>8</Substeps>");
  std::ofstream(tmp / "stiff.scene") << jelly;
  const RunResult info = runSoftsub("info stiff.scene", tmp.path());
  ASSERT_EQ(info.code, 0) << info.err;
  const std::string prefix = "stability (the estimate): unstable at 8 substeps: expect a blow-up (";
  const std::size_t at = info.out.find(prefix);
  ASSERT_NE(at, std::string::npos) << info.out;
  const int asked = std::stoi(info.out.substr(at + prefix.size()));
  EXPECT_GT(asked, 8);
  expectContains(info.out, "substeps for a factor 2 to spare); most demanding pair jelly / jelly");
  const RunResult run = runSoftsub("run stiff.scene --frames 0 --formats none", tmp.path());
  expectContains(run.err, fmt::format("raise Substeps to {} or use --adaptive", asked));
  // At the example's own 24 substeps: marginal, and the same count for the factor 2.
  const RunResult own = runSoftsub("info " + quote(examplesDir() / "jelly-block.scene"), tmp.path());
  expectContains(own.out,
                 fmt::format("stability (the estimate): marginal at 24 substeps: stable, with less than a "
                             "factor 2 in the time step to spare ({} substeps for that)",
                             asked));
}

// A <Pair> of a fluid with itself replaces its own function and viscosity: info said
// nothing, so the fluid's Viscosity 1000 read as the one in use. And a primitive without
// Size takes one fitted to its mesh, which info did not show (a review).
TEST(Info, SaysWhatAPairReplacesAndTheSizeFittedToAMesh) {
  TempDir tmp;
  scenarios::writeTextFile(tmp / "cube.obj", scenarios::boxObj(2.0));
  std::ofstream(tmp / "p.scene")
      << "<Scene version=\"1\"><Environment/><Fluid><Name>g</Name><Viscosity>1000</Viscosity>"
         "<Fill><Shape>box</Shape><Min>-1 1 -1</Min><Max>1 3 1</Max></Fill></Fluid>"
         "<Fluid><Name>h</Name><Fill><Shape>box</Shape><Min>3 1 3</Min><Max>5 3 5</Max></Fill></Fluid>"
         "<Object><Name>crate</Name><Shape>box</Shape><Geometry>cube.obj</Geometry><UniformScale>1.5</"
         "UniformScale>"
         "<InitialPosition>6 3 -5</InitialPosition></Object>"
         "<Interactions><Pair><A>g</A><B>g</B><Linear><AtZero>5</AtZero><Cutoff>1</Cutoff><Min>0</"
         "Min><Max>5</Max>"
         "</Linear><Damping>1</Damping></Pair></Interactions></Scene>\n";
  const RunResult r = runSoftsub("info p.scene", tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  expectContains(
      r.out,
      "    not used: InteractionDistance, Amplitude, FiniteDistance, MinimumForce, MaximumForce and "
      "Viscosity (pair g / g below replaces its own function and viscosity)\n");
  EXPECT_EQ(r.out.find("not used", r.out.find("  h: ")), std::string::npos)
      << "h has no such pair: " << r.out;
  // boxObj(2): a cube of edge 2, scaled 1.5: the inertia's box is 3 x 3 x 3, written as a
  // scene writes Size, before UniformScale (a review: the scaled 3 3 3, pasted as Size,
  // would be scaled again).
  expectContains(
      r.out, "    Size 2 2 2 (fitted to the mesh's bounding box, for the inertia; before UniformScale)\n");
}

// A folder of .sim frames without manifests (the viewer's S writes none) was refused as
// "not a softsub run's output folder", though render, mesh and the add-on play it (a
// review): info says what it holds. A folder without frames is still refused.
TEST(Info, AFolderOfFramesWithoutManifestsIsDescribedNotRefused) {
  TempDir tmp;
  const RunResult run =
      runSoftsub("run " + quote(examplesDir() / "two-fluids.scene") + " --frames 3 --formats sim -q --out o",
                 tmp.path());
  ASSERT_EQ(run.code, 0) << run.err;
  fs::create_directories(tmp / "bare");
  for (int f = 0; f <= 3; ++f) {
    const std::string name = fmt::format("two-fluids.{:04}.sim", f);
    fs::copy_file(tmp / "o" / name, tmp / "bare" / name);
  }
  const RunResult r = runSoftsub("info bare", tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  expectContains(r.out, "frames of two-fluids in bare: 4 frames, 0..3, without manifests");
  // A gap and a second scene are said (a review: one scene was described, no gap).
  fs::remove(tmp / "bare" / "two-fluids.0002.sim");
  fs::copy_file(tmp / "o" / "two-fluids.0000.sim", tmp / "bare" / "other.0000.sim");
  const RunResult two = runSoftsub("info bare", tmp.path());
  ASSERT_EQ(two.code, 0) << two.err;
  expectContains(two.out,
                 "frames of two-fluids in bare: 3 frames, 0..3 (1 missing in between), without manifests");
  expectContains(two.out, "frames of other in bare: 1 frame, 0..0, without manifests");
  expectContains(two.out, "the folder holds frames of 2 scenes");
  fs::create_directories(tmp / "empty");
  const RunResult none = runSoftsub("info empty", tmp.path());
  EXPECT_EQ(none.code, 2) << none.err;
  expectContains(none.err, "not a softsub output folder");
}

// A cylinder fitted to a mesh has its axis along y: a rod modelled along z took the
// inertia of a disc four times its volume without a word (a review). A box 1 x 1 x 4
// stands in for the rod: as a fitted cylinder (radius 2, height 1) it holds 3.1 times its
// volume, and is named; as a fitted box, or with Size, or as Shape mesh, it is not.
TEST(Info, APrimitiveFittedFarFromItsMeshsVolumeIsNamed) {
  TempDir tmp;
  scenarios::writeTextFile(tmp / "rod.obj",
                           "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 4\nv 1 0 4\nv 0 1 4\nv 1 1 4\n"
                           "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n");
  const auto info = [&](const std::string& object) {
    std::ofstream(tmp / "rod.scene") << "<Scene version=\"1\"><Environment/><Object><Name>rod</Name>"
                                     << object
                                     << "<Geometry>rod.obj</Geometry><InitialPosition>0 3 0</InitialPosition>"
                                        "</Object></Scene>\n";
    const RunResult r = runSoftsub("info rod.scene", tmp.path());
    EXPECT_EQ(r.code, 0) << r.err;
    return r.err;
  };
  const std::string cylinder = info("<Shape>cylinder</Shape>");
  EXPECT_NE(
      cylinder.find("Object 'rod' (line 1): the cylinder fitted to its mesh for the inertia (Size 2 1) holds "
                    "3.14 times the mesh's volume"),
      std::string::npos)
      << cylinder;
  // Scaled, the Size is still said as a scene writes it, before UniformScale; a sphere
  // has no axis to turn.
  const std::string scaled = info("<Shape>cylinder</Shape><UniformScale>2</UniformScale>");
  EXPECT_NE(scaled.find("(Size 2 1) holds 3.14 times"), std::string::npos) << scaled;
  const std::string sphere = info("<Shape>sphere</Shape>");
  EXPECT_NE(sphere.find("the sphere fitted to its mesh for the inertia (Size 2) holds 8.38 times"),
            std::string::npos)
      << sphere;
  EXPECT_EQ(sphere.find("axis"), std::string::npos) << sphere;
  EXPECT_EQ(info("<Shape>box</Shape>"), "");
  EXPECT_EQ(info("<Shape>cylinder</Shape><Size>0.5 4</Size>"), "");
  EXPECT_EQ(info("<Shape>mesh</Shape>"), "");
}

// An object without <ParticleSize> is filled with particles of 1/20 of its largest extent;
// info printed the unset field as 'ParticleSize 0' (a value the schema refuses) next to
// the real diameter. It prints the size used.
TEST(Info, AnObjectWithoutParticleSizeShowsTheSizeUsed) {
  TempDir tmp;
  std::ofstream(tmp / "ball.scene")
      << "<Scene version=\"1\"><Fluid><Name>a</Name><NumberOfParticles>1</NumberOfParticles>"
         "<Particles>1 20 3</Particles></Fluid>"
         "<Object><Name>ball</Name><Shape>sphere</Shape><Size>2</Size></Object></Scene>\n";
  const RunResult r = runSoftsub("info ball.scene", tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  expectContains(r.out, "particles of diameter 0.2, ");
  expectContains(r.out, "ParticleSize 0.2, ");
  EXPECT_EQ(r.out.find("ParticleSize 0,"), std::string::npos) << r.out;
}

TEST(Info, SceneWithoutEnvironmentSaysSo) {
  TempDir tmp;
  std::ofstream(tmp / "free.scene")
      << "<Scene version=\"1\"><Fluid><Name>a</Name><NumberOfParticles>1</NumberOfParticles>"
         "<Particles>1 2 3</Particles></Fluid></Scene>\n";
  const RunResult r = runSoftsub("info free.scene", tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  expectContains(r.out, "environment: none");
  expectContains(r.out, "a: 1 particles (1 explicit, 0 fills), bounds x [1, 1]  y [2, 2]  z [3, 3]");
}

TEST(Info, SimPdcAndPlyPrintCountsAndBounds) {
  TempDir tmp;
  const fs::path out = runTwoFluids(tmp);
  const RunResult sim = runSoftsub("info " + quote(out / "two-fluids.0002.sim"), tmp.path());
  ASSERT_EQ(sim.code, 0) << sim.err;
  expectContains(sim.out, "frame 2, time 0.0833333 s, 2 fluids, 1,728 particles");
  expectContains(sim.out, "syrup: 864 particles, bounds x [");
  expectContains(sim.out, "oil: 864 particles, bounds x [");

  const RunResult pdc = runSoftsub("info " + quote(out / "pdc" / "oilShape.500.pdc"), tmp.path());
  ASSERT_EQ(pdc.code, 0) << pdc.err;
  expectContains(pdc.out, "version 1, byte order 1, 864 particles");
  expectContains(pdc.out, "position: vector array, 2,592 values");
  expectContains(pdc.out, "particleId: double array, 864 values");
  expectContains(pdc.out, "position bounds x [");

  const RunResult ply = runSoftsub("info " + quote(out / "ply" / "two-fluids.0002.ply"), tmp.path());
  ASSERT_EQ(ply.code, 0) << ply.err;
  expectContains(ply.out, "binary_little_endian, 1,728 vertices");
  expectContains(ply.out, "frame 2");
  expectContains(ply.out, "fluid 0 syrup: 864 particles");
  expectContains(ply.out, "fluid 1 oil: 864 particles");
}

TEST(Info, UnknownExtensionIsBadInput) {
  TempDir tmp;
  std::ofstream(tmp / "notes.txt") << "hello\n";
  const RunResult r = runSoftsub("info notes.txt", tmp.path());
  EXPECT_EQ(r.code, 2);
  expectContains(r.err, "error: notes.txt");
  expectContains(r.err, "unknown file extension '.txt'");
  expectContains(r.err, ".scene (or .xml), .sim, .pdc, .ply");
}

// A path that is not there is named as missing, whatever its extension: a mistyped run
// folder (no extension) was told "no file extension" with exit 2 (a review).
TEST(Info, AMissingPathIsAnIoErrorWhateverItsExtension) {
  TempDir tmp;
  for (const char* path : {"no_such_runSim", "gone.sim", "gone.txt"}) {
    const RunResult r = runSoftsub(std::string("info ") + path, tmp.path());
    EXPECT_EQ(r.code, 3) << path;
    expectContains(r.err, std::string("cannot read '") + path + "': No such file or directory");
  }
}

// `run` takes a scene under any name; `info` reads a scene named .xml too (it refused it).
TEST(Info, ASceneNamedXmlIsAScene) {
  TempDir tmp;
  fs::copy_file(examplesDir() / "two-fluids.scene", tmp / "shot.XML");
  const RunResult r = runSoftsub("info shot.XML", tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  expectContains(r.out, "scene shot:");
  expectContains(r.out, "fluids: 2");
}

TEST(Info, MissingOrBrokenFiles) {
  TempDir tmp;
  EXPECT_EQ(runSoftsub("info missing.sim", tmp.path()).code, 3);
  std::ofstream(tmp / "broken.sim") << "<Simulation";
  const RunResult broken = runSoftsub("info broken.sim", tmp.path());
  EXPECT_EQ(broken.code, 2) << broken.err;
  expectContains(broken.err, "broken.sim");
  std::ofstream(tmp / "broken.pdc") << "PDC";
  EXPECT_EQ(runSoftsub("info broken.pdc", tmp.path()).code, 2);
}

// pugixml stops at the root's end tag and dropped whatever followed it: a .sim file with
// junk after </Simulation> (text, a CDATA section, a processing instruction, a second
// declaration) read as a good frame. It is refused at its line, as the scene reader
// refuses the same after </Scene>; comments and white space stay fine in both.
TEST(Info, JunkAfterTheRootElementIsRefusedCommentsAndWhiteSpaceAreNot) {
  TempDir tmp;
  const std::string sim = readFile(runTwoFluids(tmp) / "two-fluids.0002.sim");
  const std::string scene = readFile(examplesDir() / "two-fluids.scene");
  const auto lineAfter = [](const std::string& text) {
    return std::to_string(1 + std::count(text.begin(), text.end(), '\n') + 1);
  };
  struct Case {
    std::string tail;
    std::string simProblem;
    std::string sceneProblem;
  };
  const std::vector<Case> junk = {
      {"\njunk\n", "Simulation: text outside the root element", "Scene: text outside the root element"},
      {"\n<!-- fine --> junk\n", "Simulation: text outside the root element",
       "Scene: text outside the root element"},
      {"\n&amp;\n", "Simulation: text outside the root element", "Scene: text outside the root element"},
      {"\n<![CDATA[x]]>\n", "Simulation: text outside the root element",
       "a CDATA section after the root element"},
      {"\n<?pi x?>\n", "Simulation: a processing instruction after the root element",
       "a processing instruction after the root element"},
      {"\n<?xml version=\"1.0\"?>\n", "Simulation: an XML declaration after the root element",
       "a processing instruction after the root element"},
  };
  for (const Case& c : junk) {
    std::ofstream(tmp / "junk.sim", std::ios::binary) << sim << c.tail;
    const RunResult r = runSoftsub("info junk.sim", tmp.path());
    EXPECT_EQ(r.code, 2) << c.tail << r.out;
    expectContains(r.err, "error: junk.sim:" + lineAfter(sim) + ": " + c.simProblem);
    EXPECT_TRUE(r.out.empty()) << r.out;
    std::ofstream(tmp / "junk.scene", std::ios::binary) << scene << c.tail;
    const RunResult s = runSoftsub("info junk.scene", tmp.path());
    EXPECT_EQ(s.code, 2) << c.tail << s.out;
    expectContains(s.err, "error: junk.scene:" + lineAfter(scene) + ": ");
    expectContains(s.err, c.sceneProblem);
  }
  std::ofstream(tmp / "fine.sim", std::ios::binary) << sim << "\n<!-- a comment -->\n  \n\t\n";
  const RunResult fine = runSoftsub("info fine.sim", tmp.path());
  EXPECT_EQ(fine.code, 0) << fine.err;
  expectContains(fine.out, "frame 2, time 0.0833333 s, 2 fluids, 1,728 particles");
  std::ofstream(tmp / "fine.scene", std::ios::binary) << scene << "\n<!-- a comment -->\n  \n\t\n";
  EXPECT_EQ(runSoftsub("info fine.scene", tmp.path()).code, 0);
}

}  // namespace
}  // namespace softsub::apptest
