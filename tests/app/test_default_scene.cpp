// The embedded default scene: what `run --print-scene` prints and what `run` with no
// scene simulates.
#include <fstream>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "app_test_util.h"
#include "cache/sim_format.h"
#include "scene/compile.h"
#include "scene/reader.h"

namespace softsub::apptest {
namespace {

TEST(DefaultScene, PrintSceneIsTheExampleFileAndParses) {
  TempDir tmp;
  const RunResult r = runSoftsub("run --print-scene", tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out, readFile(examplesDir() / "softsub-demo.scene"));
  EXPECT_NO_THROW((void)scene::readSceneText(r.out, "printed.scene"));
  EXPECT_TRUE(listEntries(tmp.path()).empty());
}

// `run SCENE --print-scene` printed the embedded default scene, SCENE ignored. It prints
// SCENE's own text, byte for byte, once SCENE reads as a valid scene; a bad or missing
// SCENE is refused as a run refuses it. Nothing is written.
TEST(DefaultScene, PrintSceneWithASceneIsThatScenesText) {
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "two-fluids.scene", tmp.path());
  for (const std::string& args :
       {"run " + quote(scene) + " --print-scene", "run --print-scene -f " + quote(scene),
        "run --print-scene --frames 2 " + quote(scene)}) {
    const RunResult r = runSoftsub(args, tmp.path());
    ASSERT_EQ(r.code, 0) << args << ": " << r.err;
    EXPECT_EQ(r.out, readFile(scene)) << args;
  }
  std::ofstream(tmp / "bad.scene")
      << "<Scene version=\"1\"><Simulation><Frames>-3</Frames></Simulation></Scene>\n";
  const RunResult bad = runSoftsub("run bad.scene --print-scene", tmp.path());
  EXPECT_EQ(bad.code, 2) << bad.err;
  EXPECT_EQ(bad.err.rfind("error: bad.scene:1: Simulation/Frames: -3 is out of range", 0), 0u) << bad.err;
  EXPECT_TRUE(bad.out.empty()) << bad.out;
  const RunResult missing = runSoftsub("run missing.scene --print-scene", tmp.path());
  EXPECT_EQ(missing.code, 3) << missing.err;
  EXPECT_TRUE(missing.out.empty()) << missing.out;
  EXPECT_EQ(listEntries(tmp.path()), (std::vector<std::string>{"bad.scene", "two-fluids.scene"}));
}

TEST(DefaultScene, TwoFluidsOfClearlyDifferentViscosityAboutTenThousandParticles) {
  TempDir tmp;
  const std::string text = runSoftsub("run --print-scene", tmp.path()).out;
  const scene::SceneDesc desc = scene::readSceneText(text, "softsub-demo.scene");
  ASSERT_EQ(desc.fluids.size(), 2u);
  const double v0 = desc.fluids[0].params.viscosity;
  const double v1 = desc.fluids[1].params.viscosity;
  EXPECT_GE(std::max(v0, v1), 5 * std::min(v0, v1)) << v0 << " vs " << v1;
  EXPECT_TRUE(desc.environment.has_value());  // a container
  EXPECT_EQ(desc.simulation.frames, 48);
  const scene::Compiled c = scene::compile(desc);
  EXPECT_GE(c.model.particleCount(), 9000u);
  EXPECT_LE(c.model.particleCount(), 11000u);
}

TEST(DefaultScene, RunWithoutSceneWritesSoftsubDemoSimInTheWorkingFolder) {
  TempDir tmp;
  const RunResult r = runSoftsub("run -q --frames 1 --formats sim", tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(listFrameFiles(tmp / "softsub-demoSim"),
            (std::vector<std::string>{"softsub-demo.0000.sim", "softsub-demo.0001.sim"}));
  const cache::SimFile sim = cache::readSimFile(tmp / "softsub-demoSim" / "softsub-demo.0001.sim");
  ASSERT_EQ(sim.frame.fluids.size(), 2u);
  EXPECT_EQ(sim.frame.fluids[0].count() + sim.frame.fluids[1].count(),
            scene::compile(scene::readSceneFile((examplesDir() / "softsub-demo.scene").string()))
                .model.particleCount());
}

TEST(DefaultScene, OutRedirectsTheDefaultScene) {
  TempDir tmp;
  const RunResult r = runSoftsub("run -q --frames 0 --out " + quote(tmp / "d"), tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_FALSE(fs::exists(tmp / "softsub-demoSim"));
  EXPECT_TRUE(fs::exists(tmp / "d" / "softsub-demo.0000.sim"));
  EXPECT_TRUE(fs::exists(tmp / "d" / "pdc" / "honeyShape.0.pdc"));
}

}  // namespace
}  // namespace softsub::apptest
