// --threads, run --stats and bench lammps end to end (issue #6).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "app_test_util.h"

namespace softsub::apptest {
namespace {

TEST(ThreadsCli, RunWritesTheSameBytesOnOneAndTwoThreads) {
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "two-fluids.scene", tmp.path());
  // --threads after the command and before it: both are the root's option.
  const RunResult one = runSoftsub("run -q --frames 4 --formats sim --threads 1 --out " + quote(tmp / "one") + " " +
                                       quote(scene),
                                   tmp.path());
  const RunResult two = runSoftsub("--threads 2 run -q --frames 4 --formats sim --out " + quote(tmp / "two") + " " +
                                       quote(scene),
                                   tmp.path());
  ASSERT_EQ(one.code, 0) << one.err;
  ASSERT_EQ(two.code, 0) << two.err;
  const auto files = listFrameFiles(tmp / "one");
  ASSERT_EQ(files.size(), 5u);
  EXPECT_EQ(listFrameFiles(tmp / "two"), files);
  for (const std::string& f : files) EXPECT_EQ(readFile(tmp / "one" / f), readFile(tmp / "two" / f)) << f;
}

TEST(ThreadsCli, AThreadCountOutOfRangeIsRefused) {
  TempDir tmp;
  for (const std::string bad : {"--threads 2000", "--threads -1", "--threads x"}) {
    const RunResult r = runSoftsub(bad + " run --frames 1 --formats none", tmp.path());
    EXPECT_EQ(r.code, 2) << bad;
    EXPECT_NE(r.err.find("--threads"), std::string::npos) << r.err;
  }
}

// The rows of --stats: frame, time, kinetic, pair, gravity, bodies, total, substeps, travel.
std::vector<std::vector<double>> statsRows(const std::string& out) {
  std::vector<std::vector<double>> rows;
  std::istringstream in(out);
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::vector<double> row;
    for (double v; fields >> v;) row.push_back(v);
    rows.push_back(row);
  }
  return rows;
}

TEST(ThreadsCli, StatsPrintsEveryFramesEnergiesThatAddUp) {
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "box-on-jelly.scene", tmp.path());
  const RunResult r = runSoftsub("run -q --frames 3 --formats none --stats " + quote(scene), tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("# frame time kinetic pair gravity bodies total substeps travel lists\n", 0), 0u) << r.out;
  const auto rows = statsRows(r.out);
  ASSERT_EQ(rows.size(), 4u) << r.out;
  for (std::size_t f = 0; f < rows.size(); ++f) {
    ASSERT_EQ(rows[f].size(), 10u);
    EXPECT_EQ(rows[f][7], 8.0) << "the scene's substeps";
    EXPECT_GE(rows[f][8], 0.0);
    EXPECT_LT(rows[f][8], 10.0) << "within the blow-up check's limit";
    EXPECT_EQ(rows[f][0], static_cast<double>(f));
    const double parts = rows[f][2] + rows[f][3] + rows[f][4] + rows[f][5];
    EXPECT_NEAR(rows[f][6], parts, 1e-6 * std::max(1.0, std::abs(parts)));
    EXPECT_GE(rows[f][2], 0.0);
    EXPECT_GE(rows[f][5], 0.0);
    // Pair lists built so far: at least the first, at most one a substep after it.
    EXPECT_GE(rows[f][9], f > 0 ? 1.0 : 0.0);
    EXPECT_LE(rows[f][9], 1.0 + 8.0 * static_cast<double>(f));
    if (f > 0) {
      EXPECT_GE(rows[f][9], rows[f - 1][9]);
    }
  }
  EXPECT_GT(rows[3][2], 0.0) << "the jelly moves under gravity";
  // The numbers do not depend on the thread count either.
  const RunResult one = runSoftsub("--threads 1 run -q --frames 3 --formats none --stats " + quote(scene), tmp.path());
  EXPECT_EQ(one.out, r.out);
}

TEST(BenchCli, LammpsComparisonRunsOurSideAndLammpsWhenInstalled) {
  TempDir tmp;
  // Without LAMMPS: a note, and softsub's side of the table.
  const RunResult ours = runSoftsub(
      "bench lammps --particles 500 --cutoff 2.5 --steps 5 --repeat 1 --lammps /nonexistent/lmp", tmp.path());
  ASSERT_EQ(ours.code, 0) << ours.err;
  EXPECT_NE(ours.err.find("LAMMPS not found"), std::string::npos) << ours.err;
  const auto rows = statsRows(ours.out);  // rows with "-" stop at the first dash
  ASSERT_GE(rows.size(), 1u) << ours.out;
  EXPECT_EQ(rows[0].at(0), 500.0);  // 4 x 5^3
  EXPECT_EQ(rows[0].at(1), 2.5);
  EXPECT_GT(rows[0].at(3), 0.0) << "atom-steps per second";
  if (findProgram("lmp").empty()) GTEST_SKIP() << "LAMMPS (lmp) is not installed: its side is not checked";
  // With LAMMPS: both codes from the same start agree on the energy after the run.
  const RunResult both = runSoftsub("bench lammps --particles 500 --cutoff 2.5 --steps 20 --repeat 1 --keep " +
                                        quote(tmp / "kept"),
                                    tmp.path());
  ASSERT_EQ(both.code, 0) << both.err;
  const auto full = statsRows(both.out);
  ASSERT_GE(full.size(), 1u) << both.out;
  ASSERT_EQ(full[0].size(), 10u) << both.out;
  EXPECT_LT(full[0][8], 1e-4) << "relative energy difference\n" << both.out;
  EXPECT_TRUE(fs::exists(tmp / "kept" / "lj-500.data"));
  EXPECT_TRUE(fs::exists(tmp / "kept" / "lj-500-rc2.5.scene"));
}

TEST(BenchCli, LammpsRowsFollowTheThreadsOption) {
  TempDir tmp;
  // The rows are 1 thread and --threads: with --threads 1 one row only (a second row
  // would claim more threads than the process may use), with --threads 3 a row for 3.
  const std::string bench = "bench lammps --particles 32 --cutoff 2.5 --steps 2 --repeat 1 --lammps /nonexistent/lmp";
  const RunResult single = runSoftsub("--threads 1 " + bench, tmp.path());
  ASSERT_EQ(single.code, 0) << single.err;
  const auto one = statsRows(single.out);
  ASSERT_EQ(one.size(), 1u) << single.out;
  EXPECT_EQ(one[0].at(2), 1.0);
  const RunResult three = runSoftsub(bench + " --threads 3", tmp.path());
  ASSERT_EQ(three.code, 0) << three.err;
  const auto rows = statsRows(three.out);
  ASSERT_EQ(rows.size(), 2u) << three.out;
  EXPECT_EQ(rows[0].at(2), 1.0);
  EXPECT_EQ(rows[1].at(2), 3.0);
}

TEST(BenchCli, LammpsRowsPrintTheBestOfTheRepeatedRunsOfEachCode) {
  TempDir tmp;
  // A stand-in for lmp: each run checks that it can open its input, counts itself in a
  // file and reports the loop time of its line in `times` (a run past the last line
  // fails), so the test sees how often it ran and which time the row printed. --keep is
  // relative to the working folder, which LAMMPS does not run in.
  const fs::path fake = tmp / "fake-lmp";
  {
    std::ofstream out(fake);
    out << "#!/bin/sh\n"
           "[ \"$1\" = -in ] && [ -f \"$2\" ] || exit 4\n"  // the input, from the folder it runs in
           "n=$(cat runs 2>/dev/null || echo 0); n=$((n+1)); echo $n > runs\n"
           "t=$(sed -n \"${n}p\" times); [ -n \"$t\" ] || exit 3\n"
           "echo \"Loop time of $t on 1 procs for 10 steps with 32 atoms\"\n"
           "echo \"10 1.5 -3.0 -1.5\"\n";
  }
  fs::permissions(fake, fs::perms::owner_all);
  const auto bench = [&](const std::string& times, const std::string& kept, const std::string& more) {
    fs::create_directories(tmp / kept);
    std::ofstream(tmp / kept / "times") << times;
    return runSoftsub("--threads 1 bench lammps --particles 32 --cutoff 2.5 --steps 10 --lammps " + quote(fake) +
                          " --keep " + quote(kept) + " " + more,
                      tmp.path());
  };
  // The fastest run in the middle: neither the first nor the last run is the best.
  const RunResult r = bench("2.0\n0.5\n1.0\n", "three", "--repeat 3");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("best of 3 runs each"), std::string::npos) << r.out;
  const auto rows = statsRows(r.out);
  ASSERT_EQ(rows.size(), 1u) << r.out;
  ASSERT_EQ(rows[0].size(), 10u) << r.out;
  EXPECT_EQ(rows[0][4], 32.0 * 10 / 0.5) << "LAMMPS's best run";
  EXPECT_EQ(rows[0][7], -1.5) << "LAMMPS's energy";
  EXPECT_EQ(readFile(tmp / "three" / "runs"), "3\n") << "LAMMPS ran once per repeat";
  for (int run = 1; run <= 3; ++run)
    EXPECT_TRUE(fs::exists(tmp / "three" / ("lj-32-rc2.5.1ranks.run" + std::to_string(run) + ".log"))) << run;
  // A run that fails ends the row: the best run before it, and a note that says which.
  const RunResult failed = bench("1.0\n", "fails", "--repeat 3");
  ASSERT_EQ(failed.code, 0) << failed.err;
  EXPECT_NE(failed.err.find("LAMMPS's run 2 of 3; the row shows its best before it"), std::string::npos)
      << failed.err;
  const auto kept = statsRows(failed.out);
  ASSERT_EQ(kept.size(), 1u) << failed.out;
  ASSERT_EQ(kept[0].size(), 10u) << failed.out;
  EXPECT_EQ(kept[0][4], 32.0 * 10 / 1.0);
  EXPECT_EQ(readFile(tmp / "fails" / "runs"), "2\n") << "no run after the failed one";
  for (const std::string bad : {"--repeat 0", "--repeat 101"}) {
    const RunResult refused = bench("1.0\n", "refused", bad);
    EXPECT_EQ(refused.code, 2) << bad;
    EXPECT_NE(refused.err.find("--repeat"), std::string::npos) << refused.err;
  }
}

}  // namespace
}  // namespace softsub::apptest
