// `softsub run` at a terminal (a pseudo-terminal made by the test): the progress line
// redrawn in place, the summary at the end, and silence with --quiet. The other tests
// run softsub with its output in files, where it prints nothing but errors.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "app_test_util.h"

namespace softsub::apptest {
namespace {

TEST(Terminal, RunDrawsARedrawnProgressLineAndASummary) {
  TempDir tmp;
  const fs::path scene = examplesDir() / "two-fluids.scene";
  const RunResult r = runSoftsubInTerminal(
      "run --frames 3 --formats sim -drawPerFrame 1 --out " + quote(tmp / "o") + " " + quote(scene),
      tmp.path());
  ASSERT_EQ(r.code, 0) << r.out;
  const std::string& t = r.out;
  // Every draw starts with \r and rewrites the line in place; frame 0 is drawn before it
  // is written (it can take long) and once written, the first frame simulated is always
  // drawn, and so is the last.
  const std::size_t zero = t.find("\rframe 0/3 | 1,728 particles | writing frame 0");
  ASSERT_NE(zero, std::string::npos) << t;
  EXPECT_NE(t.find("\rframe 0/3 | 1,728 particles | simulating", zero), std::string::npos) << t;
  const std::size_t first = t.find("\rframe 1/3 | 1,728 particles | ");
  ASSERT_NE(first, std::string::npos) << t;
  const std::size_t last = t.find("\rframe 3/3 | 1,728 particles | ");
  ASSERT_NE(last, std::string::npos) << t;
  EXPECT_LT(first, last);
  EXPECT_NE(t.find(" ms/frame | ETA ", first), std::string::npos) << t;
  EXPECT_NE(t.find(" ms/frame | ETA 0:00", last), std::string::npos) << t;  // nothing left
  // The line is ended before the summary, which comes last.
  const std::size_t done = t.find("\r\ndone: 3 frames, 1,728 particles, ");
  ASSERT_NE(done, std::string::npos) << t;
  EXPECT_LT(zero, first);
  EXPECT_LT(last, done);
  // The summary's time a frame is its total over the frames simulated (frame 0's writing
  // included): a 1M-particle surface run's summary left frame 0 out (a review).
  double total = 0, perFrame = 0;
  ASSERT_EQ(std::sscanf(t.c_str() + done, "\r\ndone: 3 frames, 1,728 particles, %lf s (%lf ms/frame)", &total,
                        &perFrame),
            2)
      << t.substr(done);
  // (the total is printed to 0.01 s: within 5 ms of it, so 5 / 3 ms a frame)
  EXPECT_NEAR(perFrame, total / 3 * 1000, 0.05 + 5.0 / 3) << t.substr(done);
  EXPECT_NE(t.find(" ms/frame), output: " + (tmp / "o").string() + "/\r\n", done), std::string::npos) << t;
  EXPECT_NE(t.find("note: -drawPerFrame applies to the viewer"), std::string::npos) << t;
  EXPECT_EQ(listFrameFiles(tmp / "o").size(), 4u);
}

// render of a scene over a range of frames: the frames simulated on the way say so, and
// the count, rate and ETA are the pictures' (frames only simulated made the ETA a
// fraction of the time left: a review).
TEST(Terminal, RenderOfASceneCountsThePicturesOfItsRange) {
  TempDir tmp;
  const RunResult r =
      runSoftsubInTerminal("render " + quote(examplesDir() / "two-fluids.scene") +
                               " --frames 2:3 --width 64 --height 36 --out " + quote(tmp / "p"),
                           tmp.path());
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("\rframe 0/3 | 1,728 particles | simulating to frame 2"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\rframe 2/3 (1 of 2) | 1,728 particles | "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\rframe 3/3 (2 of 2) | 1,728 particles | "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("done: 2 pictures written to "), std::string::npos) << r.out;
}

// render of a recorded folder at a terminal: the progress runs to the last frame of the
// range drawn, with the recording's particles (it showed "frame 0/11 | 0 particles" and
// was never redrawn: a review).
TEST(Terminal, RenderOfARecordingDrawsItsProgressToTheRangesLastFrame) {
  TempDir tmp;
  ASSERT_EQ(runSoftsub("run -q --frames 6 --formats sim --out " + quote(tmp / "o") + " " +
                           quote(examplesDir() / "two-fluids.scene"),
                       tmp.path())
                .code,
            0);
  const RunResult r = runSoftsubInTerminal(
      "render " + quote(tmp / "o") + " --frames 0:3 --width 64 --height 36 --out " + quote(tmp / "p"),
      tmp.path());
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("\rframe 0/3 (1 of 4) | 1,728 particles | "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\rframe 3/3 (4 of 4) | 1,728 particles | "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(" ms/frame | ETA 0:00"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("/6 |"), std::string::npos) << r.out;
}

// The viewer's stability hint as a warning (a scene that would gain energy without ever
// tripping the blow-up check ran silently): the example's jelly at ten times its
// viscosity is called unstable at its 24 substeps; the example itself, and --adaptive
// (which takes the estimate's count), get no warning.
TEST(Terminal, RunWarnsWhenTheStabilityEstimateCallsTheSceneUnstable) {
  TempDir tmp;
  std::string text = readFile(examplesDir() / "jelly-block.scene");
  const std::string viscosity = "<Viscosity>15</Viscosity>";
  ASSERT_NE(text.find(viscosity), std::string::npos);
  text.replace(text.find(viscosity), viscosity.size(), "<Viscosity>150</Viscosity>");
  {
    std::ofstream(tmp / "stiff.scene") << text;
  }
  const RunResult stiff = runSoftsubInTerminal("run --frames 0 --formats none stiff.scene", tmp.path());
  ASSERT_EQ(stiff.code, 0) << stiff.out;
  EXPECT_NE(stiff.out.find("warning: stiff.scene: the stability estimate calls jelly / jelly unstable at 24 substeps "
                           "a frame"),
            std::string::npos)
      << stiff.out;
  EXPECT_NE(stiff.out.find("raise Substeps to "), std::string::npos) << stiff.out;
  // A warning is about the run's result, not progress: a pipe or a farm log gets it too,
  // and only --quiet leaves it out.
  const RunResult piped = runSoftsub("run --frames 0 --formats none stiff.scene", tmp.path());
  ASSERT_EQ(piped.code, 0) << piped.err;
  EXPECT_EQ(piped.err.rfind("warning: stiff.scene: the stability estimate calls jelly / jelly unstable", 0), 0u)
      << piped.err;
  EXPECT_EQ(piped.err.find("note:"), std::string::npos) << piped.err;
  const RunResult quiet = runSoftsub("run -q --frames 0 --formats none stiff.scene", tmp.path());
  EXPECT_TRUE(quiet.err.empty()) << quiet.err;
  const RunResult adaptive =
      runSoftsubInTerminal("run --frames 0 --formats none --adaptive stiff.scene", tmp.path());
  EXPECT_EQ(adaptive.out.find("stability estimate"), std::string::npos) << adaptive.out;
  const RunResult example = runSoftsubInTerminal(
      "run --frames 0 --formats none " + quote(examplesDir() / "jelly-block.scene"), tmp.path());
  EXPECT_EQ(example.out.find("stability estimate"), std::string::npos) << example.out;
}

TEST(Terminal, QuietPrintsNothingEvenAtATerminal) {
  TempDir tmp;
  const RunResult r = runSoftsubInTerminal(
      "run --quiet --frames 2 -drawPerFrame 1 --formats none " + quote(examplesDir() / "two-fluids.scene"),
      tmp.path());
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

TEST(Terminal, OneFrameIsSingular) {
  TempDir tmp;
  const RunResult r = runSoftsubInTerminal(
      "run --frames 1 --formats none " + quote(examplesDir() / "two-fluids.scene"), tmp.path());
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("\r\ndone: 1 frame, 1,728 particles, "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("output: nothing written\r\n"), std::string::npos) << r.out;
}

TEST(Terminal, ErrorsStillShowAtATerminal) {
  TempDir tmp;
  const RunResult r = runSoftsubInTerminal("run --frames=-5", tmp.path());
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_EQ(r.out.rfind("error: command line: --frames: -5 is out of range", 0), 0u) << r.out;
  EXPECT_TRUE(listEntries(tmp.path()).empty());
}

}  // namespace
}  // namespace softsub::apptest
