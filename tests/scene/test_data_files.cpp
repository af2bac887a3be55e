// The scene files under tests/data/scenes: every bad one is refused with the message its
// first-line comment `<!-- expect: ... -->` names; every good one reads and round-trips.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "scene/compile.h"
#include "scene/reader.h"
#include "scene/writer.h"

namespace softsub::scene {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> scenesIn(const std::string& sub) {
  std::vector<fs::path> out;
  const fs::path dir = fs::path(SOFTSUB_SOURCE_DIR) / "tests/data/scenes" / sub;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.path().extension() == ".scene") out.push_back(e.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

// "unknown element" from a first line "<!-- expect: unknown element -->".
std::string expectation(const fs::path& file) {
  std::ifstream in(file);
  std::string first;
  std::getline(in, first);
  const std::string open = "<!-- expect: ";
  const std::string close = " -->";
  if (first.rfind(open, 0) != 0 || first.size() < open.size() + close.size() ||
      first.compare(first.size() - close.size(), close.size(), close) != 0) {
    return {};
  }
  return first.substr(open.size(), first.size() - open.size() - close.size());
}

TEST(SceneFiles, BadScenesAreRefusedWithTheExpectedMessage) {
  const auto files = scenesIn("bad");
  EXPECT_GE(files.size(), 10U);
  for (const fs::path& file : files) {
    SCOPED_TRACE(file.filename().string());
    const std::string expected = expectation(file);
    ASSERT_FALSE(expected.empty()) << "first line must be <!-- expect: ... -->";
    try {
      (void)readSceneFile(file.string());
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
      EXPECT_EQ(e.where().file, file.string());
      EXPECT_GT(e.where().line, 0) << e.what();
    }
  }
}

TEST(SceneFiles, GoodScenesReadAndRoundTrip) {
  const auto files = scenesIn("good");
  EXPECT_GE(files.size(), 3U);
  for (const fs::path& file : files) {
    SCOPED_TRACE(file.filename().string());
    const SceneDesc d = readSceneFile(file.string());
    EXPECT_FALSE(d.fluids.empty());
    // Next to the original, so relative mesh paths resolve the same way.
    EXPECT_EQ(readSceneText(writeSceneText(d), (file.parent_path() / "again.scene").string()), d);
  }
}

// The complete example in docs/scene-format.md (its first ```xml block) is a valid scene,
// and a clean one: neither the reader nor the compiler warns about it (an oil point used
// to sit exactly on a point of honey's sphere fill).
TEST(SceneFiles, DocsExampleIsValid) {
  std::ifstream in(std::string(SOFTSUB_SOURCE_DIR) + "/docs/scene-format.md");
  ASSERT_TRUE(in);
  std::string line;
  std::string example;
  bool inside = false;
  while (std::getline(in, line)) {
    if (!inside && line == "```xml") {
      inside = true;
    } else if (inside && line == "```") {
      break;
    } else if (inside) {
      example += line + "\n";
    }
  }
  ASSERT_FALSE(example.empty());
  std::vector<std::string> warnings;
  ReadOptions options;
  options.warnings = &warnings;
  const SceneDesc d = readSceneText(example, "scene-format.md", options);
  EXPECT_EQ(d.fluids.size(), 2U);
  EXPECT_EQ(d.interactions.pairs.size(), 2U);
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  const Compiled compiled = compile(d);
  EXPECT_TRUE(compiled.warnings.empty()) << compiled.warnings.front();
}

}  // namespace
}  // namespace softsub::scene
