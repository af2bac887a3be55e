// Stopping a run: Ctrl-C / SIGTERM finish the current frame (exit 130), and a blow-up
// stops with exit 4, the earlier frames intact.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <fstream>
#include <functional>
#include <thread>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "app_test_util.h"
#include "cache/sim_format.h"

namespace softsub::apptest {
namespace {

class Interrupt : public ::testing::TestWithParam<int> {};

// Waits (up to `limit`) until ready(), sends `sig` to `pid` and waits for it: it must
// exit by itself with code 130, not be ended by the signal.
void signalAndExpect130(pid_t pid, int sig, const std::function<bool()>& ready, std::chrono::seconds limit,
                        std::chrono::microseconds poll) {
  const auto deadline = std::chrono::steady_clock::now() + limit;
  while (!ready() && std::chrono::steady_clock::now() < deadline) std::this_thread::sleep_for(poll);
  ASSERT_EQ(::kill(pid, sig), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 130);
}

TEST_P(Interrupt, FinishesTheCurrentFrameAndExits130) {
  const int sig = GetParam();
  TempDir tmp;
  const fs::path out = tmp / "o";
  const pid_t pid = spawnSoftsub({"run", "--frames", "100000", "--formats", "sim,pdc", "--out", out.string(),
                                  (examplesDir() / "jelly-block.scene").string()},
                                 tmp / "err");
  ASSERT_GT(pid, 0);
  // Once a few frames are out, so that the signal lands in the middle of the run.
  signalAndExpect130(
      pid, sig, [&] { return fs::exists(out / "jelly-block.0003.sim"); }, std::chrono::seconds(120),
      std::chrono::milliseconds(20));
  if (HasFatalFailure()) return;

  const std::string err = readFile(tmp / "err");
  const std::string tail = " is the last complete frame";
  const auto at = err.find(tail);
  ASSERT_NE(at, std::string::npos) << err;
  const auto start = err.rfind("frame ", at);
  ASSERT_NE(start, std::string::npos) << err;
  const int last = std::stoi(err.substr(start + 6, at - start - 6));
  EXPECT_NE(err.find(sig == SIGINT ? "SIGINT" : "SIGTERM"), std::string::npos) << err;
  EXPECT_GE(last, 3);
  // Frames 0..last are complete and readable; nothing after them, no temporary files.
  std::vector<std::string> expected;
  for (int f = 0; f <= last; ++f) {
    expected.push_back(fmt::format("jelly-block.{:04}.sim", f));
    expected.push_back(fmt::format("pdc/jellyShape.{}.pdc", f * 250));
  }
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(listFrameFiles(out), expected);
  EXPECT_EQ(cache::readSimFile(out / fmt::format("jelly-block.{:04}.sim", last)).frame.frame, last);
}

// Whether process `pid` has installed a handler for `sig` (SigCgt in /proc/PID/status).
bool catches(pid_t pid, int sig) {
  std::ifstream status(fmt::format("/proc/{}/status", pid));
  for (std::string line; std::getline(status, line);)
    if (line.rfind("SigCgt:", 0) == 0) return (std::stoull(line.substr(7), nullptr, 16) >> (sig - 1)) & 1u;
  return false;
}

// A stop asked for while the scene is still being read (a large one: 300,000 particles
// written out) ends the run the same way, exit 130, before any frame is written; it
// used to kill the process, whose handlers came only after the scene.
TEST_P(Interrupt, WhileTheSceneLoadsExits130WithNothingWritten) {
  const int sig = GetParam();
  TempDir tmp;
  {
    std::ofstream scene(tmp / "big.scene");
    scene << "<Scene "
             "version=\"1\">\n<Simulation><Frames>3</Frames></Simulation>\n<Fluid><Name>goo</"
             "Name><Particles>\n";
    for (int i = 0; i < 300000; ++i)
      scene << fmt::format("{} {} {}\n", (i % 100) * 0.1, (i / 100 % 100) * 0.1, (i / 10000) * 0.1);
    scene << "</Particles></Fluid>\n</Scene>\n";
  }
  const fs::path out = tmp / "o";
  const pid_t pid = spawnSoftsub(
      {"run", "--formats", "sim", "--out", out.string(), (tmp / "big.scene").string()}, tmp / "err");
  ASSERT_GT(pid, 0);
  // As soon as its handler is in place: while the scene is still being read.
  signalAndExpect130(
      pid, sig, [&] { return catches(pid, sig); }, std::chrono::seconds(60), std::chrono::microseconds(200));
  if (HasFatalFailure()) return;
  const std::string err = readFile(tmp / "err");
  EXPECT_NE(err.find(fmt::format("interrupted by {} before the first frame was complete",
                                 sig == SIGINT ? "SIGINT" : "SIGTERM")),
            std::string::npos)
      << err;
  EXPECT_FALSE(fs::exists(out / "big.0000.sim"));
  // render too: no folder, no picture.
  const fs::path pictures = tmp / "pictures";
  const pid_t drawing =
      spawnSoftsub({"render", "--out", pictures.string(), (tmp / "big.scene").string()}, tmp / "err2");
  ASSERT_GT(drawing, 0);
  signalAndExpect130(
      drawing, sig, [&] { return catches(drawing, sig); }, std::chrono::seconds(60),
      std::chrono::microseconds(200));
  if (HasFatalFailure()) return;
  EXPECT_NE(readFile(tmp / "err2").find("interrupted before the first picture (nothing written)"),
            std::string::npos)
      << readFile(tmp / "err2");
  EXPECT_FALSE(fs::exists(pictures));
}

std::string signalName(const ::testing::TestParamInfo<int>& p) {
  return p.param == SIGINT ? "SIGINT" : "SIGTERM";
}

INSTANTIATE_TEST_SUITE_P(App, Interrupt, ::testing::Values(SIGINT, SIGTERM), signalName);

TEST(BlowUp, ExitsFourNamingTheFrameAndKeepsEarlierFrames) {
  TempDir tmp;
  // A repulsion at the edge of single precision (the most a scene may hold): the forces
  // of three close neighbours add up beyond it, so the first step is non-finite.
  std::ofstream(tmp / "blow.scene") << R"(<Scene version="1">
  <Simulation><Frames>5</Frames></Simulation>
  <Fluid><Name>unstable</Name><Particles>0 0 0  0.05 0 0  0.1 0 0  0.15 0 0</Particles></Fluid>
  <Interactions>
    <Pair><A>unstable</A><B>unstable</B>
      <Linear><AtZero>3.4e38</AtZero><Cutoff>1</Cutoff><Min>0</Min><Max>3.4e38</Max></Linear></Pair>
  </Interactions>
</Scene>
)";
  const RunResult r = runSoftsub("run blow.scene --formats sim", tmp.path());
  EXPECT_EQ(r.code, 4) << r.err;
  // The stability estimate's warning first (it calls this scene unstable), then the error.
  ASSERT_NE(r.err.find("warning: blow.scene: the stability estimate calls unstable / unstable unstable"),
            std::string::npos)
      << r.err;
  const std::string error = r.err.substr(r.err.find("\nerror: ") + 1);
  EXPECT_NE(error.find("frame 1"), std::string::npos) << r.err;
  EXPECT_NE(error.find("fluid 'unstable'"), std::string::npos) << r.err;
  EXPECT_NE(error.find("frames 0..0 are complete"), std::string::npos) << r.err;
  // Frame 0 is complete (its manifest and checkpoint too); nothing of frame 1 is there.
  EXPECT_EQ(listFiles(tmp / "blowSim"), (std::vector<std::string>{"blow.0000.sim", "checkpoint/blow.0000.state",
                                                                  "manifest/blow.0000.manifest"}));
  EXPECT_NE(error.find("raise Substeps or use --adaptive"), std::string::npos) << r.err;
  // At the most substeps a frame can have, only a higher frame rate shortens the step.
  const RunResult most = runSoftsub("run blow.scene --formats none --substeps 10000", tmp.path());
  EXPECT_EQ(most.code, 4) << most.err;
  EXPECT_NE(most.err.find("raise FramesPerSecond: the 10000 substeps a frame are the most there can be"),
            std::string::npos)
      << most.err;
  EXPECT_EQ(most.err.find("raise Substeps"), std::string::npos) << most.err;
}

}  // namespace
}  // namespace softsub::apptest
