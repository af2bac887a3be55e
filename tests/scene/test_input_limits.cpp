// The reader's limits beyond the rows of reader_error_rows.h: the file-size cap (refused
// before reading), a byte order mark, numbers under a comma-decimal locale, and the
// warnings a mesh fill of an open mesh gives (docs/robustness.md).
#include <gtest/gtest.h>
#include <stdlib.h>

#include <chrono>
#include <clocale>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <locale>
#include <string>

#include "forces/interaction_table.h"
#include "scene/compile.h"
#include "scene/reader.h"
#include "scene_test_util.h"

namespace softsub::scene {
namespace {

namespace fs = std::filesystem;
using testing::readError;
using testing::readFileError;
using testing::TempFolder;

void writeText(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
}

const std::string kScene =
    "<Scene version=\"1\">\n<Fluid><Name>w</Name><Viscosity>2.5</Viscosity>"
    "<Particles>0 1.25 0</Particles></Fluid>\n</Scene>\n";

TEST(InputLimits, TextOverTheSizeCapIsRefused) {
  ReadOptions options;
  options.maxFileBytes = 64;
  const InputError e = readError(kScene, options);
  EXPECT_EQ(e.where().element, "XML");
  EXPECT_NE(e.problem().find(std::to_string(kScene.size()) + " bytes, more than the cap of 64 bytes"),
            std::string::npos)
      << e.what();
  options.maxFileBytes = kScene.size();
  EXPECT_NO_THROW((void)readSceneText(kScene, "t.scene", options));
}

TEST(InputLimits, AHugeFileIsRefusedBeforeItIsRead) {
  TempFolder dir;
  const fs::path file = dir.path() / "huge.scene";
  writeText(file, kScene);
  // A sparse file one byte over the default cap: reading it would take seconds and 1 GiB.
  fs::resize_file(file, (std::uintmax_t{1} << 30) + 1);
  const auto t0 = std::chrono::steady_clock::now();
  const InputError e = readFileError(file);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 0.5);
  EXPECT_NE(e.problem().find("1073741825 bytes, more than the cap of 1 GiB"), std::string::npos) << e.what();
  EXPECT_NE(e.allowed().find("at most 1 GiB"), std::string::npos) << e.what();
}

// Old Mac files end lines with a CR alone: every error was reported at line 1.
TEST(InputLimits, ErrorsCountLinesEndedByLfCrLfOrALoneCr) {
  for (const std::string eol : {"\n", "\r\n", "\r"}) {
    const std::string text = "<?xml version=\"1.0\"?>" + eol + "<Scene version=\"1\">" + eol + "<Fluid>" +
                             eol + "<Name>w</Name>" + eol + "<Viscosity>-1</Viscosity>" + eol +
                             "<Particles>0 0 0</Particles></Fluid>" + eol + "</Scene>" + eol;
    EXPECT_EQ(testing::readError(text).where().line, 5) << static_cast<int>(eol.back());
  }
}

TEST(InputLimits, AByteOrderMarkIsFine) {
  const SceneDesc d = readSceneText("\xEF\xBB\xBF" + kScene, "t.scene");
  ASSERT_EQ(d.fluids.size(), 1U);
  EXPECT_EQ(d.fluids[0].params.viscosity, 2.5);
}

// Sets a locale whose decimal separator is a comma (de_DE.UTF-8), built into a temporary
// folder with localedef when the system has none; restores "C" on destruction.
class CommaLocale {
 public:
  CommaLocale() {
    if (tryLocale()) return;
    if (std::system("command -v localedef >/dev/null 2>&1") != 0) return;
    const std::string cmd = "localedef -i de_DE -f UTF-8 '" + (dir_.path() / "de_DE.UTF-8").string() +
                            "' >/dev/null 2>&1";
    if (std::system(cmd.c_str()) != 0) return;
    ::setenv("LOCPATH", dir_.path().c_str(), 1);
    tryLocale();
  }
  ~CommaLocale() {
    std::locale::global(std::locale::classic());
    std::setlocale(LC_ALL, "C");
    ::unsetenv("LOCPATH");
  }
  CommaLocale(const CommaLocale&) = delete;
  CommaLocale& operator=(const CommaLocale&) = delete;
  [[nodiscard]] bool active() const { return active_; }

 private:
  bool tryLocale() {
    if (std::setlocale(LC_ALL, "de_DE.UTF-8") == nullptr) return false;
    try {
      std::locale::global(std::locale("de_DE.UTF-8"));
    } catch (const std::runtime_error&) {
      std::setlocale(LC_ALL, "C");
      return false;
    }
    active_ = std::string(std::localeconv()->decimal_point) == ",";
    return active_;
  }

  TempFolder dir_;
  bool active_ = false;
};

TEST(InputLimits, NumbersDoNotDependOnTheLocale) {
  const CommaLocale comma;
  if (!comma.active()) GTEST_SKIP() << "no comma-decimal locale (de_DE.UTF-8) and localedef could not build one";
  ASSERT_EQ(std::strtod("2,5", nullptr), 2.5) << "the locale is not in effect";
  const SceneDesc d = readSceneText(kScene, "t.scene");
  ASSERT_EQ(d.fluids.size(), 1U);
  EXPECT_EQ(d.fluids[0].params.viscosity, 2.5);
  EXPECT_EQ(d.fluids[0].particles.at(0).y(), 1.25);
  const InputError e = readError(
      "<Scene version=\"1\">\n<Fluid><Name>w</Name><Viscosity>2,5</Viscosity>"
      "<Particles>0 1 0</Particles></Fluid>\n</Scene>\n");
  EXPECT_NE(e.problem().find("'2,5' holds a comma"), std::string::npos) << e.what();
}

TEST(InputLimits, AVolumeFillOfAnOpenMeshWarnsWithFileAndLine) {
  TempFolder dir;
  fs::copy_file(fs::path(SOFTSUB_SOURCE_DIR) / "tests/data/bad/meshes/open_box.obj", dir.path() / "open.obj");
  const std::string fill =
      "<Scene version=\"1\">\n<Fluid>\n<Name>w</Name>\n<Fill>\n<Shape>mesh</Shape>\n"
      "<Geometry>open.obj</Geometry>\n<Spacing>0.5</Spacing>\n";
  writeText(dir.path() / "a.scene", fill + "</Fill>\n</Fluid>\n</Scene>\n");
  writeText(dir.path() / "b.scene", fill + "<Surface>true</Surface>\n</Fill>\n</Fluid>\n</Scene>\n");
  std::vector<std::string> warnings;
  ReadOptions options;
  options.warnings = &warnings;
  (void)readSceneFile((dir.path() / "a.scene").string(), options);
  ASSERT_EQ(warnings.size(), 1U);
  EXPECT_EQ(warnings[0].rfind((dir.path() / "a.scene").string() + ":6: Fluid 'w'/Fill[1]/Geometry: mesh 'open.obj': "
                              "the mesh is not closed (4 edge(s)", 0),
            0U)
      << warnings[0];
  // A surface fill does not need a closed mesh: no warning.
  warnings.clear();
  (void)readSceneFile((dir.path() / "b.scene").string(), options);
  EXPECT_TRUE(warnings.empty()) << warnings.front();
}

}  // namespace
// The interaction table's size is capped (forces::kMaxTableFloats): a scene whose
// distinct pair functions would pass it is refused naming the fluid (or <Pair>) whose
// function does not fit, instead of running out of memory (300 fluids with their own
// <Pair> functions took 1.1 GB; the 1024-fluid limit allowed about 12 GB).
TEST(InputLimits, AnInteractionTablePastItsCapIsRefusedNamingTheLine) {
  std::string body;
  const int fluids = 129;  // each 2 MiB of table (cutoff 600 x FiniteDistance): 258 MiB
  for (int k = 0; k < fluids; ++k)
    body += "<Fluid><Name>f" + std::to_string(k) + "</Name><Amplitude>" + std::to_string(1 + k) +
            "</Amplitude><InteractionDistance>600</InteractionDistance><FiniteDistance>1</FiniteDistance>"
            "<Particles>" +
            std::to_string(k) + " 0 0</Particles></Fluid>\n";
  const SceneDesc desc = readSceneText(testing::sceneWith(body), "t.scene");
  try {
    (void)compile(desc);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "t.scene");
    // 127 tables of 2^19 floats fit beside the zero piece; fluid f127, on line 2 + 127, does not.
    const auto fit =
        static_cast<int>((forces::kMaxTableFloats - 2) / (2 * std::size_t{forces::kMaxIntervals}));
    EXPECT_EQ(e.where().line, 2 + fit) << e.what();
    EXPECT_NE(std::string(e.what()).find("distinct pair functions need more than"), std::string::npos)
        << e.what();
  }
}

}  // namespace softsub::scene
