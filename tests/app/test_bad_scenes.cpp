// Every invalid scene in tests/data/scenes/bad/ is refused by `softsub run` with exit
// code 2, its expected message, `<file>:<line>`, and no output folder.
#include <cctype>

#include <gtest/gtest.h>

#include "app_test_util.h"

namespace softsub::apptest {
namespace {

/// True when `text` holds `name:<digits>` (a file and a line number).
bool hasFileLine(const std::string& text, const std::string& name) {
  for (auto at = text.find(name + ":"); at != std::string::npos; at = text.find(name + ":", at + 1)) {
    const std::size_t digit = at + name.size() + 1;
    if (digit < text.size() && std::isdigit(static_cast<unsigned char>(text[digit]))) return true;
  }
  return false;
}

/// The text after `<!-- expect:` on the file's first line.
std::string expectedMessage(const std::string& text) {
  const std::string open = "<!-- expect:";
  const auto start = text.find(open);
  const auto end = text.find("-->", start);
  if (start != 0 || end == std::string::npos) return {};
  std::string s = text.substr(open.size(), end - open.size());
  while (!s.empty() && s.front() == ' ') s.erase(s.begin());
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

TEST(BadScenes, EachIsRefusedWithItsMessageAndNothingIsWritten) {
  const fs::path dir = fs::path(SOFTSUB_SOURCE_DIR) / "tests/data/scenes/bad";
  ASSERT_TRUE(fs::is_directory(dir));
  int checked = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() != ".scene") continue;
    ++checked;
    const std::string name = entry.path().filename().string();
    const std::string expect = expectedMessage(readFile(entry.path()));
    ASSERT_FALSE(expect.empty()) << name << " has no <!-- expect: ... --> line";
    TempDir tmp;
    const fs::path scene = copyInto(entry.path(), tmp.path());
    for (const std::string& extra : std::vector<std::string>{"", " --out " + quote(tmp / "out")}) {
      const RunResult r = runSoftsub("run " + quote(scene) + extra, tmp.path());
      EXPECT_EQ(r.code, 2) << name << "\n" << r.err;
      EXPECT_EQ(r.err.rfind("error: ", 0), 0u) << name << "\n" << r.err;
      EXPECT_NE(r.err.find(expect), std::string::npos) << name << ": expected '" << expect << "' in\n" << r.err;
      EXPECT_TRUE(hasFileLine(r.err, name))
          << name << ": no <file>:<line> in\n" << r.err;
      // Neither <sceneDir>/<name>Sim nor --out was created: the scene is the only entry.
      EXPECT_EQ(listEntries(tmp.path()), std::vector<std::string>{name}) << name;
      EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << name << ": one line expected\n" << r.err;
    }
  }
  EXPECT_GE(checked, 10);
}

TEST(BadScenes, MaxParticlesRefusesABigScene) {
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "two-fluids.scene", tmp.path());
  const RunResult r = runSoftsub("run --max-particles 100 " + quote(scene), tmp.path());
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("100"), std::string::npos) << r.err;
  EXPECT_EQ(listEntries(tmp.path()), std::vector<std::string>{"two-fluids.scene"});
}

}  // namespace
}  // namespace softsub::apptest
