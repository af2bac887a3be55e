// The command line itself: help, version, usage errors and their exit codes.
#include <fstream>

#include <gtest/gtest.h>

#include "app_test_util.h"
#include "scene/schema.h"

namespace softsub::apptest {
namespace {

TEST(Cli, HelpOnEveryCommandExitsZero) {
  TempDir tmp;
  for (const char* args : {"--help", "-h", "run --help", "info --help", "schema --help"}) {
    const RunResult r = runSoftsub(args, tmp.path());
    EXPECT_EQ(r.code, 0) << args << "\n" << r.err;
    EXPECT_NE(r.out.find("Usage:"), std::string::npos) << args << "\n" << r.out;
  }
  const RunResult run = runSoftsub("run --help", tmp.path());
  for (const char* option : {"--frames", "--substeps", "--out", "--formats", "--integrator", "--quiet",
                             "--max-particles", "--print-scene", "--record", "--stop-recording-at",
                             "--draw-per-frame"})
    EXPECT_NE(run.out.find(option), std::string::npos) << option;
  EXPECT_TRUE(listEntries(tmp.path()).empty());
}

TEST(Cli, TheCommandsFooterIsOnTheRootHelpOnly) {
  TempDir tmp;
  const std::string footer = "Run 'softsub COMMAND --help'";
  EXPECT_NE(runSoftsub("--help", tmp.path()).out.find(footer), std::string::npos);
  for (const char* args : {"run --help", "info --help", "schema --help"}) {
    const RunResult r = runSoftsub(args, tmp.path());
    EXPECT_EQ(r.out.find(footer), std::string::npos) << args << "\n" << r.out;
  }
}

TEST(Cli, VersionPrintsTheProjectVersion) {
  TempDir tmp;
  const RunResult r = runSoftsub("--version", tmp.path());
  EXPECT_EQ(r.code, 0);
  EXPECT_EQ(r.out.rfind("softsub ", 0), 0u) << r.out;
}

TEST(Cli, BadUsageExitsTwoWithAnErrorLineAndWritesNothing) {
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "two-fluids.scene", tmp.path());
  const std::string s = quote(scene);
  const char* cases[] = {
      "",                                   // no command
      "bogus",                              // unknown command
      "run --bogus",                        // unknown option
      "run --frames abc",                   // not a number
      "run --frames",                       // missing value
      "run --substeps 0 ",                  // below the schema's range
      "run --formats sim,gif",              // unknown format
      "run --formats none,sim",             // none mixed with others
      "run --integrator rk4",               // not an integrator
      "run --max-particles 0",              // not positive
      "-record 2 -f",                       // record is 0 or 1 (scene appended below)
      "-stopRecordingAt -2 -f",             // below -1
      "-updateNum",                         // missing value
      "info",                               // missing file
      "schema extra",                       // unexpected argument
  };
  for (const char* c : cases) {
    std::string args = c;
    if (args.ends_with("-f")) args += " " + s;
    else if (args.starts_with("run --")) args += " " + s;
    const RunResult r = runSoftsub(args, tmp.path());
    EXPECT_EQ(r.code, 2) << "softsub " << args << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("error: ", 0), 0u) << "softsub " << args << "\n" << r.err;
    EXPECT_EQ(listEntries(tmp.path()), std::vector<std::string>{"two-fluids.scene"}) << args;
  }
}

// An empty name is refused by every command that takes a file or folder, in the
// option's words: `run ""` ran the embedded default scene and `run --out "" SCENE` wrote
// into the scene's default folder, both with exit code 0.
TEST(Cli, AnEmptyFileOrFolderNameIsRefusedNotTakenForTheDefault) {
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "two-fluids.scene", tmp.path());
  const std::string s = quote(scene);
  const std::string cases[] = {"run ''",          "run --out '' " + s,   "-f ''",
                               "render ''",       "render --out '' " + s, "view ''",
                               "fill '' --spacing 1", "fill " + s + " --spacing 1 --out ''", "mesh ''",
                               "info ''",         "bench lammps --keep ''", "bench lammps --lammps ''"};
  for (const std::string& args : cases) {
    const RunResult r = runSoftsub(args, tmp.path());
    EXPECT_EQ(r.code, 2) << "softsub " << args << "\n" << r.err;
    EXPECT_NE(r.err.find("an empty name is no file or folder"), std::string::npos) << "softsub " << args << "\n"
                                                                                   << r.err;
    EXPECT_EQ(listEntries(tmp.path()), std::vector<std::string>{"two-fluids.scene"}) << args;
  }
}

TEST(Cli, TwoScenesAreRefused) {
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "two-fluids.scene", tmp.path());
  const RunResult r = runSoftsub("run " + quote(scene) + " -f " + quote(scene), tmp.path());
  EXPECT_EQ(r.code, 2) << r.err;
}

TEST(Cli, OverrideErrorsNameTheOptionAndTheAllowedRange) {
  TempDir tmp;
  const RunResult r = runSoftsub("run --substeps 0 " + quote(examplesDir() / "two-fluids.scene"), tmp.path());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--substeps"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("allowed"), std::string::npos) << r.err;
  const RunResult f = runSoftsub("run --formats gif", tmp.path());
  EXPECT_EQ(f.code, 2);
  EXPECT_NE(f.err.find("unknown format 'gif'"), std::string::npos) << f.err;
}

// A negative override is a value like any other: checked against the schema's range,
// never taken for "not given" (which once ran the scene's frames with exit code 0).
TEST(Cli, NegativeAndOutOfRangeOverridesExitTwoAndWriteNothing) {
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "two-fluids.scene", tmp.path());
  struct Case {
    const char* args;
    const char* message;  // expected in stderr
  };
  const Case cases[] = {
      {"run --frames=-5",
       "error: command line: --frames: -5 is out of range (allowed: integer [0, 1000000])"},
      {"run --frames -5", "error: command line: --frames: -5 is out of range"},
      {"run --frames=1000001", "--frames: 1000001 is out of range"},
      {"run --substeps=0",
       "error: command line: --substeps: 0 is out of range (allowed: integer [1, 10000])"},
      {"run --substeps=-3", "error: command line: --substeps: -3 is out of range"},
      {"run --substeps -3", "--substeps: -3 is out of range"},
      {"-updateNum -3 -f", "--substeps: -3 is out of range"},
      {"run --frames=abc",
       "error: command line: --frames: abc is not a whole number (allowed: integer [0, 1000000])"},
      {"run --frames 1.5", "error: command line: --frames: 1.5 is not a whole number"},
      {"run --frames 2 --frames 3", "error: command line: --frames: given 2 times (allowed: once)"},
      {"--threads 2000 run",
       "error: command line: --threads: 2000 is out of range (allowed: integer [0, 1024])"},
      {"run --stop-recording-at -2",
       "error: command line: --stop-recording-at: -2 is out of range (allowed: integer >= -1)"},
      {"run --integrator rk4",
       "error: command line: --integrator: rk4 is not one of the choices (allowed: explicit-euler, "
       "symplectic-euler, "
       "velocity-verlet)"},
  };
  for (const Case& c : cases) {
    const std::string args = std::string(c.args) + " " + quote(scene);
    const RunResult r = runSoftsub(args, tmp.path());
    EXPECT_EQ(r.code, 2) << "softsub " << args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << "softsub " << args << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("error: ", 0), 0u) << "softsub " << args << "\n" << r.err;
    EXPECT_TRUE(r.out.empty()) << args;
    EXPECT_EQ(listEntries(tmp.path()), std::vector<std::string>{"two-fluids.scene"}) << args;
  }
}

// Whole numbers are decimal even with leading zeros (a padded frame number): CLI11 alone
// read "010" as octal 8, and refused "0048".
TEST(Cli, LeadingZerosAreDecimalNotOctal) {
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "two-fluids.scene", tmp.path());
  const RunResult r = runSoftsub("run --frames 010 --stop-recording-at 0009 --formats sim -q --out o " + quote(scene),
                                 tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(listFrameFiles(tmp / "o").size(), 10U);  // frames 0..9
}

// --speed-limit nan once passed the range check (NaN fails every comparison) and turned
// the blow-up check's speed test off without a word.
TEST(Cli, SpeedLimitMustBeAFiniteNumber) {
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "two-fluids.scene", tmp.path());
  for (const std::string bad : {"nan", "-nan", "NaN", "inf", "-1", "1e7"}) {
    const RunResult r = runSoftsub("run --frames 1 --speed-limit " + bad + " " + quote(scene), tmp.path());
    EXPECT_EQ(r.code, 2) << bad << ": " << r.err;
    EXPECT_NE(r.err.find("error: command line: --speed-limit: " + bad + " is "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("(allowed: 0 to 1e6)"), std::string::npos) << r.err;
    EXPECT_EQ(listEntries(tmp.path()), std::vector<std::string>{"two-fluids.scene"}) << bad;
  }
  EXPECT_EQ(runSoftsub("run --frames 0 --formats none --speed-limit 0 " + quote(scene), tmp.path()).code, 0);
}

// A word that is no command is named as such (CLI11 alone says "A subcommand is
// required"), also after --threads and its value.
TEST(Cli, AnUnknownCommandIsNamedWithTheCommandsThatExist) {
  TempDir tmp;
  for (const std::string args : {"bogus", "--threads 2 bogus", "bogus --threads 1"}) {
    const RunResult r = runSoftsub(args, tmp.path());
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_NE(r.err.find("error: 'bogus' is not a command (allowed: run, info, fill, schema, render, view, mesh, bench)"),
              std::string::npos)
        << args << ": " << r.err;
  }
  EXPECT_NE(runSoftsub("", tmp.path()).err.find("A subcommand is required"), std::string::npos);
  // The same one level down (a review: `bench foo` said "A subcommand is required").
  const RunResult bench = runSoftsub("bench foo", tmp.path());
  EXPECT_EQ(bench.code, 2);
  EXPECT_NE(bench.err.find("error: 'foo' is not a bench command (allowed: lammps)"), std::string::npos)
      << bench.err;
  EXPECT_NE(runSoftsub("bench", tmp.path()).err.find("error: 'bench' needs a command (allowed: lammps)"),
            std::string::npos);
}

// An empty scene name given without -f is blamed on SCENE, the positional the user
// typed (it said --scene); with -f, on --scene.
TEST(Cli, AnEmptySceneNameIsBlamedOnWhatWasTyped) {
  TempDir tmp;
  const RunResult positional = runSoftsub("run ''", tmp.path());
  EXPECT_EQ(positional.code, 2);
  EXPECT_NE(positional.err.find("error: command line: SCENE: an empty name is no file or folder"),
            std::string::npos)
      << positional.err;
  EXPECT_NE(runSoftsub("run -f ''", tmp.path()).err.find("error: command line: --scene: an empty name"),
            std::string::npos);
}

// A particle cap below 1 says what is allowed in words (it printed the range up to the
// largest double, 309 digits).
TEST(Cli, AParticleCapBelowOneSaysWhatIsAllowed) {
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "two-fluids.scene", tmp.path());
  for (const std::string command : {"run", "render --out r", "view"}) {
    const RunResult r = runSoftsub(command + " --max-particles 0 " + quote(scene), tmp.path());
    EXPECT_EQ(r.code, 2) << command;
    EXPECT_NE(r.err.find("error: command line: --max-particles: 0 is out of range (allowed: a whole number in [1, "
                         "9223372036854775807])"),
              std::string::npos)
        << command << ": " << r.err;
    EXPECT_LT(r.err.size(), 300u) << r.err;
  }
  EXPECT_EQ(listEntries(tmp.path()), std::vector<std::string>{"two-fluids.scene"});
  // A whole number with an exponent is one ("2e7"); 2.5e0 is not, and 1e19 is too many.
  EXPECT_EQ(runSoftsub("run --frames 0 --formats none --max-particles 2e7 " + quote(scene), tmp.path()).code, 0);
  const RunResult small = runSoftsub("run --frames 0 --formats none --max-particles 1e2 " + quote(scene), tmp.path());
  EXPECT_EQ(small.code, 2);
  EXPECT_NE(small.err.find("more than the cap of 100"), std::string::npos) << small.err;
  const RunResult half = runSoftsub("run --max-particles 2.5e0 " + quote(scene), tmp.path());
  EXPECT_NE(half.err.find("--max-particles: 2.5e0 is not a whole number"), std::string::npos) << half.err;
  const RunResult huge = runSoftsub("run --max-particles 1e19 " + quote(scene), tmp.path());
  EXPECT_NE(huge.err.find("--max-particles: 1e19 is out of range"), std::string::npos) << huge.err;
}

// The ends of the ranges are allowed: --frames 0 writes only the initial state.
TEST(Cli, OverridesAtTheEndsOfTheirRangesAreAccepted) {
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "two-fluids.scene", tmp.path());
  const RunResult r = runSoftsub("run --frames=0 --substeps=1 --formats sim " + quote(scene), tmp.path());
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(listFrameFiles(tmp / "two-fluidsSim"), std::vector<std::string>{"two-fluids.0000.sim"});
}

TEST(Cli, MissingSceneFileIsAnIoError) {
  TempDir tmp;
  const RunResult r = runSoftsub("run nowhere.scene", tmp.path());
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("nowhere.scene"), std::string::npos) << r.err;
  EXPECT_TRUE(listEntries(tmp.path()).empty());
}

TEST(Cli, UnwritableOutputIsAnIoError) {
  TempDir tmp;
  { std::ofstream(tmp / "file") << "x"; }
  const RunResult r = runSoftsub(
      "run --frames 1 --out " + quote(tmp / "file" / "out") + " " + quote(examplesDir() / "two-fluids.scene"),
      tmp.path());
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_EQ(r.err.rfind("error: ", 0), 0u) << r.err;
}

TEST(Cli, SchemaPrintsTheSchemaMarkdown) {
  TempDir tmp;
  const RunResult r = runSoftsub("schema", tmp.path());
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out, scene::schemaMarkdown());
  EXPECT_NE(r.out.find("Fluid"), std::string::npos);
}

}  // namespace
}  // namespace softsub::apptest
