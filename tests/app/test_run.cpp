// `softsub run` end to end: the files it writes, what they hold, determinism, formats,
// the seed's flags, and what it reports.
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "app_test_util.h"
#include "cache/sim_format.h"
#include "scene/reader.h"

namespace softsub::apptest {
namespace {

/// The files a run of `stem` with fluids `fluids` writes for frames 0..last at 24 fps.
std::vector<std::string> expectedFiles(const std::string& stem, const std::vector<std::string>& fluids,
                                       int last, bool sim = true, bool pdc = true, bool ply = true,
                                       const std::vector<std::string>& objects = {}) {
  std::vector<std::string> out;
  if (sim)  // each object's mesh, once
    for (const std::string& o : objects) out.push_back(fmt::format("{}Geo/{}.obj", stem, o));
  for (int f = 0; f <= last; ++f) {
    if (sim) out.push_back(fmt::format("{}.{:04}.sim", stem, f));
    if (ply) out.push_back(fmt::format("ply/{}.{:04}.ply", stem, f));
    if (pdc)
      for (const std::string& fluid : fluids) out.push_back(fmt::format("pdc/{}Shape.{}.pdc", fluid, f * 250));
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<std::string> fluidNames(const fs::path& scene) {
  std::vector<std::string> out;
  for (const auto& f : scene::readSceneFile(scene.string()).fluids) out.push_back(f.name);
  return out;
}

std::vector<std::string> objectNames(const fs::path& scene) {
  std::vector<std::string> out;
  for (const auto& o : scene::readSceneFile(scene.string()).objects) out.push_back(o.name);
  return out;
}

/// Every file of `a` equals the same file of `b`, byte for byte, and they list the same files.
void expectSameFiles(const fs::path& a, const fs::path& b) {
  const auto files = listFrameFiles(a);
  ASSERT_EQ(files, listFrameFiles(b));
  ASSERT_FALSE(files.empty());
  for (const std::string& f : files) EXPECT_TRUE(readFile(a / f) == readFile(b / f)) << f << " differs";
}

class Examples : public ::testing::TestWithParam<std::string> {};

std::string exampleTestName(const ::testing::TestParamInfo<std::string>& p) {
  std::string n = fs::path(p.param).stem().string();
  std::replace(n.begin(), n.end(), '-', '_');
  return n;
}

TEST_P(Examples, ThreeFramesWriteEveryFormatAndReadBack) {
  const fs::path scene = examplesDir() / GetParam();
  TempDir tmp;
  const fs::path out = tmp / "out";
  const RunResult r = runSoftsub("run --frames 3 --out " + quote(out) + " " + quote(scene), tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string stem = scene.stem().string();
  EXPECT_EQ(listFrameFiles(out), expectedFiles(stem, fluidNames(scene), 3, true, true, true, objectNames(scene)));
  const auto counts = fluidCounts(scene);
  for (int f = 0; f <= 3; ++f) {
    const cache::SimFile sim = cache::readSimFile(out / fmt::format("{}.{:04}.sim", stem, f));
    EXPECT_EQ(sim.frame.frame, f);
    EXPECT_NEAR(sim.frame.time, f / 24.0, 1e-9);
    ASSERT_EQ(sim.frame.fluids.size(), counts.size());
    for (std::size_t k = 0; k < counts.size(); ++k) EXPECT_EQ(sim.frame.fluids[k].count(), counts[k]);
    // Every object names its mesh, which is there.
    ASSERT_EQ(sim.frame.objects.size(), objectNames(scene).size());
    for (const ObjectSnapshot& o : sim.frame.objects) {
      EXPECT_EQ(o.filename, fmt::format("{}Geo/{}.obj", stem, o.name));
      EXPECT_TRUE(fs::is_regular_file(out / o.filename)) << o.filename;
    }
  }
  // Only --out was written: nothing beside the scene, nothing in the working folder.
  EXPECT_FALSE(fs::exists(scene.parent_path() / (stem + "Sim")));
  EXPECT_EQ(listEntries(tmp.path()), std::vector<std::string>{"out"});
}

TEST_P(Examples, RerunGivesByteIdenticalFiles) {
  const fs::path scene = examplesDir() / GetParam();
  TempDir tmp;
  for (const char* dir : {"a", "b"}) {
    const RunResult r = runSoftsub("run -q --frames 3 --out " + quote(tmp / dir) + " " + quote(scene), tmp.path());
    ASSERT_EQ(r.code, 0) << r.err;
  }
  expectSameFiles(tmp / "a", tmp / "b");
}

INSTANTIATE_TEST_SUITE_P(App, Examples,
                         ::testing::Values("softsub-demo.scene", "honey-drop.scene", "two-fluids.scene",
                                           "jelly-block.scene", "goo-torus.scene", "interactions.scene",
                                           "viscous-posts.scene", "wall-impact.scene", "box-on-jelly.scene",
                                           "crate-stack.scene", "crate-in-pool.scene"),
                         exampleTestName);

TEST(Run, EveryExampleIsCovered) {
  EXPECT_GE(exampleScenes().size(), 4u);
  for (const fs::path& p : exampleScenes()) {
    TempDir tmp;
    const RunResult r = runSoftsub("run -q --frames 1 --formats sim --out " + quote(tmp / "o") + " " + quote(p),
                                   tmp.path());
    EXPECT_EQ(r.code, 0) << p << "\n" << r.err;
    EXPECT_EQ(listFrameFiles(tmp / "o").size(), 2u + objectNames(p).size()) << p;
  }
}

TEST(Run, DefaultOutputFolderIsBesideTheScene) {
  TempDir tmp;
  fs::create_directory(tmp / "work");
  const fs::path scene = copyInto(examplesDir() / "two-fluids.scene", tmp.path());
  const RunResult r = runSoftsub("run -q --frames 2 " + quote(scene), tmp / "work");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(listFrameFiles(tmp / "two-fluidsSim"), expectedFiles("two-fluids", {"syrup", "oil"}, 2));
  EXPECT_TRUE(listEntries(tmp / "work").empty());
}

TEST(Run, FormatsSimWritesOnlySimFiles) {
  TempDir tmp;
  const RunResult r = runSoftsub(
      "run -q --frames 2 --formats sim --out " + quote(tmp / "o") + " " + quote(examplesDir() / "two-fluids.scene"),
      tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(listFrameFiles(tmp / "o"), expectedFiles("two-fluids", {}, 2, true, false, false));
  EXPECT_EQ(listEntries(tmp / "o").size(), 5u);  // no pdc/ or ply/ folder either (3 frames, manifest/, checkpoint/)
}

TEST(Run, FormatsPdcPlyAndNone) {
  TempDir tmp;
  const fs::path scene = examplesDir() / "two-fluids.scene";
  ASSERT_EQ(runSoftsub("run -q --frames 1 --formats pdc,ply --out " + quote(tmp / "o") + " " + quote(scene),
                       tmp.path()).code, 0);
  EXPECT_EQ(listFrameFiles(tmp / "o"), expectedFiles("two-fluids", {"syrup", "oil"}, 1, false, true, true));
  const RunResult none =
      runSoftsub("run --frames 1 --formats none --out " + quote(tmp / "n") + " " + quote(scene), tmp.path());
  EXPECT_EQ(none.code, 0) << none.err;
  EXPECT_FALSE(fs::exists(tmp / "n"));
  EXPECT_TRUE(none.err.empty()) << none.err;  // not a terminal: no summary
}

TEST(Run, OverridesChangeTheRun) {
  TempDir tmp;
  const fs::path scene = examplesDir() / "two-fluids.scene";
  const std::string base = "run -q --frames 2 --formats sim ";
  for (const char* v : {"explicit-euler", "symplectic-euler", "velocity-verlet"})
    ASSERT_EQ(runSoftsub(base + "--integrator " + v + " --out " + quote(tmp / v) + " " + quote(scene),
                         tmp.path()).code, 0) << v;
  ASSERT_EQ(runSoftsub(base + "--substeps 3 --out " + quote(tmp / "s3") + " " + quote(scene), tmp.path()).code, 0);
  const std::string last = "two-fluids.0002.sim";
  EXPECT_NE(readFile(tmp / "explicit-euler" / last), readFile(tmp / "velocity-verlet" / last));
  EXPECT_NE(readFile(tmp / "symplectic-euler" / last), readFile(tmp / "s3" / last));
}

TEST(Run, SeedFlagsBehaveAsDocumented) {
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "two-fluids.scene", tmp.path());
  // -f, -updateNum 2, -record 1, -stopRecordingAt 2: frames 0..2 beside the scene, the run ends at 2.
  const RunResult seed =
      runSoftsub("-f " + quote(scene) + " -updateNum 2 -record 1 -stopRecordingAt 2", tmp.path());
  ASSERT_EQ(seed.code, 0) << seed.err;
  EXPECT_EQ(listFrameFiles(tmp / "two-fluidsSim"), expectedFiles("two-fluids", {"syrup", "oil"}, 2));
  // Not a terminal: no progress, note or summary; warnings only (at 2 substeps the
  // stability estimate has one).
  std::istringstream lines(seed.err);
  for (std::string line; std::getline(lines, line);) EXPECT_EQ(line.rfind("warning: ", 0), 0u) << seed.err;
  // The same run spelled with softsub's own options gives the same bytes.
  const RunResult own =
      runSoftsub("run -q --substeps 2 --frames 2 --out " + quote(tmp / "ref") + " " + quote(scene), tmp.path());
  ASSERT_EQ(own.code, 0) << own.err;
  expectSameFiles(tmp / "two-fluidsSim", tmp / "ref");
}

TEST(Run, SeedRecordZeroWritesNothing) {
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "two-fluids.scene", tmp.path());
  const RunResult r = runSoftsub("-f " + quote(scene) + " -record 0 --frames 1", tmp.path());
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(listEntries(tmp.path()), std::vector<std::string>{"two-fluids.scene"});
}

TEST(Run, SeedStopRecordingAtMinusOneAndDrawPerFrame) {
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "two-fluids.scene", tmp.path());
  const RunResult r = runSoftsub(
      "-f " + quote(scene) + " -stopRecordingAt -1 -drawPerFrame 1 --frames 1 --formats sim", tmp.path());
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;  // the note is for a terminal (tests/app/test_terminal.cpp)
  EXPECT_EQ(listFrameFiles(tmp / "two-fluidsSim"), expectedFiles("two-fluids", {}, 1, true, false, false));
}

TEST(Run, StopRecordingAtBeyondTheLastFrameRunsTheScene) {
  TempDir tmp;
  const RunResult r = runSoftsub("run -q --frames 2 --stop-recording-at 10 --formats sim --out " +
                                     quote(tmp / "o") + " " + quote(examplesDir() / "two-fluids.scene"),
                                 tmp.path());
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(listFrameFiles(tmp / "o").size(), 3u);
  // The seed ran to -stopRecordingAt; here the scene's last frame comes first, which is
  // said (a seed scene, with no <Frames>, stopped at 120 of 300 without a word: a review).
  const RunResult said =
      runSoftsub("-f " + quote(examplesDir() / "two-fluids.scene") +
                     " --frames 2 -stopRecordingAt 10 --formats sim --out " + quote(tmp / "p"),
                 tmp.path());
  EXPECT_EQ(said.code, 0) << said.err;
  EXPECT_NE(said.err.find("warning: "), std::string::npos) << said.err;
  EXPECT_NE(said.err.find("--stop-recording-at 10 is past the run's last frame 2 (--frames)"),
            std::string::npos)
      << said.err;
  EXPECT_NE(said.err.find("give --frames 10"), std::string::npos) << said.err;
  const RunResult within =
      runSoftsub("-f " + quote(examplesDir() / "two-fluids.scene") +
                     " --frames 4 -stopRecordingAt 2 --formats sim --out " + quote(tmp / "q"),
                 tmp.path());
  EXPECT_EQ(within.code, 0) << within.err;
  EXPECT_TRUE(within.err.empty()) << within.err;
}

// Issue 2: "quiet when not a terminal or with --quiet". A pipe, a file or a farm log
// gets nothing but errors; the progress line and the summary are for a terminal.
TEST(Run, NothingButErrorsWhenNotATerminal) {
  TempDir tmp;
  const fs::path scene = examplesDir() / "two-fluids.scene";
  int i = 0;
  for (const char* options :
       {"--formats sim", "--formats none", "--formats sim -drawPerFrame 1", "--quiet"}) {
    const std::string out = quote(tmp / ("o" + std::to_string(i++)));
    const RunResult r = runSoftsub(
        "run --frames 2 " + std::string(options) + " --out " + out + " " + quote(scene), tmp.path());
    ASSERT_EQ(r.code, 0) << options << "\n" << r.err;
    EXPECT_TRUE(r.out.empty()) << options << "\n" << r.out;
    EXPECT_TRUE(r.err.empty()) << options << "\n" << r.err;
  }
  // The same output piped through a shell pipeline: still a pipe, still nothing.
  const std::string cmd = "cd " + quote(tmp.path()) + " && " + quote(SOFTSUB_BINARY) +
                          " run --frames 1 --out p " + quote(scene) + " 2>&1 </dev/null | wc -c";
  FILE* pipe = ::popen(cmd.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  char buf[64] = {};
  const std::size_t n = std::fread(buf, 1, sizeof buf - 1, pipe);
  EXPECT_EQ(::pclose(pipe), 0);
  EXPECT_EQ(std::stoi(std::string(buf, n)), 0) << "bytes written to the pipe";
  EXPECT_EQ(listFrameFiles(tmp / "p"), expectedFiles("two-fluids", {"syrup", "oil"}, 1));
}

// An object that moves more than its particles' diameter in a substep can pass through a
// plate one particle thick (contacts see overlaps, not paths): `run` says so once, with
// the substeps that would keep it to one diameter, unless --quiet; a slower one, and
// --adaptive (which keeps each move to a quarter of the contact reach), say nothing.
TEST(Run, AnObjectFasterThanAParticleASubstepIsWarnedAboutOnce) {
  TempDir tmp;
  const auto sceneOf = [](double speed) {
    return "<Scene version=\"1\"><Simulation><Frames>4</Frames><Substeps>8</Substeps></Simulation>"
           "<Environment><Width>10</Width><Height>60</Height><Depth>10</Depth></Environment>"
           "<Object><Name>plate</Name><Shape>box</Shape><Size>8 0.2 8</Size><ParticleSize>0.5</ParticleSize>"
           "<InitialPosition>0 5 0</InitialPosition><IsDynamic>false</IsDynamic></Object>"
           "<Object><Name>ball</Name><Shape>sphere</Shape><Size>1</Size><ParticleSize>0.25</ParticleSize>"
           "<InitialPosition>0 12 0</InitialPosition><InitialLinearVelocity>0 -" +
           std::to_string(speed) + " 0</InitialLinearVelocity></Object></Scene>";
  };
  std::ofstream(tmp / "fast.scene") << sceneOf(300);
  std::ofstream(tmp / "slow.scene") << sceneOf(20);
  // 300 units/s at 24 x 8 substeps a second: 1.5625 a substep, 6.25 diameters of 0.25.
  const RunResult fast = runSoftsub("run --formats none fast.scene", tmp.path());
  ASSERT_EQ(fast.code, 0) << fast.err;
  const std::string expected =
      "warning: fast.scene: object 'ball' moves up to 1.56 units a substep at frame 0, more than its particles' "
      "diameter 0.25: it can pass into or through thin parts of other objects; raise Substeps to 50 or use "
      "--adaptive\n";
  EXPECT_EQ(fast.err.rfind(expected, 0), 0U) << fast.err;  // the first line, whole
  EXPECT_EQ(fast.err.find("moves up to"), fast.err.rfind("moves up to")) << "warned more than once:\n" << fast.err;
  for (const char* args : {"run --formats none -q fast.scene", "run --formats none --adaptive fast.scene",
                           "run --formats none slow.scene"}) {
    const RunResult r = runSoftsub(args, tmp.path());
    ASSERT_EQ(r.code, 0) << args << "\n" << r.err;
    EXPECT_EQ(r.err.find("moves up to"), std::string::npos) << args << "\n" << r.err;
  }
}

TEST(Run, ZeroFramesWritesTheInitialState) {
  TempDir tmp;
  const RunResult r = runSoftsub("run -q --frames 0 --formats sim --out " + quote(tmp / "o") + " " +
                                     quote(examplesDir() / "jelly-block.scene"),
                                 tmp.path());
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(listFrameFiles(tmp / "o"), std::vector<std::string>{"jelly-block.0000.sim"});
}

// A fluid or object name becomes part of file names; the longest, a PDC file's temporary
// name, adds some 125 bytes. Names of 100 characters write every format; 101 are refused
// when the scene is read (235 once passed and failed at the first write, exit 3).
TEST(Run, NamesOfTheLongestAllowedLengthWriteEveryFormat) {
  TempDir tmp;
  const auto sceneOf = [](std::size_t length) {
    return "<Scene version=\"1\"><Simulation><Frames>1</Frames></Simulation><Environment/>"
           "<Fluid><Name>" + std::string(length, 'f') + "</Name><Particles>0 1 0  1 1 0</Particles></Fluid>"
           "<Object><Name>" + std::string(length, 'o') + "</Name><Shape>sphere</Shape><Size>1</Size>"
           "<InitialPosition>0 5 0</InitialPosition></Object></Scene>\n";
  };
  std::ofstream(tmp / "long.scene") << sceneOf(100);
  const RunResult r = runSoftsub("run --formats all,mesh,vdb --out o long.scene", tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(tmp / "o/pdc" / (std::string(100, 'f') + "Shape.250.pdc")));
  EXPECT_TRUE(fs::exists(tmp / "o/vdb" / (std::string(100, 'f') + ".0001.vdb")));
  EXPECT_TRUE(fs::exists(tmp / "o/longGeo" / (std::string(100, 'o') + ".obj")));
  for (const std::string which : {"fluid", "object"}) {
    std::string text = sceneOf(100);
    const char c = which == "fluid" ? 'f' : 'o';
    text.replace(text.find(std::string(100, c)), 100, std::string(101, c));
    std::ofstream(tmp / "longer.scene") << text;
    const RunResult refused = runSoftsub("run --formats all,mesh,vdb --out p longer.scene", tmp.path());
    EXPECT_EQ(refused.code, 2) << which << ": " << refused.err;
    EXPECT_NE(refused.err.find("longer.scene:1: "), std::string::npos) << refused.err;
    EXPECT_NE(refused.err.find("/Name: the name is 101 bytes long"), std::string::npos) << refused.err;
    EXPECT_FALSE(fs::exists(tmp / "p")) << which;
  }
}

// The scene's name (its file name without .scene) names every output file; a tab in it
// was refused as `<input>: scene name: ...`, without the file, once frame 0's folder was
// being made. The error names the scene file (control characters escaped) before anything
// is created; with nothing to write the name is no file's and the run goes on.
TEST(Run, AnOutputNameFromTheSceneFileNameIsRefusedNamingTheFile) {
  TempDir tmp;
  const std::string name = "a\tb.scene";
  fs::copy_file(examplesDir() / "two-fluids.scene", tmp / name);
  const std::string expected =
      "error: " + (tmp / "a\\tb.scene").string() + ": scene name: name 'a?b' cannot be used";
  for (const std::string formats : {"all", "sim", "mesh", "none --preview"}) {
    const RunResult r =
        runSoftsub("run --frames 1 --formats " + formats + " --out o " + quote(tmp / name), tmp.path());
    EXPECT_EQ(r.code, 2) << formats << ": " << r.err;
    EXPECT_EQ(r.err.rfind(expected, 0), 0u) << formats << ": " << r.err;
    EXPECT_FALSE(fs::exists(tmp / "o")) << formats;
  }
  const RunResult none = runSoftsub("run --frames 1 --formats none --out o " + quote(tmp / name), tmp.path());
  EXPECT_EQ(none.code, 0) << none.err;
  EXPECT_FALSE(fs::exists(tmp / "o"));
}

// The scene's name (the file's name without .scene) is capped as fluid and object names
// are: a 240-character one once wrote frame 0's PDC and then failed at the PLY file with
// "File name too long" (exit 3), leaving a partial folder.
TEST(Run, ASceneNameLongerThan100BytesIsRefusedBeforeAnythingIsWritten) {
  TempDir tmp;
  const std::string scene =
      "<Scene version=\"1\"><Simulation><Frames>1</Frames></Simulation><Environment/>"
      "<Fluid><Name>a</Name><Particles>0 1 0</Particles></Fluid></Scene>\n";
  std::ofstream(tmp / (std::string(100, 'L') + ".scene")) << scene;
  std::ofstream(tmp / (std::string(101, 'L') + ".scene")) << scene;
  const RunResult ok = runSoftsub("run --out o " + std::string(100, 'L') + ".scene", tmp.path());
  EXPECT_EQ(ok.code, 0) << ok.err;
  EXPECT_TRUE(fs::exists(tmp / "o/ply" / (std::string(100, 'L') + ".0001.ply")));
  const RunResult refused = runSoftsub("run --out p " + std::string(101, 'L') + ".scene", tmp.path());
  EXPECT_EQ(refused.code, 2) << refused.err;
  EXPECT_NE(refused.err.find("scene name: name '"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("is 101 bytes long"), std::string::npos) << refused.err;
  EXPECT_FALSE(fs::exists(tmp / "p"));
}

// A run writes each object's mesh to <out>/<scene>Geo/<object>.obj, the folder the docs
// suggest for input meshes: with --out the scene's own folder, a run once replaced the
// user's mesh with its export (comments, UVs and quads lost). Refused, whatever the
// path's spelling, before anything is written; another --out runs.
TEST(Run, ARunNeverWritesOverTheScenesInputMesh) {
  TempDir tmp;
  fs::create_directories(tmp / "shotGeo");
  const std::string mesh =
      "# the artist's crate\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
      "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  std::ofstream(tmp / "shotGeo/crate.obj") << mesh;
  std::ofstream(tmp / "shot.scene")
      << "<Scene version=\"1\"><Simulation><Frames>1</Frames></Simulation><Environment/>\n"
         "<Fluid><Name>a</Name><Particles>0 8 0</Particles></Fluid>\n"
         "<Object><Name>crate</Name><Geometry>shotGeo/crate.obj</Geometry>"
         "<InitialPosition>0 3 0</InitialPosition></Object></Scene>\n";
  for (const std::string& out : std::vector<std::string>{".", "./", quote(tmp.path())}) {
    const RunResult r = runSoftsub("run --out " + out + " shot.scene", tmp.path());
    EXPECT_EQ(r.code, 2) << out << ": " << r.err;
    EXPECT_NE(r.err.find("shot.scene:3: Object[1]/Geometry: the mesh"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("would write over"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(tmp / "shot.0000.sim")) << out;
    std::ifstream in(tmp / "shotGeo/crate.obj");
    const std::string kept((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(kept, mesh) << out;
  }
  // Without .sim frames no object mesh is written: nothing to refuse.
  EXPECT_EQ(runSoftsub("run --out . --formats pdc shot.scene", tmp.path()).code, 0);
  const RunResult elsewhere = runSoftsub("run --out o shot.scene", tmp.path());
  EXPECT_EQ(elsewhere.code, 0) << elsewhere.err;
  EXPECT_TRUE(fs::exists(tmp / "o/shotGeo/crate.obj"));
}

// --max-substeps is --adaptive's ceiling: alone it was silently ignored, and below the
// scene's Substeps it silently cut frames to fewer than the scene asks for. Both are
// refused before anything is written; a frame the ceiling holds back is warned about
// once (--adaptive turns the stability warning off, so nothing else would say so).
TEST(Run, MaxSubstepsIsCheckedAndAFrameItHoldsBackIsWarnedAbout) {
  TempDir tmp;
  std::ofstream(tmp / "fast.scene")
      << "<Scene version=\"1\"><Simulation><Frames>2</Frames><Substeps>8</Substeps></Simulation>"
         "<Environment><Height>100</Height></Environment><Fluid><Name>a</Name>"
         "<InitialSpeed>0 -500 0</InitialSpeed><Particles>0 50 0</Particles></Fluid></Scene>\n";
  const RunResult alone = runSoftsub("run fast.scene --max-substeps 20 --out o", tmp.path());
  EXPECT_EQ(alone.code, 2) << alone.err;
  EXPECT_NE(alone.err.find("--max-substeps requires --adaptive"), std::string::npos) << alone.err;
  const RunResult below = runSoftsub("run fast.scene --adaptive --max-substeps 7 --out o", tmp.path());
  EXPECT_EQ(below.code, 2) << below.err;
  EXPECT_NE(below.err.find("--max-substeps: 7 is below the scene's Substeps (8)"), std::string::npos)
      << below.err;
  EXPECT_FALSE(fs::exists(tmp / "o"));
  // 500 units/s at 24 frames a second and a quarter of the 1.5 interaction distance a
  // substep: 56 substeps a frame.
  const RunResult capped =
      runSoftsub("run fast.scene --adaptive --max-substeps 8 --formats none --stats", tmp.path());
  EXPECT_EQ(capped.code, 0) << capped.err;
  EXPECT_NE(capped.err.find("warning: fast.scene: frame 1 needed 56 substeps for --adaptive's limits, and "
                            "--max-substeps held it to 8"),
            std::string::npos)
      << capped.err;
  EXPECT_NE(capped.err.find("raise --max-substeps to 56"), std::string::npos) << capped.err;
  const RunResult free = runSoftsub("run fast.scene --adaptive --formats none", tmp.path());
  EXPECT_EQ(free.code, 0) << free.err;
  EXPECT_EQ(free.err.find("held it"), std::string::npos) << free.err;
}

// Errors showed a file name's control characters escaped, warnings raw: a scene named
// "x<newline>y.scene" split its stability warning over two lines.
TEST(Run, AWarningShowsTheSceneFileNameOnOneLine) {
  TempDir tmp;
  fs::copy_file(examplesDir() / "jelly-block.scene", tmp / "x\ny.scene");
  const RunResult r =
      runSoftsub("run --frames 1 --substeps 1 --formats none " + quote(tmp / "x\ny.scene"), tmp.path());
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("x\\ny.scene: the stability estimate calls"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("x\ny.scene"), std::string::npos) << r.err;
}

// Maya finds a PDC cache by its particle shape's name, which can hold no '-' and not
// start with a digit: a fluid named so gets a warning when its PDC files are written.
TEST(Run, AFluidNameNoMayaShapeCanTakeIsWarnedAboutForPdc) {
  TempDir tmp;
  std::ofstream(tmp / "m.scene")
      << "<Scene version=\"1\"><Simulation><Frames>1</Frames></Simulation><Environment/>"
         "<Fluid><Name>goo-1</Name><Particles>0 1 0</Particles></Fluid>"
         "<Fluid><Name>honey_2</Name><Particles>2 1 0</Particles></Fluid></Scene>\n";
  const RunResult pdc = runSoftsub("run m.scene --out o", tmp.path());
  EXPECT_EQ(pdc.code, 0) << pdc.err;
  EXPECT_NE(pdc.err.find("warning: m.scene: fluid 'goo-1': Maya node names cannot hold '-'"),
            std::string::npos)
      << pdc.err;
  EXPECT_EQ(pdc.err.find("'honey_2'"), std::string::npos) << pdc.err;
  const RunResult sim = runSoftsub("run m.scene --out p --formats sim", tmp.path());
  EXPECT_EQ(sim.code, 0) << sim.err;
  EXPECT_EQ(sim.err.find("Maya"), std::string::npos) << sim.err;
}

// PDC files, surfaces and grids are named after the fluid, not the scene: a second
// scene with a fluid of the same name, run into the same folder, replaced the first's
// PDC files without a word (and info then called both runs complete). Refused before
// anything is written; files named after the scene (.sim, .ply) may share a folder.
TEST(Run, ASecondSceneNeverWritesOverAnotherScenesFluidFiles) {
  TempDir tmp;
  fs::copy_file(examplesDir() / "two-fluids.scene", tmp / "a.scene");
  fs::copy_file(examplesDir() / "two-fluids.scene", tmp / "b.scene");
  ASSERT_EQ(runSoftsub("run -q a.scene --frames 1 --out o", tmp.path()).code, 0);
  const std::string before = readFile(tmp / "o/pdc/syrupShape.250.pdc");
  const RunResult r = runSoftsub("run b.scene --frames 1 --out o", tmp.path());
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(
      r.err.find("a file of scene 'a' (listed in manifest/a.0000.manifest), which this run of 'b' would "
                 "write over"),
      std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(tmp / "o/b.0000.sim"));
  EXPECT_EQ(readFile(tmp / "o/pdc/syrupShape.250.pdc"), before);
  EXPECT_EQ(runSoftsub("run -q b.scene --frames 1 --formats sim,ply --out o", tmp.path()).code, 0);
  EXPECT_EQ(runSoftsub("run -q a.scene --frames 1 --out o", tmp.path()).code, 0)
      << "a scene rewrites its own";
}

// A fresh run into a folder that holds an earlier run of the same scene: the earlier
// run's frames go with its manifests, so another frame rate's PDC ticks, a renamed
// fluid's files or frames past this run's end never mix with this run's (Maya and
// Houdini read a sequence by file name). Files the earlier manifests do not list, or
// list at another size (edited since), stay; --resume keeps everything.
TEST(Run, AFreshRunRemovesTheEarlierRunsFramesOnly) {
  TempDir tmp;
  const std::string scene =
      "<Scene version=\"1\"><Simulation><FramesPerSecond>{}</FramesPerSecond></Simulation><Environment/>\n"
      "<Fluid><Name>{}</Name><Particles>0 8 0  1 8 0</Particles></Fluid></Scene>\n";
  std::ofstream(tmp / "shot.scene") << fmt::format(fmt::runtime(scene), 24, "goo");
  ASSERT_EQ(runSoftsub("run -q shot.scene --frames 3 --out o", tmp.path()).code, 0);
  ASSERT_TRUE(fs::exists(tmp / "o/pdc/gooShape.750.pdc"));
  std::ofstream(tmp / "o/pdc/notes.txt") << "the artist's";
  std::ofstream(tmp / "o/ply/shot.0003.ply", std::ios::app) << "edited";  // another size now
  // 30 frames a second, a renamed fluid, fewer frames.
  std::ofstream(tmp / "shot.scene") << fmt::format(fmt::runtime(scene), 30, "jam");
  const RunResult r = runSoftsub("run -q shot.scene --frames 1 --out o", tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(listFiles(tmp / "o/pdc"),
            (std::vector<std::string>{"jamShape.0.pdc", "jamShape.200.pdc", "notes.txt"}));
  EXPECT_EQ(listFiles(tmp / "o/ply"),
            (std::vector<std::string>{"shot.0000.ply", "shot.0001.ply", "shot.0003.ply"}));
  EXPECT_FALSE(fs::exists(tmp / "o/shot.0002.sim"));
  EXPECT_FALSE(fs::exists(tmp / "o/shot.0003.sim"));
  EXPECT_EQ(readFile(tmp / "o/pdc/notes.txt"), "the artist's");
  // A format the fresh run does not write leaves no empty folder behind.
  ASSERT_EQ(runSoftsub("run -q shot.scene --frames 1 --formats sim,ply --out o", tmp.path()).code, 0);
  EXPECT_EQ(listFiles(tmp / "o/pdc"), (std::vector<std::string>{"notes.txt"}));
  ASSERT_EQ(runSoftsub("run -q shot.scene --frames 1 --formats sim,ply --out q", tmp.path()).code, 0);
  ASSERT_TRUE(fs::exists(tmp / "q/ply/shot.0001.ply"));
  ASSERT_EQ(runSoftsub("run -q shot.scene --frames 1 --formats pdc --out q", tmp.path()).code, 0);
  EXPECT_FALSE(fs::exists(tmp / "q/ply"));
  EXPECT_FALSE(fs::exists(tmp / "q/shot.0000.sim"));
  ASSERT_EQ(runSoftsub("run -q shot.scene --frames 1 --out o", tmp.path()).code, 0);
  // Resuming keeps the run's frames.
  ASSERT_EQ(runSoftsub("run -q shot.scene --frames 2 --out o --resume", tmp.path()).code, 0);
  EXPECT_TRUE(fs::exists(tmp / "o/shot.0001.sim"));
  EXPECT_TRUE(fs::exists(tmp / "o/pdc/jamShape.400.pdc"));
}

// A run killed while it wrote a frame left that frame's files and no manifest for it. A
// fresh, shorter run removes them as well: they are named as the last manifest's files
// with the next frame's number (PDC: ticks one step on) and were written after it. A
// file of that name older than the last manifest is not the killed run's and stays.
TEST(Run, AFreshRunRemovesTheFrameAKilledRunWasWriting) {
  TempDir tmp;
  std::ofstream(tmp / "shot.scene")
      << "<Scene version=\"1\"><Simulation><FramesPerSecond>30</FramesPerSecond></Simulation><Environment/>\n"
         "<Fluid><Name>goo</Name><Particles>0 8 0  1 8 0</Particles></Fluid></Scene>\n";
  ASSERT_EQ(runSoftsub("run -q shot.scene --frames 4 --formats sim,pdc,ply,mesh --out o", tmp.path()).code,
            0);
  // Killed before frame 4's manifest: its files are there, its manifest is not.
  fs::remove(tmp / "o/manifest/shot.0004.manifest");
  const std::vector<fs::path> frame4{"o/shot.0004.sim", "o/pdc/gooShape.800.pdc", "o/ply/shot.0004.ply",
                                     "o/mesh/goo.0004.obj"};
  for (const fs::path& f : frame4) ASSERT_TRUE(fs::exists(tmp / f)) << f;
  // One of them older than frame 3's manifest: not the killed run's.
  const auto old = fs::last_write_time(tmp / "o/manifest/shot.0003.manifest") - std::chrono::hours(1);
  fs::last_write_time(tmp / "o/ply/shot.0004.ply", old);
  ASSERT_EQ(runSoftsub("run -q shot.scene --frames 2 --formats sim,pdc,ply,mesh --out o", tmp.path()).code,
            0);
  EXPECT_FALSE(fs::exists(tmp / "o/shot.0004.sim"));
  EXPECT_FALSE(fs::exists(tmp / "o/pdc/gooShape.800.pdc"));
  EXPECT_FALSE(fs::exists(tmp / "o/mesh/goo.0004.obj"));
  EXPECT_TRUE(fs::exists(tmp / "o/ply/shot.0004.ply"));
  EXPECT_EQ(listFiles(tmp / "o/pdc"),
            (std::vector<std::string>{"gooShape.0.pdc", "gooShape.200.pdc", "gooShape.400.pdc"}));
}

// A scene kept in one of the run's frame folders could be named like a frame there.
TEST(Run, ASceneInsideTheRunsFrameFoldersIsRefused) {
  TempDir tmp;
  fs::create_directories(tmp / "o/pdc");
  const std::string text =
      "<Scene version=\"1\"><Environment/><Fluid><Name>w</Name><Particles>0 8 "
      "0</Particles></Fluid></Scene>\n";
  std::ofstream(tmp / "o/pdc/wShape.0.pdc") << text;
  const RunResult r = runSoftsub("run o/pdc/wShape.0.pdc --frames 1 --out o", tmp.path());
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("a folder this run writes its frames into"), std::string::npos) << r.err;
  EXPECT_EQ(readFile(tmp / "o/pdc/wShape.0.pdc"), text);
}

// Maya's PDC ticks are 32-bit: a run whose last PDC file would be named past them is
// refused before anything is written; without PDC files it runs.
TEST(Run, PdcTicksPastMayasThirtyTwoBitsAreRefused) {
  TempDir tmp;
  std::ofstream(tmp / "slow.scene")
      << "<Scene version=\"1\"><Simulation><FramesPerSecond>0.001</FramesPerSecond><Frames>400</Frames>"
         "</Simulation><Environment/><Fluid><Name>w</Name><Particles>0 8 0</Particles></Fluid></Scene>\n";
  const RunResult r = runSoftsub("run slow.scene --out o", tmp.path());
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("2400000000 ticks"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(tmp / "o"));
  EXPECT_EQ(runSoftsub("run -q slow.scene --out o --frames 357", tmp.path()).code, 0);  // 357,000,000 ticks
  const RunResult simOnly = runSoftsub("run -q slow.scene --out s --formats sim --frames 400", tmp.path());
  EXPECT_EQ(simOnly.code, 0) << simOnly.err;
}

}  // namespace
}  // namespace softsub::apptest
