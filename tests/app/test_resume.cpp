// No frame lost, exact resume (issue #7): manifests mark complete frames, `run --resume`
// reproduces an uninterrupted run byte for byte after a stop, a kill at any moment or a
// full disk, and a run with other settings is never resumed.
#include <signal.h>
#include <sys/wait.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <thread>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "app_test_util.h"
#include "cache/atomic_file.h"
#include "cache/manifest.h"
#include "cache/pdc_format.h"
#include "cache/ply_format.h"
#include "cache/sim_format.h"

namespace softsub::apptest {
namespace {

using Tree = std::map<std::string, std::string>;

/// Every file under `dir` with its bytes.
Tree treeOf(const fs::path& dir) {
  Tree t;
  for (const std::string& f : listFiles(dir)) t[f] = readFile(dir / f);
  return t;
}

/// The files of `a` and `b` that differ or exist in one only (empty when equal).
std::vector<std::string> differences(const Tree& a, const Tree& b) {
  std::vector<std::string> d;
  for (const auto& [name, bytes] : a) {
    const auto it = b.find(name);
    if (it == b.end()) d.push_back("only in the first: " + name);
    else if (it->second != bytes) d.push_back("differs: " + name);
  }
  for (const auto& [name, bytes] : b)
    if (!a.contains(name)) d.push_back("only in the second: " + name);
  return d;
}

bool hasTemporaries(const fs::path& dir) {
  for (const std::string& f : listFiles(dir))
    if (fs::path(f).filename().string().find(".tmp.") != std::string::npos) return true;
  return false;
}

std::string scenePath(const std::string& name) { return quote(examplesDir() / name); }

/// Checks every frame that has a manifest: complete, and each listed file reads back
/// whole with finite values. Returns how many frames were checked.
int checkCompleteFrames(const fs::path& out, const std::string& scene) {
  int checked = 0;
  for (const std::int64_t f : cache::manifestFrames(out, scene)) {
    const fs::path mp = cache::manifestPath(out, scene, f);
    const cache::Manifest m = cache::decodeManifest(readFile(mp), mp.string());
    EXPECT_EQ(m.frame, f);
    EXPECT_EQ(cache::incompleteReason(out, m, false), "") << mp;
    for (const cache::ManifestEntry& e : m.files) {
      const fs::path p = out / e.path;
      if (p.extension() == ".sim") {
        const cache::SimFile sim = cache::readSimFile(p);
        EXPECT_EQ(sim.frame.frame, f) << p;
        for (const FluidSnapshot& fluid : sim.frame.fluids)
          for (const float x : fluid.positions) EXPECT_TRUE(std::isfinite(x)) << p;
      } else if (p.extension() == ".pdc") {
        EXPECT_GT(cache::readPdcFile(p).count, 0) << p;
      } else if (p.extension() == ".ply") {
        const cache::PlyCloud ply = cache::readPlyFile(p);
        EXPECT_TRUE(ply.hasFrame && ply.frame == f) << p;
        EXPECT_GT(ply.vertexCount, 0u) << p;
      }
    }
    ++checked;
  }
  return checked;
}

TEST(Resume, AfterAShorterRunTheOutputsAreByteIdenticalWithBodiesAndAdaptiveSubsteps) {
  for (const std::string options : {"", " --adaptive --checkpoint-every 3 --integrator velocity-verlet"}) {
    TempDir tmp;
    const std::string base = "run -q " + scenePath("box-on-jelly.scene") + options;
    ASSERT_EQ(runSoftsub(base + " --frames 10 --out ref", tmp.path()).code, 0);
    ASSERT_EQ(runSoftsub(base + " --frames 4 --out part", tmp.path()).code, 0);
    const RunResult r = runSoftsub(base + " --frames 10 --resume --out part", tmp.path());
    ASSERT_EQ(r.code, 0) << r.err;
    const Tree ref = treeOf(tmp / "ref");
    EXPECT_EQ(differences(ref, treeOf(tmp / "part")), std::vector<std::string>{}) << options;
    EXPECT_TRUE(ref.contains("manifest/box-on-jelly.0010.manifest"));
    EXPECT_EQ(ref.contains("checkpoint/box-on-jelly.0010.state"), options.empty()) << "every frame's by default";
    EXPECT_EQ(ref.contains("checkpoint/box-on-jelly.0009.state"), true) << "a multiple of 3 and of 1";
    EXPECT_EQ(checkCompleteFrames(tmp / "ref", "box-on-jelly"), 11);
    // A finished run resumed again has nothing to do and changes nothing.
    ASSERT_EQ(runSoftsub(base + " --frames 10 --resume --out part", tmp.path()).code, 0);
    EXPECT_EQ(differences(ref, treeOf(tmp / "part")), std::vector<std::string>{});
  }
}

TEST(Resume, KilledAtRandomMomentsEveryFinishedFrameIsValidAndResumeMatches) {
  TempDir tmp;
  const std::vector<std::string> args = {"run",      (examplesDir() / "softsub-demo.scene").string(),
                                         "--frames", "24",
                                         "--out"};
  const auto start = std::chrono::steady_clock::now();
  {
    std::vector<std::string> a = args;
    a.push_back((tmp / "ref").string());
    const int pid = spawnSoftsub(a, tmp / "err");
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << readFile(tmp / "err");
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const Tree ref = treeOf(tmp / "ref");
  std::mt19937 rng(20261122);
  std::uniform_real_distribution<double> when(0.0, 1.1 * seconds);
  int kills = 0, midWrite = 0, beforeAnyFrame = 0;
  // At least 20 kills, and on until one has landed in the middle of a write (a
  // temporary file on disk). A kill at a random moment lands there with a chance of
  // about 1 in 5 in a release build, but far less under the sanitizers, whose
  // simulation is slowed more than its writes (once 0 in 80). So every fourth kill
  // waits for a temporary file to appear instead, then freezes the process at once.
  for (int attempt = 0; attempt < 80 && (kills < 20 || midWrite == 0); ++attempt) {
    const fs::path out = tmp / fmt::format("k{}", attempt);
    std::vector<std::string> a = args;
    a.push_back(out.string());
    const auto launched = std::chrono::steady_clock::now();
    const int pid = spawnSoftsub(a, tmp / "err");
    ASSERT_GT(pid, 0);
    const double wait = when(rng);
    // Read while the process writes: a file renamed away mid-listing may throw.
    const auto sawTemporary = [&out] {
      try {
        return hasTemporaries(out);
      } catch (const fs::filesystem_error&) {
        return false;
      }
    };
    if (attempt % 4 == 3) {
      while (!sawTemporary() &&
             std::chrono::duration<double>(std::chrono::steady_clock::now() - launched).count() < 1.1 * seconds) {
      }
    } else {
      std::this_thread::sleep_for(std::chrono::duration<double>(wait));
    }
    // Frozen first, so what is on disk is what the kill leaves.
    ::kill(pid, SIGSTOP);
    const bool tmpOnDisk = hasTemporaries(out);
    ::kill(pid, SIGKILL);
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    ++kills;
    midWrite += tmpOnDisk ? 1 : 0;
    const int complete = checkCompleteFrames(out, "softsub-demo");
    beforeAnyFrame += complete == 0 ? 1 : 0;
    const RunResult r = runSoftsub("run -q " + scenePath("softsub-demo.scene") + " --frames 24 --resume --out " +
                                       quote(out),
                                   tmp.path());
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_FALSE(hasTemporaries(out)) << "stale temporaries are removed";
    ASSERT_EQ(differences(ref, treeOf(out)), std::vector<std::string>{})
        << "kill " << kills << " after " << complete << " complete frames";
    fs::remove_all(out);
  }
  EXPECT_GE(kills, 20);
  EXPECT_GT(midWrite, 0) << "no kill landed in the middle of a write";
  ::testing::Test::RecordProperty("kills", kills);
  ::testing::Test::RecordProperty("mid_write", midWrite);
  std::printf("%d kills, %d in the middle of a write, %d before the first frame was complete\n", kills, midWrite,
              beforeAnyFrame);
}

TEST(Resume, AFolderOfARunWithOtherSettingsIsRefusedAndLeftAlone) {
  TempDir tmp;
  const std::string base = "run -q " + scenePath("two-fluids.scene") + " --frames 3 --out o";
  ASSERT_EQ(runSoftsub(base, tmp.path()).code, 0);
  // A killed run's leftover (a dead process on this host): a refused resume leaves it too.
  const fs::path leftover = tmp / "o" / fmt::format(".two-fluids.0004.sim.tmp.{}.999999999.0", cache::hostTag());
  std::ofstream(leftover) << "half";
  const Tree before = treeOf(tmp / "o");
  for (const std::string other : {" --substeps 9", " --formats sim,pdc", " --integrator explicit-euler",
                                  " --adaptive", " --speed-limit 5"}) {
    const RunResult r = runSoftsub(base + " --resume" + other, tmp.path());
    EXPECT_EQ(r.code, 2) << other << "\n" << r.err;
    EXPECT_NE(r.err.find("other settings"), std::string::npos) << r.err;
    EXPECT_EQ(differences(before, treeOf(tmp / "o")), std::vector<std::string>{}) << other;
  }
  // The thread count is not a setting: results do not depend on it. That run removes the
  // leftover.
  EXPECT_EQ(runSoftsub("--threads 1 " + base + " --resume", tmp.path()).code, 0);
  EXPECT_FALSE(fs::exists(leftover));
  // More frames than before extend the run.
  EXPECT_EQ(runSoftsub("run -q " + scenePath("two-fluids.scene") + " --frames 5 --out o --resume", tmp.path()).code,
            0);
  ASSERT_EQ(runSoftsub("run -q " + scenePath("two-fluids.scene") + " --frames 5 --out ref", tmp.path()).code, 0);
  EXPECT_EQ(differences(treeOf(tmp / "ref"), treeOf(tmp / "o")), std::vector<std::string>{});
  // Nothing to resume without outputs.
  const RunResult none = runSoftsub(base + " --resume --formats none", tmp.path());
  EXPECT_EQ(none.code, 2);
  EXPECT_NE(none.err.find("--resume"), std::string::npos) << none.err;
}

// --stop-recording-at only ends a batch run, as --frames does: it is not a setting. It was
// part of the fingerprint, so a run it ended could never be extended (every --resume was
// refused as "other settings"), and a value past the scene's end changed every manifest.
TEST(Resume, StopRecordingAtEndsARunThatCanBeExtendedAndPastTheEndChangesNothing) {
  TempDir tmp;
  const std::string base = "run -q " + scenePath("two-fluids.scene");
  ASSERT_EQ(runSoftsub(base + " --frames 6 --out ref", tmp.path()).code, 0);
  ASSERT_EQ(runSoftsub(base + " --frames 6 --stop-recording-at 2 --out o", tmp.path()).code, 0);
  EXPECT_EQ(cache::manifestFrames(tmp / "o", "two-fluids"), (std::vector<std::int64_t>{0, 1, 2}));
  const RunResult more = runSoftsub(base + " --frames 6 --stop-recording-at 4 --resume --out o", tmp.path());
  ASSERT_EQ(more.code, 0) << more.err;
  EXPECT_EQ(cache::manifestFrames(tmp / "o", "two-fluids").back(), 4);
  const RunResult rest = runSoftsub(base + " --frames 6 --resume --out o", tmp.path());
  ASSERT_EQ(rest.code, 0) << rest.err;
  const Tree ref = treeOf(tmp / "ref");
  EXPECT_EQ(differences(ref, treeOf(tmp / "o")), std::vector<std::string>{});
  // Past the last frame: the same files as without it, and resumable without it.
  ASSERT_EQ(runSoftsub(base + " --frames 6 --stop-recording-at 100 --out past", tmp.path()).code, 0);
  EXPECT_EQ(differences(ref, treeOf(tmp / "past")), std::vector<std::string>{});
}

// A run that writes nothing (--formats none, -record 0) has nothing to resume and makes
// nothing to resume from: --resume with it is a usage error of the command line, refused
// before the scene is read (a missing scene was exit 3, "cannot read"), and nothing on
// disk changes.
TEST(Resume, WithoutOutputsIsACommandLineErrorBeforeTheSceneIsRead) {
  TempDir tmp;
  const std::string base = "run -q " + scenePath("two-fluids.scene") + " --frames 1 --out o";
  ASSERT_EQ(runSoftsub(base, tmp.path()).code, 0);
  const Tree before = treeOf(tmp / "o");
  for (const std::string nothing : {" --formats none", " -record 0", " --record 0 --formats sim"}) {
    for (const std::string& scene : {scenePath("two-fluids.scene"), std::string("missing.scene")}) {
      const RunResult r = runSoftsub("run " + scene + nothing + " --resume --out o", tmp.path());
      EXPECT_EQ(r.code, 2) << nothing << " " << scene << ": " << r.err;
      EXPECT_EQ(r.err.rfind(
                    "error: command line: --resume: there is nothing to resume: this run writes no files", 0),
                0u)
          << r.err;
      EXPECT_EQ(differences(before, treeOf(tmp / "o")), std::vector<std::string>{}) << nothing;
    }
  }
  EXPECT_EQ(listEntries(tmp.path()), std::vector<std::string>{"o"});
}

TEST(Resume, AnEditedObjectMeshIsAnotherSetting) {
  TempDir tmp;
  const fs::path good = fs::path(SOFTSUB_SOURCE_DIR) / "tests/data/scenes/good";
  fs::copy(good / "objects.scene", tmp / "objects.scene");
  fs::copy(good / "cubeGeo", tmp / "cubeGeo", fs::copy_options::recursive);
  const std::string base = "run -q objects.scene --frames 2 --out o";
  ASSERT_EQ(runSoftsub(base, tmp.path()).code, 0);
  // The same cube, 10% larger: the scene's text is unchanged, its object is not.
  std::string obj = readFile(tmp / "cubeGeo" / "cube.obj"), scaled;
  std::istringstream lines(obj);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("v ", 0) == 0) {
      std::istringstream v(line.substr(2));
      double x, y, z;
      v >> x >> y >> z;
      line = fmt::format("v {} {} {}", 1.1 * x, 1.1 * y, 1.1 * z);
    }
    scaled += line + "\n";
  }
  std::ofstream(tmp / "cubeGeo" / "cube.obj") << scaled;
  const Tree before = treeOf(tmp / "o");
  const RunResult r = runSoftsub(base + " --resume", tmp.path());
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("other settings"), std::string::npos) << r.err;
  EXPECT_EQ(differences(before, treeOf(tmp / "o")), std::vector<std::string>{});
}

TEST(Resume, NothingToResumeStartsAtFrameZeroAndAFreshRunForgetsTheOldOne) {
  TempDir tmp;
  const std::string base = "run -q " + scenePath("honey-drop.scene");
  ASSERT_EQ(runSoftsub(base + " --frames 4 --out ref", tmp.path()).code, 0);
  ASSERT_EQ(runSoftsub(base + " --frames 4 --out o --resume", tmp.path()).code, 0);
  EXPECT_EQ(differences(treeOf(tmp / "ref"), treeOf(tmp / "o")), std::vector<std::string>{});
  // A fresh, shorter run into the same folder: the old run's manifests and checkpoints go.
  ASSERT_EQ(runSoftsub(base + " --frames 2 --substeps 9 --out o", tmp.path()).code, 0);
  EXPECT_EQ(cache::manifestFrames(tmp / "o", "honey-drop"), (std::vector<std::int64_t>{0, 1, 2}));
  EXPECT_EQ(cache::checkpointFrames(tmp / "o", "honey-drop"), (std::vector<std::int64_t>{1, 2})) << "the two newest";
  // --checkpoint-every 0: manifests, no checkpoint; resume then starts over.
  ASSERT_EQ(runSoftsub(base + " --frames 2 --checkpoint-every 0 --out n", tmp.path()).code, 0);
  EXPECT_EQ(cache::manifestFrames(tmp / "n", "honey-drop").size(), 3u);
  EXPECT_TRUE(cache::checkpointFrames(tmp / "n", "honey-drop").empty());
}

TEST(Resume, InfoTellsWhichFramesAreCompleteAndWhereResumeContinues) {
  TempDir tmp;
  ASSERT_EQ(runSoftsub("run -q " + scenePath("two-fluids.scene") + " --frames 3 --out o", tmp.path()).code, 0);
  RunResult r = runSoftsub("info o", tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("run two-fluids in o: frames 0..3 complete, 8 substeps a frame"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("checkpoints: 2, 3"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("would continue after frame 3"), std::string::npos) << r.out;
  r = runSoftsub("info o/manifest/two-fluids.0001.manifest", tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("frame 1, 8 substeps"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(": complete"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("two-fluids.0001.sim"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("removed since"), std::string::npos) << "frame 1's checkpoint was pruned\n" << r.out;
  r = runSoftsub("info o/checkpoint/two-fluids.0003.state", tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("frame 3, "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("intact"), std::string::npos) << r.out;
  // A lost file makes its frame and every later one incomplete; the checkpoints are
  // then past the complete frames, so a resume starts over.
  fs::remove(tmp / "o" / "two-fluids.0002.sim");
  r = runSoftsub("info o", tmp.path());
  EXPECT_NE(r.out.find("frames 0..1 complete"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("then: frame 2: 'two-fluids.0002.sim' is missing"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("would start over at frame 0"), std::string::npos) << r.out;
  // A damaged checkpoint is refused by info as by --resume.
  std::string state = readFile(tmp / "o" / "checkpoint" / "two-fluids.0003.state");
  state[state.size() / 2] ^= 1;
  std::ofstream(tmp / "o" / "checkpoint" / "two-fluids.0003.state", std::ios::binary) << state;
  r = runSoftsub("info o/checkpoint/two-fluids.0003.state", tmp.path());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("checksum"), std::string::npos) << r.err;
  EXPECT_EQ(runSoftsub("info " + quote(tmp.path()), tmp.path()).code, 2) << "not a run's folder";
}

// A checkpoint copied in from a run with other settings (same scene and particles,
// another --substeps) is skipped by --resume, which then continued after frame 2;
// info said "after frame 3". Both now go by the manifest's settings.
TEST(Resume, InfoSkipsACheckpointOfAnotherRunAsResumeDoes) {
  TempDir tmp;
  const std::string run = "run -q " + scenePath("two-fluids.scene");
  ASSERT_EQ(runSoftsub(run + " --frames 3 --out o", tmp.path()).code, 0);
  ASSERT_EQ(runSoftsub(run + " --frames 3 --substeps 9 --out other", tmp.path()).code, 0);
  fs::copy_file(tmp / "other/checkpoint/two-fluids.0003.state", tmp / "o/checkpoint/two-fluids.0003.state",
                fs::copy_options::overwrite_existing);
  const RunResult info = runSoftsub("info o", tmp.path());
  ASSERT_EQ(info.code, 0) << info.err;
  EXPECT_NE(info.out.find("made by another run (other settings): skipped"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("would continue after frame 2"), std::string::npos) << info.out;
  const RunResult resumed = runSoftsub(run + " --frames 4 --resume --out o", tmp.path());
  EXPECT_EQ(resumed.code, 0) << resumed.err;
  EXPECT_TRUE(fs::exists(tmp / "o/manifest/two-fluids.0004.manifest"));
}

TEST(Resume, AFullDiskIsAnIoErrorWithEarlierFramesCompleteAndResumeFinishesTheRun) {
  TempDir tmp;
  const std::string base = "run -q " + scenePath("two-fluids.scene") + " --frames 8";
  ASSERT_EQ(runSoftsub(base + " --out ref", tmp.path()).code, 0);
  const Tree ref = treeOf(tmp / "ref");
  std::size_t total = 0;
  for (const auto& [name, bytes] : ref) total += bytes.size();
  // The disk fills up about halfway through the run.
  const std::string env = fmt::format(
      "LD_PRELOAD={} SOFTSUB_TEST_DISK_BYTES={} ASAN_OPTIONS=${{ASAN_OPTIONS:+$ASAN_OPTIONS:}}"
      "verify_asan_link_order=0 ",
      quote(FULL_DISK_SHIM), total / 2);
  const RunResult r = runCommand(env + quote(softsubBinary()) + " " + base + " --out full", tmp.path());
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_EQ(r.err.rfind("error: cannot write '", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << r.err;
  EXPECT_FALSE(hasTemporaries(tmp / "full")) << "the failed write's temporary file is removed";
  const int complete = checkCompleteFrames(tmp / "full", "two-fluids");
  EXPECT_GE(complete, 2);
  EXPECT_LE(complete, 7);
  // Space again: the run resumes and ends as if nothing had happened.
  ASSERT_EQ(runSoftsub(base + " --out full --resume", tmp.path()).code, 0);
  EXPECT_EQ(differences(ref, treeOf(tmp / "full")), std::vector<std::string>{});
}

TEST(Resume, AFileSizeLimitIsAnIoErrorNotACrash) {
  TempDir tmp;
  // ulimit -f: files of at most 8 blocks (4 or 8 KiB); SIGXFSZ would kill an unprepared process.
  const RunResult r = runCommand(
      "ulimit -f 8 && " + quote(softsubBinary()) + " run -q " + scenePath("two-fluids.scene") + " --frames 2 --out o",
      tmp.path());
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("File too large"), std::string::npos) << r.err;
  EXPECT_FALSE(hasTemporaries(tmp / "o"));
  EXPECT_TRUE(cache::manifestFrames(tmp / "o", "two-fluids").empty()) << "no frame is marked complete";
}

TEST(BlowUpCheck, TheSpeedLimitStopsARunAtItsSubstepWithEarlierFramesComplete) {
  TempDir tmp;
  // The demo's fastest particle covers about 0.06 interaction distances a substep by
  // frame 24: a limit of 0.01 is crossed a few frames in.
  const RunResult r =
      runSoftsub("run -q " + scenePath("softsub-demo.scene") + " --frames 24 --speed-limit 0.01 --out o", tmp.path());
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_NE(r.err.find(", substep "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("particle id "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("speed is "), std::string::npos) << r.err;
  const auto frames = cache::manifestFrames(tmp / "o", "softsub-demo");
  ASSERT_FALSE(frames.empty());
  EXPECT_LT(frames.back(), 24);
  EXPECT_NE(r.err.find(fmt::format("frames 0..{} are complete", frames.back())), std::string::npos) << r.err;
  EXPECT_EQ(checkCompleteFrames(tmp / "o", "softsub-demo"), static_cast<int>(frames.size()));
}

}  // namespace
}  // namespace softsub::apptest

namespace softsub::apptest {
namespace {

// A second run started into a folder a run is writing (a farm task re-queued while its
// first attempt still runs) is refused with exit code 2, naming the first run, and
// changes nothing; so is a `mesh` of that folder. The first run is not disturbed, and
// once it has stopped the folder takes a run again. (A review: the second run's fresh
// start deleted the first run's files, which then failed with exit code 3 or ended
// with success over files no longer its own.)
TEST(Resume, ASecondRunIntoAFolderBeingWrittenIsRefused) {
  TempDir tmp;
  const fs::path out = tmp / "shot";
  const int pid = spawnSoftsub({"run", (examplesDir() / "softsub-demo.scene").string(), "--frames", "100000",
                                "--formats", "sim", "--out", out.string()},
                               tmp / "err");
  ASSERT_GT(pid, 0);
  // Until its frame 1 is complete: the lock is taken before frame 0.
  const auto launched = std::chrono::steady_clock::now();
  while (!fs::exists(out / "manifest" / "softsub-demo.0001.manifest") &&
         std::chrono::steady_clock::now() - launched < std::chrono::seconds(60))
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_TRUE(fs::exists(out / "manifest" / "softsub-demo.0001.manifest")) << readFile(tmp / "err");
  const RunResult second =
      runSoftsub("run " + scenePath("softsub-demo.scene") + " --frames 3 --out " + quote(out), tmp.path());
  EXPECT_EQ(second.code, 2) << second.err;
  EXPECT_NE(second.err.find("is being written by another softsub process (softsub run, pid " +
                            std::to_string(pid) + " on host "),
            std::string::npos)
      << second.err;
  // It wrote nothing: its formats (sim, pdc, ply) would have made pdc/ and ply/.
  EXPECT_FALSE(fs::exists(out / "pdc"));
  EXPECT_FALSE(fs::exists(out / "ply"));
  const RunResult mesh = runSoftsub("mesh " + quote(out), tmp.path());
  EXPECT_EQ(mesh.code, 2) << mesh.err;
  EXPECT_NE(mesh.err.find("SIMDIR: '"), std::string::npos) << mesh.err;
  EXPECT_FALSE(fs::exists(out / "mesh"));
  // info names the writer.
  const RunResult info = runSoftsub("info " + quote(out), tmp.path());
  EXPECT_NE(info.out.find("being written now by softsub run, pid " + std::to_string(pid)), std::string::npos)
      << info.out;
  // The first run is still going and still has its frame 0.
  EXPECT_TRUE(fs::exists(out / "softsub-demo.0000.sim"));
  ::kill(pid, SIGINT);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status)) << status;
  EXPECT_EQ(WEXITSTATUS(status), 130) << readFile(tmp / "err");
  EXPECT_FALSE(fs::exists(out / ".softsub.lock")) << "the run removes its lock file";
  const RunResult after = runSoftsub(
      "run -q " + scenePath("softsub-demo.scene") + " --frames 2 --formats sim --out " + quote(out),
      tmp.path());
  EXPECT_EQ(after.code, 0) << after.err;
  EXPECT_EQ(checkCompleteFrames(out, "softsub-demo"), 3);
}

}  // namespace
}  // namespace softsub::apptest
