// The seed's single-dash flags, rewritten before CLI11 parses the line.
#include <gtest/gtest.h>

#include "seed_flags.h"

namespace softsub::app {
namespace {

std::vector<std::string> rewrite(std::vector<std::string> args) {
  args.insert(args.begin(), "softsub");
  auto out = rewriteSeedFlags(args);
  out.erase(out.begin());
  return out;
}

using Args = std::vector<std::string>;

TEST(SeedFlags, MapsToLongOptionsAndImpliesRun) {
  EXPECT_EQ(rewrite({"-f", "a.scene", "-updateNum", "2", "-record", "1", "-stopRecordingAt", "5",
                     "-drawPerFrame", "1"}),
            (Args{"run", "-f", "a.scene", "--substeps=2", "--record=1", "--stop-recording-at=5",
                  "--draw-per-frame=1"}));
}

// "-f=FILE" was read as the file "=FILE" ("cannot read scene file '=/path/x.scene'").
TEST(SeedFlags, FWithAnEqualsSignNamesTheScene) {
  EXPECT_EQ(rewrite({"-f=/path/x.scene"}), (Args{"run", "--scene=/path/x.scene"}));
  EXPECT_EQ(rewrite({"view", "-f=a.scene"}), (Args{"view", "--scene=a.scene"}));
}

TEST(SeedFlags, JoinsNegativeValues) {
  EXPECT_EQ(rewrite({"-f", "a.scene", "-stopRecordingAt", "-1"}),
            (Args{"run", "-f", "a.scene", "--stop-recording-at=-1"}));
  EXPECT_EQ(rewrite({"-stopRecordingAt=-1"}), (Args{"run", "--stop-recording-at=-1"}));
}

TEST(SeedFlags, KeepsAnExplicitSubcommand) {
  EXPECT_EQ(rewrite({"run", "-f", "a.scene", "-record", "0"}),
            (Args{"run", "-f", "a.scene", "--record=0"}));
  EXPECT_EQ(rewrite({"run", "a.scene", "--frames", "3"}), (Args{"run", "a.scene", "--frames", "3"}));
  // The viewer takes the seed's flags too, -drawPerFrame included.
  EXPECT_EQ(rewrite({"view", "-f", "a.scene", "-updateNum", "4", "-drawPerFrame", "0", "-record", "0"}),
            (Args{"view", "-f", "a.scene", "--substeps=4", "--draw-per-frame=0", "--record=0"}));
}

// After the root's --threads the named command was missed: "run" went in first and the
// command became a second scene ("--scene: At Most 1 required but received 2").
TEST(SeedFlags, FindsTheCommandAfterTheRootsOptions) {
  EXPECT_EQ(rewrite({"--threads", "1", "view", "-f", "a.scene", "-updateNum", "8"}),
            (Args{"--threads", "1", "view", "-f", "a.scene", "--substeps=8"}));
  EXPECT_EQ(rewrite({"--threads=2", "run", "a.scene", "-record", "0"}),
            (Args{"--threads=2", "run", "a.scene", "--record=0"}));
  EXPECT_EQ(rewrite({"--threads", "1", "-f", "a.scene"}), (Args{"--threads", "1", "run", "-f", "a.scene"}));
}

TEST(SeedFlags, LeavesOtherLinesAlone) {
  EXPECT_EQ(rewrite({}), Args{});
  EXPECT_EQ(rewrite({"--help"}), Args{"--help"});
  EXPECT_EQ(rewrite({"info", "x.sim"}), (Args{"info", "x.sim"}));
  EXPECT_EQ(rewrite({"run", "--", "-record"}), (Args{"run", "--", "-record"}));
}

TEST(SeedFlags, MissingValueIsLeftForTheParserToReport) {
  EXPECT_EQ(rewrite({"-updateNum"}), (Args{"run", "--substeps"}));
}

}  // namespace
}  // namespace softsub::app
