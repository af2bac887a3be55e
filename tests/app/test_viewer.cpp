// `softsub view --script` end to end, in a real window under Xvfb: a scripted parameter
// change, frames, a saved scene and a screenshot; playback of a recorded folder; scripts
// with a bad line or value refused with the script's file and line.
#include <array>
#include <cstdio>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "app_test_util.h"
#include "cache/folder_lock.h"
#include "cache/manifest.h"
#include "cache/sim_format.h"
#include "picture_checks.h"

namespace softsub::apptest {
namespace {

constexpr int kWidth = 900;
constexpr int kHeight = 600;

void writeText(const fs::path& p, const std::string& text) {
  std::FILE* f = std::fopen(p.c_str(), "wb");
  ASSERT_NE(f, nullptr) << p;
  std::fwrite(text.data(), 1, text.size(), f);
  std::fclose(f);
}

/// Skips the test when there is no xvfb-run (the install script installs it: CI runs these).
#define SKIP_WITHOUT_XVFB()                                                           \
  do {                                                                                \
    if (findProgram("xvfb-run").empty()) GTEST_SKIP() << "xvfb-run is not installed"; \
  } while (0)

/// `softsub view <input> --script <script> --width 900 --height 600 <options>` in a
/// virtual X server; killed after 60 s (a script without a working `quit` would hang). xvfb-run
/// itself sometimes fails around the viewer, and then the run is tried again: -a can lose
/// the race for a display number to a parallel test ("Xvfb failed to start"), and when
/// the viewer exits at once (a script refused on its first lines) xvfb-run's cleanup can
/// fail and replace the viewer's exit code with its own 5 (seen twice in full CI runs).
/// In the sanitizer build, LeakSanitizer's own tracer sometimes crashes (signal 11) while
/// it stops the viewer's threads at exit (the GL driver's and TBB's), and its "fatal
/// error" replaces the viewer's exit code with 1 (seen in a full CI run, and in one of
/// six runs of one test alone on a busy machine; none in 32 on an idle one). That is the
/// tool failing, not a leak, which it reports differently ("detected memory leaks"), so
/// the run is tried again as well.
RunResult view(const fs::path& input, const fs::path& script, const fs::path& cwd,
               const std::string& options = "") {
  const std::string command = fmt::format(
      "timeout -k 5 60 xvfb-run -a -s '-screen 0 1400x1000x24' {} view {} --script {} "
      "--width {} --height {} {}",
      quote(softsubBinary()), quote(input), quote(script), kWidth, kHeight, options);
  RunResult r;
  for (int attempt = 0; attempt < 3; ++attempt) {
    r = runCommand(command, cwd);
    if (r.err.find("Xvfb failed to start") == std::string::npos &&
        r.err.find("xvfb-run: error: problem while cleaning up") == std::string::npos &&
        r.err.find("LeakSanitizer has encountered a fatal error") == std::string::npos)
      break;
  }
  return r;
}

/// A scene's state after `frames` frames, simulated here the way the viewer does.
FrameSnapshot frameAfter(const scene::SceneDesc& desc, int frames) {
  scene::Compiled c = scene::compile(desc);
  solver::Simulation sim(c.model, std::move(c.state));
  for (int f = 0; f < frames; ++f) sim.advanceFrame();
  return sim.snapshot();
}

/// The screenshot is the window: its size, not blank, and each fluid of `frame` shows in
/// its colour where its particles' centroid projects through `camera`.
void expectScreenshotShows(const fs::path& png, const render::Camera& camera, const FrameSnapshot& frame) {
  ASSERT_TRUE(fs::is_regular_file(png)) << png;
  const render::Image im = readPng(png);
  EXPECT_EQ(im.width, kWidth);
  EXPECT_EQ(im.height, kHeight);
  EXPECT_GT(distinctColours(im), 500u) << "blank or nearly blank screenshot";
  EXPECT_GT(brightnessSpread(im), 10.0);
  const int half = std::max(2, static_cast<int>(largestPixelRadius(camera, frame, im.height)));
  for (const FluidSnapshot& f : frame.fluids) {
    SCOPED_TRACE(f.name);
    const auto px = render::projectToPixel(camera, centroid(f), im.width, im.height);
    ASSERT_TRUE(px);
    EXPECT_GE(shareShowing(im, (*px)[0], (*px)[1], half, f.colour), 0.5)
        << "fluid colour missing around its centroid's pixel " << (*px)[0] << ", " << (*px)[1];
    EXPECT_GT(shareShowing(im, f.colour) * im.width * im.height, 500.0);
  }
}

/// Runs `scene` for `frames` frames into `<dir>/<stem>Sim` (.sim only) and returns the folder.
fs::path recordFrames(const fs::path& scene, int frames, const fs::path& dir) {
  const fs::path recorded = dir / (scene.stem().string() + "Sim");
  const RunResult run = runSoftsub("run " + quote(scene) + " --frames " + std::to_string(frames) +
                                       " --formats sim -q --out " + quote(recorded),
                                   dir);
  EXPECT_EQ(run.code, 0) << run.err;
  return recorded;
}

// M (surfaces) on a scene whose particle size the surfaces' grid cannot take ended the
// viewer with "internal error" (exit 1): it now keeps drawing the particles and says why.
TEST(Viewer, KeyMOnAParticleSizeTooLargeForSurfacesSaysSoAndGoesOn) {
  SKIP_WITHOUT_XVFB();
  TempDir tmp;
  writeText(tmp / "huge.scene",
            "<Scene version=\"1\"><Simulation><Frames>2</Frames></Simulation><Fluid><Name>a</Name>"
            "<ParticleSize>3e38</ParticleSize><Particles>0 0 0  1e38 0 0</Particles></Fluid></Scene>\n");
  writeText(tmp / "s.txt", "key M\nframes 1\nquit\n");
  const RunResult r = view(tmp / "huge.scene", tmp / "s.txt", tmp.path());
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(
      r.err.find("error: no surfaces for this scene: surface: voxel size 1.5e+38 above the largest the grid "
                 "takes (allowed: voxel <= 1e+30)"),
      std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
}

// S into the folder of an earlier `run` of the same scene: that run's journal goes, as
// when `run` starts afresh. It used to stay, and `run --resume` took the viewer's tweaked
// frames for the earlier run's and continued them from the old run's checkpoint.
TEST(Viewer, KeySInAnEarlierRunsFolderRemovesThatRunsJournal) {
  SKIP_WITHOUT_XVFB();
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "honey-drop.scene", tmp.path());
  const fs::path out = tmp / "honey-dropSim";
  const RunResult first = runSoftsub("run " + quote(scene) + " --frames 3 --formats sim -q", tmp.path());
  ASSERT_EQ(first.code, 0) << first.err;
  ASSERT_FALSE(cache::manifestFrames(out, "honey-drop").empty());
  ASSERT_FALSE(cache::checkpointFrames(out, "honey-drop").empty());
  const fs::path script = tmp / "s.txt";
  writeText(script, "set fluid honey Viscosity 7.5\nframes 2\nkey S\nquit\n");
  const RunResult r = view(scene, script, tmp.path());
  ASSERT_EQ(r.code, 0) << r.err << r.out;
  EXPECT_TRUE(fs::is_regular_file(out / "honey-drop.0002.sim"));
  EXPECT_TRUE(cache::manifestFrames(out, "honey-drop").empty());
  EXPECT_TRUE(cache::checkpointFrames(out, "honey-drop").empty());
  // Nor their empty folders (a review), and info describes the viewer's frames.
  EXPECT_FALSE(fs::exists(out / "manifest"));
  EXPECT_FALSE(fs::exists(out / "checkpoint"));
  const RunResult info = runSoftsub("info " + quote(out), tmp.path());
  EXPECT_EQ(info.code, 0) << info.err;
  EXPECT_NE(info.out.find("frames of honey-drop in "), std::string::npos) << info.out;
  // So a resumed run starts over at frame 0 instead of mixing the two simulations.
  const RunResult resumed =
      runSoftsub("run " + quote(scene) + " --frames 4 --formats sim -q --resume", tmp.path());
  ASSERT_EQ(resumed.code, 0) << resumed.err;
  const RunResult clean = runSoftsub("run " + quote(scene) + " --frames 4 --formats sim -q --out clean", tmp.path());
  ASSERT_EQ(clean.code, 0) << clean.err;
  for (int f = 0; f <= 4; ++f) {
    const std::string name = fmt::format("honey-drop.{:04}.sim", f);
    EXPECT_EQ(readFile(out / name), readFile(tmp / "clean" / name)) << name;
  }
}

// S into a folder that a run is writing (its lock held: here by the test) is refused
// with the holder's name, and writes nothing there.
TEST(Viewer, KeySIntoAFolderARunIsWritingIsRefused) {
  SKIP_WITHOUT_XVFB();
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "honey-drop.scene", tmp.path());
  const fs::path out = tmp / "honey-dropSim";
  const cache::FolderLock held(out, "run", {"test", 0, "lock"}, "");
  const fs::path script = tmp / "s.txt";
  writeText(script, "frames 2\nkey S\nquit\n");
  const RunResult r = view(scene, script, tmp.path());
  EXPECT_NE(r.code, 0) << r.err << r.out;
  EXPECT_NE((r.err + r.out).find("is being written by another softsub process (softsub run, pid "),
            std::string::npos)
      << r.err << r.out;
  EXPECT_FALSE(fs::exists(out / "honey-drop.0000.sim"));
}

TEST(Viewer, AScriptTweaksAParameterStepsSavesAndTakesAScreenshot) {
  SKIP_WITHOUT_XVFB();
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "honey-drop.scene", tmp.path());
  const scene::SceneDesc original = scene::readSceneFile(scene.string());
  ASSERT_EQ(original.fluids.size(), 1u);
  const std::string fluid = original.fluids[0].name;
  const double viscosity = original.fluids[0].params.viscosity * 2 + 0.5;  // a new value
  const fs::path script = tmp / "tweak.txt";
  writeText(script, fmt::format("# thicker honey, three frames, keep both\n"
                                "set fluid {} Viscosity {}\n"
                                "frames 3\n"
                                "key S                 # the recorded frames 0..3 as caches\n"
                                "save tweaked.scene\n"
                                "screenshot shot.png   # the window, panel included\n"
                                "quit\n",
                                fluid, viscosity));
  const RunResult r = view(scene, script, tmp.path());
  ASSERT_EQ(r.code, 0) << r.err << r.out;

  // The saved scene is the original with the new viscosity, nothing else changed.
  ASSERT_TRUE(fs::is_regular_file(tmp / "tweaked.scene")) << r.err;
  const scene::SceneDesc saved = scene::readSceneFile((tmp / "tweaked.scene").string());
  scene::SceneDesc expected = original;
  expected.fluids[0].params.viscosity = viscosity;
  EXPECT_NE(saved.fluids.at(0).params.viscosity, original.fluids[0].params.viscosity);
  EXPECT_EQ(saved.fluids.at(0).params.viscosity, viscosity);
  EXPECT_TRUE(saved == expected) << "the saved scene differs from the original in more than the viscosity";
  EXPECT_EQ(saved.simulation, original.simulation);
  EXPECT_EQ(saved.camera, original.camera);
  EXPECT_EQ(saved.environment, original.environment);
  EXPECT_EQ(saved.interactions, original.interactions);

  // The screenshot shows the honey where the tweaked simulation has it after 3 frames,
  // seen from the scene's camera (no key moved it).
  expectScreenshotShows(tmp / "shot.png", cameraOf(original), frameAfter(expected, 3));
  // The original scene file is untouched.
  EXPECT_EQ(readFile(scene), readFile(examplesDir() / "honey-drop.scene"));

  // S wrote the recorded frames 0..3 into the default output folder; frame 3 holds the
  // tweaked simulation's positions exactly.
  const fs::path out = tmp / "honey-dropSim";
  for (int f = 0; f <= 3; ++f)
    EXPECT_TRUE(fs::is_regular_file(out / fmt::format("honey-drop.{:04}.sim", f))) << f;
  EXPECT_FALSE(fs::exists(out / "honey-drop.0004.sim"));
  const FrameSnapshot written = cache::readSimFile(out / "honey-drop.0003.sim").frame;
  const FrameSnapshot simulated = frameAfter(expected, 3);
  ASSERT_EQ(written.fluids.size(), 1u);
  EXPECT_EQ(written.fluids[0].positions, simulated.fluids.at(0).positions);
}

/// The frame files `<stem>.NNNN.sim` in `dir`, by frame number.
std::vector<int> simFrames(const fs::path& dir, const std::string& stem) {
  std::vector<int> frames;
  for (int f = 0; f < 100; ++f)
    if (fs::exists(dir / fmt::format("{}.{:04}.sim", stem, f))) frames.push_back(f);
  return frames;
}

// `key N` in a script steps exactly one frame, as pressing N does, wherever it stands in
// the script (it used to do nothing unless it was the script's last command), and pauses;
// `wait` only draws, playing or paused: while a script runs only `frames` and N simulate.
TEST(Viewer, ScriptedKeyNStepsExactlyOneFrame) {
  SKIP_WITHOUT_XVFB();
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "honey-drop.scene", tmp.path());
  const scene::SceneDesc desc = scene::readSceneFile(scene.string());
  const fs::path out = tmp / "honey-dropSim";
  struct Case {
    std::string script, options;
    std::vector<int> frames;  // the frames S writes
  };
  const Case cases[] = {
      {"frames 3\nkey N\nwait 3\nkey S\nquit\n", "", {0, 1, 2, 3, 4}},
      {"key N\nwait 5\nkey S\nquit\n", "--paused", {0, 1}},
      {"key N\nkey N\nkey S\nquit\n", "--paused", {0, 1, 2}},
      {"frames 1\nwait 4\nkey S\nquit\n", "", {0, 1}},  // playing: wait simulates nothing
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.script + c.options);
    fs::remove_all(out);
    writeText(tmp / "step.txt", c.script);
    const RunResult r = view(scene, tmp / "step.txt", tmp.path(), c.options);
    ASSERT_EQ(r.code, 0) << r.err << r.out;
    ASSERT_EQ(simFrames(out, "honey-drop"), c.frames) << r.err;
    // The last frame written is the simulation's after that many frames, exactly.
    const int last = c.frames.back();
    const FrameSnapshot written = cache::readSimFile(out / fmt::format("honey-drop.{:04}.sim", last)).frame;
    ASSERT_EQ(written.fluids.size(), 1u);
    EXPECT_EQ(written.fluids[0].positions, frameAfter(desc, last).fluids.at(0).positions);
  }
}

TEST(Viewer, AColourChangeShowsInTheNextScreenshot) {
  SKIP_WITHOUT_XVFB();
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "honey-drop.scene", tmp.path());
  const scene::SceneDesc original = scene::readSceneFile(scene.string());
  const std::string fluid = original.fluids.at(0).name;
  // The colour with the channels rotated: a clearly different hue from the scene's.
  const Vec3& c = original.fluids[0].colour;
  const std::array<float, 3> before{static_cast<float>(c.x()), static_cast<float>(c.y()),
                                    static_cast<float>(c.z())};
  const std::array<float, 3> after{before[2], before[0], before[1]};
  ASSERT_TRUE(distinguishable(before, after));
  writeText(tmp / "colour.txt", fmt::format("screenshot before.png\n"
                                            "set fluid {} Colour {} {} {}\n"
                                            "wait 1\n"
                                            "screenshot after.png\n"
                                            "quit\n",
                                            fluid, after[0], after[1], after[2]));
  const RunResult r = view(scene, tmp / "colour.txt", tmp.path());
  ASSERT_EQ(r.code, 0) << r.err << r.out;
  const render::Image a = readPng(tmp / "before.png"), b = readPng(tmp / "after.png");
  ASSERT_EQ(a.width, kWidth);
  ASSERT_EQ(b.width, kWidth);
  // Where the fluid is (no frame was simulated in between: `wait` only draws), the old
  // colour before and the new one after.
  const render::Camera camera = cameraOf(original);
  const FrameSnapshot frame = initialFrame(original);
  const auto px = render::projectToPixel(camera, centroid(frame.fluids.at(0)), kWidth, kHeight);
  ASSERT_TRUE(px);
  const int half = std::max(2, static_cast<int>(largestPixelRadius(camera, frame, kHeight)));
  EXPECT_GE(shareShowing(a, (*px)[0], (*px)[1], half, before), 0.5);
  EXPECT_LE(shareShowing(a, (*px)[0], (*px)[1], half, after), 0.05);
  EXPECT_GE(shareShowing(b, (*px)[0], (*px)[1], half, after), 0.5);
  EXPECT_LE(shareShowing(b, (*px)[0], (*px)[1], half, before), 0.05);
  // And over the whole window, the fluid's many particles in the new colour.
  EXPECT_GT(shareShowing(b, after) * b.width * b.height, 2000.0);
  EXPECT_GT(shareShowing(a, before) * a.width * a.height, 2000.0);
}

TEST(Viewer, MShowsSurfacesInsteadOfParticles) {
  // M toggles surfaces: the fluid still shows in its colour where it is, and the window
  // differs from the particles' (no frame is simulated in between: `wait` only draws).
  SKIP_WITHOUT_XVFB();
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "honey-drop.scene", tmp.path());
  writeText(tmp / "m.txt", "screenshot particles.png\nkey M\nwait 1\nscreenshot surface.png\nquit\n");
  const RunResult r = view(scene, tmp / "m.txt", tmp.path());
  ASSERT_EQ(r.code, 0) << r.err << r.out;
  const scene::SceneDesc desc = scene::readSceneFile(scene.string());
  expectScreenshotShows(tmp / "surface.png", cameraOf(desc), initialFrame(desc));
  EXPECT_GT(differingPixels(readPng(tmp / "surface.png"), readPng(tmp / "particles.png")),
            static_cast<std::size_t>(kWidth * kHeight / 200));
}

TEST(Viewer, PlaysBackARecordedFolder) {
  SKIP_WITHOUT_XVFB();
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "two-fluids.scene", tmp.path());
  const fs::path recorded = recordFrames(scene, 4, tmp.path());
  writeText(tmp / "play.txt", "frames 2\nscreenshot play.png\nquit\n");
  const RunResult r = view(recorded, tmp / "play.txt", tmp.path());
  ASSERT_EQ(r.code, 0) << r.err << r.out;
  // Two frames on from the first: the recording's frame 2, drawn with the scene's colours
  // from its camera.
  const scene::SceneDesc desc = scene::readSceneFile(scene.string());
  FrameSnapshot frame = cache::readSimFile(recorded / "two-fluids.0002.sim").frame;
  ASSERT_EQ(frame.fluids.size(), desc.fluids.size());
  for (std::size_t k = 0; k < frame.fluids.size(); ++k) {
    const Vec3& c = desc.fluids[k].colour;
    frame.fluids[k].colour = {static_cast<float>(c.x()), static_cast<float>(c.y()),
                              static_cast<float>(c.z())};
    frame.fluids[k].particleSize = static_cast<float>(desc.fluids[k].params.particleSize);
  }
  expectScreenshotShows(tmp / "play.png", cameraOf(desc), frame);
  // Playing back writes nothing into the recording.
  EXPECT_EQ(listFrameFiles(recorded).size(), 5u);
}

// Played away from its scene file, a recording is drawn grey at size 1 with no container,
// and frames without a manifest are left out: the viewer says so on stderr, as render and
// mesh do (it said nothing).
TEST(Viewer, PlayingARecordingAwayFromItsSceneWarns) {
  SKIP_WITHOUT_XVFB();
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "two-fluids.scene", tmp.path());
  const fs::path recorded = recordFrames(scene, 3, tmp.path());
  const fs::path moved = tmp / "elsewhere" / "two-fluidsSim";
  fs::create_directories(moved.parent_path());
  fs::rename(recorded, moved);
  fs::remove(moved / "manifest" / "two-fluids.0003.manifest");
  writeText(tmp / "play.txt", "frames 1\nquit\n");
  const RunResult r = view(moved, tmp / "play.txt", tmp.path());
  ASSERT_EQ(r.code, 0) << r.err << r.out;
  EXPECT_NE(
      r.err.find("warning: no usable scene file at " + (tmp / "elsewhere/two-fluids.scene").string() +
                 ": every fluid is drawn grey at ParticleSize 1, with no container (give the scene with a "
                 "copy of it beside the folder named two-fluids.scene)"),
      std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("warning: frames 3 to 3 of 'two-fluids' left out"), std::string::npos) << r.err;
}

TEST(Viewer, ARecordingRefusesParameterEdits) {
  SKIP_WITHOUT_XVFB();
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "honey-drop.scene", tmp.path());
  const fs::path recorded = recordFrames(scene, 1, tmp.path());
  const std::string fluid = scene::readSceneFile(scene.string()).fluids.at(0).name;
  writeText(tmp / "edit.txt",
            fmt::format("frames 1\nset fluid {} Viscosity 2\nsave never.scene\nquit\n", fluid));
  const RunResult r = view(recorded, tmp / "edit.txt", tmp.path());
  EXPECT_EQ(r.code, 2) << r.err << r.out;
  EXPECT_NE(r.err.find("edit.txt:2"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(tmp / "never.scene"));
}

// A scripted command whose file cannot be written exits 3, as docs/cli.md says, whichever
// command writes it (save and S exited 2, only screenshot 3); the commands after it do not
// run. Here a regular file stands where a folder should be.
TEST(Viewer, AScriptedWriteThatFailsExitsThree) {
  SKIP_WITHOUT_XVFB();
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "honey-drop.scene", tmp.path());
  writeText(tmp / "afile", "a file, not a folder\n");
  struct Case {
    std::string script, options, naming;
  };
  const Case cases[] = {
      {"save afile/x.scene\nsave never.scene\nquit\n", "", "afile/x.scene"},
      {"frames 1\nkey S\nsave never.scene\nquit\n", "--out afile/sub", "afile/sub"},
      {"screenshot afile/x.png\nsave never.scene\nquit\n", "", "afile/x.png"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.script);
    writeText(tmp / "write.txt", c.script);
    const RunResult r = view(scene, tmp / "write.txt", tmp.path(), c.options);
    EXPECT_EQ(r.code, 3) << r.err << r.out;
    EXPECT_NE(r.err.find("error: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(c.naming), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(tmp / "never.scene"));
  }
  // A command refused for another reason is still bad input: S on a recording.
  const fs::path recorded = recordFrames(scene, 1, tmp.path());
  writeText(tmp / "s.txt", "key S\nsave never.scene\nquit\n");
  const RunResult r = view(recorded, tmp / "s.txt", tmp.path());
  EXPECT_EQ(r.code, 2) << r.err << r.out;
  EXPECT_FALSE(fs::exists(tmp / "never.scene"));
}

// `--record 0` (the seed's -record 0) keeps nothing, so S writes nothing: not even frame
// 0, which it used to write, and no folder is made.
TEST(Viewer, RecordZeroKeepsNothingForS) {
  SKIP_WITHOUT_XVFB();
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "honey-drop.scene", tmp.path());
  writeText(tmp / "s.txt", "frames 2\nkey S\nquit\n");
  const RunResult r = view(scene, tmp / "s.txt", tmp.path(), "--record 0");
  ASSERT_EQ(r.code, 0) << r.err << r.out;
  EXPECT_FALSE(fs::exists(tmp / "honey-dropSim")) << r.err;
  EXPECT_NE(r.err.find("nothing written: --record 0 keeps no frames"), std::string::npos) << r.err;
  // --record 1, the default, keeps every frame.
  const RunResult kept = view(scene, tmp / "s.txt", tmp.path(), "--record 1");
  ASSERT_EQ(kept.code, 0) << kept.err << kept.out;
  EXPECT_EQ(simFrames(tmp / "honey-dropSim", "honey-drop"), (std::vector<int>{0, 1, 2})) << kept.err;
}

struct BadScript {
  std::string name;    ///< test name
  std::string text;    ///< the script; %FLUID% is the scene's fluid
  int line;            ///< the line the message must name
  std::string naming;  ///< also in the message
};

class ViewerRefusesScript : public ::testing::TestWithParam<BadScript> {};

TEST_P(ViewerRefusesScript, WithExitTwoNamingTheScriptAndLine) {
  SKIP_WITHOUT_XVFB();
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "honey-drop.scene", tmp.path());
  std::string text = GetParam().text;
  const std::string fluid = scene::readSceneFile(scene.string()).fluids.at(0).name;
  for (auto at = text.find("%FLUID%"); at != std::string::npos; at = text.find("%FLUID%"))
    text.replace(at, 7, fluid);
  const fs::path script = tmp / "bad-script.txt";
  writeText(script, text);
  const RunResult r = view(scene, script, tmp.path());
  EXPECT_EQ(r.code, 2) << r.err << r.out;
  EXPECT_NE(r.err.find(fmt::format("bad-script.txt:{}", GetParam().line)), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(GetParam().naming), std::string::npos) << r.err;
  // Nothing the script would have written after the failure is there.
  EXPECT_FALSE(fs::exists(tmp / "never.scene"));
}

INSTANTIATE_TEST_SUITE_P(
    Bad, ViewerRefusesScript,
    ::testing::Values(
        BadScript{"UnknownCommand", "# comment\nframes 1\nfrobnicate 3\nsave never.scene\nquit\n", 3,
                  "frobnicate"},
        BadScript{"UnknownKey", "key F13\nsave never.scene\nquit\n", 1, "F13"},
        BadScript{"ViscosityNotANumber",
                  "frames 1\n\nset fluid %FLUID% Viscosity thick\nsave never.scene\nquit\n", 3, "Viscosity"},
        BadScript{"ColourOutOfRange", "set fluid %FLUID% Colour 2 0 0\nsave never.scene\nquit\n", 1,
                  "Colour"},
        BadScript{"UnknownTag", "set fluid %FLUID% Stickiness 3\nsave never.scene\nquit\n", 1, "Stickiness"},
        BadScript{"UnknownFluid", "frames 1\nset fluid no-such-fluid Viscosity 2\nsave never.scene\nquit\n",
                  2, "no-such-fluid"},
        BadScript{"FramesNotACount", "frames many\nsave never.scene\nquit\n", 1, "frames"},
        // A value in range on its own that the scene's rules refuse (MinimumForce above
        // MaximumForce) was said without the script's file and line (a review).
        BadScript{"MinimumForceAboveMaximum",
                  "frames 1\nset fluid %FLUID% MinimumForce 5000\nsave never.scene\nquit\n", 2,
                  "the edit is refused"}),
    [](const auto& p) { return p.param.name; });

}  // namespace
}  // namespace softsub::apptest

namespace softsub::apptest {
namespace {

// A recording plays as it was simulated: --substeps and --max-particles are refused with
// one (exit 2, naming the option) before a window is opened, rather than ignored.
TEST(Viewer, SimulationOptionsWithARecordingAreRefused) {
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "honey-drop.scene", tmp.path());
  const fs::path recorded = recordFrames(scene, 1, tmp.path());
  for (const std::string option : {"--substeps 4", "--max-particles 100000"}) {
    const RunResult r = runCommand(fmt::format("env -u DISPLAY -u WAYLAND_DISPLAY {} view {} {}",
                                               quote(softsubBinary()), quote(recorded), option),
                                   tmp.path());
    EXPECT_EQ(r.code, 2) << option << ": " << r.err;
    EXPECT_EQ(
        r.err.rfind("error: command line: " + option.substr(0, option.find(' ')) + ": is for a scene", 0), 0u)
        << r.err;
  }
}

// S writes caches named after the scene (and its fluids and objects), P screenshots: a
// scene file named with a tab got as far as S, which failed as `<input>: scene name: ...`.
// The names are checked as run checks them, before the window opens (no display needed),
// and the error names the scene file.
TEST(Viewer, ASceneNameThatCannotBeAFileNameIsRefusedBeforeTheWindowOpens) {
  TempDir tmp;
  const std::string name = "a\tb.scene";
  fs::copy_file(examplesDir() / "honey-drop.scene", tmp / name);
  const RunResult r = runCommand(
      fmt::format("env -u DISPLAY -u WAYLAND_DISPLAY {} view {}", quote(softsubBinary()), quote(tmp / name)),
      tmp.path());
  EXPECT_EQ(r.code, 2) << r.err;
  const std::string expected =
      "error: " + (tmp / "a\\tb.scene").string() + ": scene name: name 'a?b' cannot be used";
  EXPECT_EQ(r.err.rfind(expected, 0), 0u) << r.err;
}

// Without a display the window cannot open: an I/O failure (exit 3) that says what to do
// instead, and the script's outputs are not written.
TEST(Viewer, WithoutADisplayExitsThreeAndPointsToRender) {
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "honey-drop.scene", tmp.path());
  {
    std::FILE* f = std::fopen((tmp / "s.txt").c_str(), "wb");
    ASSERT_NE(f, nullptr);
    std::fputs("save out.scene\nquit\n", f);
    std::fclose(f);
  }
  const RunResult r = runCommand(fmt::format("env -u DISPLAY -u WAYLAND_DISPLAY {} view {} --script s.txt",
                                             quote(softsubBinary()), quote(scene)),
                                 tmp.path());
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("cannot open a window"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("softsub render"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(tmp / "out.scene"));
}

}  // namespace
}  // namespace softsub::apptest
