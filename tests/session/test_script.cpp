// The viewer's scripts: every command parses to what it says; a bad line is refused with
// the file, the line and what is allowed.
#include <gtest/gtest.h>

#include <string>

#include "cache/atomic_file.h"
#include "core/error.h"
#include "session/script.h"
#include "session_test_support.h"

namespace softsub::session {
namespace {

using K = ScriptCommandKind;

TEST(Script, ParsesEveryCommand) {
  const std::string text =
      "# a demo\n"
      "\n"
      "set fluid honey Viscosity 8   # thicker\n"
      "set fluid honey Colour 0.9  0.6 0.1\n"
      "  set simulation Gravity 0 -3 0\r\n"
      "set simulation Integrator velocity-verlet\n"
      "key space\n"
      "key R\n"
      "frames 24\n"
      "wait 0\n"
      "save out/tweaked.scene  # keep it\n"
      "screenshot shots/my shot take#1.png\n"
      "quit\n";
  const std::vector<ScriptCommand> got = parseScript(text, "demo.txt");
  const std::vector<ScriptCommand> want = {
      {K::SetFluid, {"honey", "Viscosity", "8"}, 3},
      {K::SetFluid, {"honey", "Colour", "0.9  0.6 0.1"}, 4},
      {K::SetSimulation, {"Gravity", "0 -3 0"}, 5},
      {K::SetSimulation, {"Integrator", "velocity-verlet"}, 6},
      {K::Key, {"SPACE"}, 7},
      {K::Key, {"R"}, 8},
      {K::Frames, {"24"}, 9},
      {K::Wait, {"0"}, 10},
      {K::Save, {"out/tweaked.scene"}, 11},
      {K::Screenshot, {"shots/my shot take#1.png"}, 12},  // '#' inside a word stays
      {K::Quit, {}, 13},
  };
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    EXPECT_EQ(got[i].kind, want[i].kind) << i;
    EXPECT_EQ(got[i].args, want[i].args) << i;
    EXPECT_EQ(got[i].line, want[i].line) << i;
  }
  EXPECT_EQ(scriptCount(got[6]), 24);
  EXPECT_EQ(scriptCount(got[7]), 0);
  for (std::string_view k : kScriptKeys)
    EXPECT_EQ(parseScript("key " + std::string(k), "k.txt").at(0).args.at(0), k);
  EXPECT_TRUE(parseScript("# nothing\n\n   \n", "empty.txt").empty());
}

/// The InputError of parsing `line` as line 3 of "bad.txt".
InputError lineError(const std::string& line) {
  try {
    (void)parseScript("frames 1\n# ok\n" + line + "\nquit\n", "bad.txt");
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError for: " << line;
  return InputError({}, "none");
}

TEST(Script, RefusesBadLinesWithFileAndLine) {
  struct Row {
    const char* line;
    const char* inMessage;
    const char* inAllowed;
  };
  const Row rows[] = {
      {"jump 3", "unknown command 'jump'", "set fluid <Name> <Tag> <value>"},
      {"Frames 3", "unknown command 'Frames'", "screenshot <path.png>"},
      {"key ESC", "unknown key 'ESC'", "SPACE, UP, DOWN, LEFT, RIGHT"},
      {"key", "expected a key", "R, S, N"},
      {"key R S", "unknown key", "R, S, N"},
      {"frames 0", "'0' is not a count", "[1, 1000000]"},
      {"frames two", "'two' is not a count", "[1, 1000000]"},
      {"frames 2.5", "is not a count", "[1, 1000000]"},
      {"wait -1", "is not a count", "[0, 1000000]"},
      {"wait", "expected a number", "[0, 1000000]"},
      {"save tweaked.xml", "is not a .scene file", "ending in .scene"},
      {"screenshot", "expected a file", "ending in .png"},
      {"quit now", "takes nothing after it", "quit"},
      {"set honey Viscosity 3", "cannot set 'honey'", "set simulation <Tag> <value>"},
      {"set fluid honey Viscosity", "expected a fluid name, a tag and a value", "set fluid <Name> <Tag> <value>"},
      {"set fluid honey Viscocity 3", "did you mean <Viscosity>", "Amplitude"},
      {"set fluid honey Viscosity -3", "out of range", ">= 0"},
      {"set fluid honey Colour 1 0", "expected 3 numbers", "[0, 1]"},
      {"set simulation Substeps 0", "out of range", "integer [1, 10000]"},
      {"set simulation Substeps", "expected a tag and a value", "set simulation <Tag> <value>"},
  };
  for (const Row& r : rows) {
    const InputError e = lineError(r.line);
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("bad.txt:3: ", 0), 0u) << r.line << " -> " << what;
    EXPECT_NE(what.find(r.inMessage), std::string::npos) << r.line << " -> " << what;
    EXPECT_NE(e.allowed().find(r.inAllowed), std::string::npos) << r.line << " -> " << what;
  }
}

TEST(Script, SetCommandsEditTheSceneAndNameTheirLine) {
  const std::vector<ScriptCommand> c =
      parseScript("set fluid syrup Viscosity 6\nset simulation Substeps 12\nset fluid tar Viscosity 1\nkey N\n", "t.txt");
  scene::SceneDesc d = test::smallScene();
  applySetCommand(c[0], d, "t.txt");
  applySetCommand(c[1], d, "t.txt");
  EXPECT_EQ(d.fluids[1].params.viscosity, 6);
  EXPECT_EQ(d.simulation.substeps, 12);
  try {
    applySetCommand(c[2], d, "t.txt");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("t.txt:3: Fluid: ", 0), 0u) << e.what();
    EXPECT_EQ(e.allowed(), "goo, syrup");
  }
  EXPECT_THROW(applySetCommand(c[3], d, "t.txt"), std::invalid_argument);
}

TEST(Script, ReadsAFile) {
  test::ScratchDir dir;
  cache::writeFileAtomic(dir.path() / "demo.txt", "frames 2\nkey S\n");
  const std::vector<ScriptCommand> c = readScriptFile(dir.path() / "demo.txt");
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[1].kind, K::Key);
  EXPECT_THROW((void)readScriptFile(dir.path() / "none.txt"), IoError);
}

}  // namespace
}  // namespace softsub::session
