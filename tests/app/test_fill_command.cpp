// `softsub fill`: a mesh file to a PLY point cloud or a <Fluid> block.
#include <gtest/gtest.h>

#include <fstream>

#include "app_test_util.h"
#include "cache/ply_format.h"
#include "scene/reader.h"
#include "support/mesh_files.h"

namespace softsub::apptest {
namespace {

void writeBoxObj(const fs::path& file, double a) { scenarios::writeTextFile(file, scenarios::boxObj(a)); }

TEST(FillCommand, WritesAPlyWhoseCountMatchesTheVolume) {
  TempDir tmp;
  writeBoxObj(tmp / "box.obj", 4.0);
  const RunResult r = runSoftsub("fill box.obj --spacing 0.5 --out box.ply", tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  const cache::PlyCloud cloud = cache::readPlyFile(tmp / "box.ply");
  EXPECT_NEAR(static_cast<double>(cloud.vertexCount), 4.0 * 4 * 4 / (0.5 * 0.5 * 0.5), 0.03 * 512);
  // The colour of the <Fluid> the snippet would make (Colour 0.8 0.5 0.2 x 255), not white.
  for (const auto& [name, value] :
       {std::pair{"red", 204.0}, std::pair{"green", 128.0}, std::pair{"blue", 51.0}}) {
    const cache::PlyProperty* channel = cloud.find(name);
    ASSERT_NE(channel, nullptr) << name;
    ASSERT_EQ(channel->values.size(), cloud.vertexCount);
    for (const double v : channel->values) ASSERT_EQ(v, value) << name;
  }
}

TEST(FillCommand, SnippetIsAFluidTheReaderAccepts) {
  TempDir tmp;
  writeBoxObj(tmp / "box.obj", 3.0);
  const RunResult r = runSoftsub("fill box.obj --spacing 1 --name cube", tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  const scene::SceneDesc d = scene::readSceneText("<Scene version=\"1\">\n" + r.out + "</Scene>\n", "snippet.scene");
  ASSERT_EQ(d.fluids.size(), 1u);
  EXPECT_EQ(d.fluids[0].name, "cube");
  EXPECT_EQ(d.fluids[0].particles.size(), 27u);  // 3 x 3 x 3 lattice points inside
  EXPECT_DOUBLE_EQ(d.fluids[0].params.particleSize, 1.0);
  // The lengths follow the spacing, written as a person would: 1.5 x 0.3 is
  // 0.44999999999999996 in full; and a comment says what does not follow it.
  const RunResult fine = runSoftsub("fill box.obj --spacing 0.3", tmp.path());
  ASSERT_EQ(fine.code, 0) << fine.err;
  EXPECT_NE(fine.out.find("<InteractionDistance>0.45</InteractionDistance>"), std::string::npos) << fine.out;
  EXPECT_NE(fine.out.find("Amplitude, the force clamps and ParticleMass keep"), std::string::npos) << fine.out;
  const scene::SceneDesc f =
      scene::readSceneText("<Scene version=\"1\">\n" + fine.out + "</Scene>\n", "fine.scene");
  EXPECT_NEAR(f.fluids[0].params.interactionDistance, 0.45, 1e-15);
  // Positions too, as the floats the simulation keeps (0.04999999999999982 was written).
  EXPECT_EQ(fine.out.find("99999"), std::string::npos) << fine.out;
  EXPECT_EQ(fine.out.find("00000000"), std::string::npos) << fine.out;
  EXPECT_DOUBLE_EQ(f.fluids[0].params.finiteDistance, 0.3);
  // Well-formed XML for strict parsers too: no "--" inside a comment, even when the mesh's
  // name has one or ends in '-' (the comment used to quote the command line, "--spacing").
  writeBoxObj(tmp / "a--b-.obj", 3.0);
  for (const std::string mesh : {"box.obj", "a--b-.obj"}) {
    const RunResult m = runSoftsub("fill " + mesh + " --spacing 1 --surface", tmp.path());
    ASSERT_EQ(m.code, 0) << m.err;
    for (std::size_t open = m.out.find("<!--"); open != std::string::npos; open = m.out.find("<!--", open + 4)) {
      const std::size_t close = m.out.find("-->", open + 4);
      ASSERT_NE(close, std::string::npos);
      const std::string body = m.out.substr(open + 4, close - open - 4);
      EXPECT_EQ(body.find("--"), std::string::npos) << body;
      EXPECT_NE(body.back(), '-') << body;
    }
  }
}

TEST(FillCommand, BadInputExitsTwoMissingFileThree) {
  TempDir tmp;
  writeBoxObj(tmp / "box.obj", 2.0);
  EXPECT_EQ(runSoftsub("fill box.obj --spacing 0 --out x.ply", tmp.path()).code, 2);
  EXPECT_EQ(runSoftsub("fill box.obj --spacing -1", tmp.path()).code, 2);
  const RunResult inf = runSoftsub("fill box.obj --spacing inf", tmp.path());
  EXPECT_EQ(inf.code, 2);
  EXPECT_NE(inf.err.find("--spacing: inf is not a valid spacing (allowed: a finite number > 0)"),
            std::string::npos)
      << inf.err;
  EXPECT_EQ(runSoftsub("fill box.obj", tmp.path()).code, 2);  // --spacing is required
  EXPECT_EQ(runSoftsub("fill missing.obj --spacing 1", tmp.path()).code, 3);
  {
    std::ofstream(tmp / "junk.obj") << "this is not a mesh\n";
  }
  EXPECT_EQ(runSoftsub("fill junk.obj --spacing 1", tmp.path()).code, 2);
  EXPECT_EQ(listEntries(tmp.path()), (std::vector<std::string>{"box.obj", "junk.obj"}));
}

// --out replaced the mesh being filled with the point cloud (exit 0) when the user
// named it after the mesh; only a .ply name that is not the mesh itself is written.
TEST(FillCommand, TheOutputNeverReplacesTheMesh) {
  TempDir tmp;
  writeBoxObj(tmp / "box.obj", 2.0);
  const std::string obj = readFile(tmp / "box.obj");
  const RunResult notPly = runSoftsub("fill box.obj --spacing 0.5 --out box.obj", tmp.path());
  EXPECT_EQ(notPly.code, 2) << notPly.err;
  EXPECT_NE(notPly.err.find("does not end in .ply"), std::string::npos) << notPly.err;
  EXPECT_EQ(readFile(tmp / "box.obj"), obj);
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 4\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n2 0 0\n0 2 0\n0 0 2\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  std::ofstream(tmp / "tet.ply") << ply;
  ASSERT_EQ(runSoftsub("fill tet.ply --spacing 0.25 --out cloud.PLY -q", tmp.path()).code, 0);
  const RunResult same = runSoftsub("fill tet.ply --spacing 0.25 --out ./tet.ply", tmp.path());
  EXPECT_EQ(same.code, 2) << same.err;
  EXPECT_NE(same.err.find("is the mesh being filled"), std::string::npos) << same.err;
  EXPECT_EQ(readFile(tmp / "tet.ply"), ply);
}

// --name went into the snippet unescaped and unchecked (`<Name><x>&</Name>`, a broken
// scene); it now follows the reader's rule for fluid names in both modes, checked first.
TEST(FillCommand, NamesFollowTheScenesFluidNameRule) {
  TempDir tmp;
  writeBoxObj(tmp / "box.obj", 2.0);
  struct Case {
    std::string name;
    std::string problem;
  };
  const std::vector<Case> cases = {
      {"'<x>&'", "'<x>&' is not a valid fluid name"},
      {"a/b", "'a/b' is not a valid fluid name"},
      {"''", "is not a valid fluid name"},
      {"'two words'", "'two words' is not a valid fluid name"},
      {std::string(101, 'n'), "the name is 101 bytes long"},
  };
  for (const Case& c : cases)
    for (const std::string mode : {"--scene-snippet", "--out x.ply"}) {
      const RunResult r = runSoftsub("fill box.obj --spacing 1 " + mode + " --name " + c.name, tmp.path());
      EXPECT_EQ(r.code, 2) << c.name << " " << mode << ": " << r.err;
      EXPECT_EQ(r.err.rfind("error: command line: --name: ", 0), 0u) << r.err;
      EXPECT_NE(r.err.find(c.problem), std::string::npos) << r.err;
      EXPECT_NE(r.err.find("(allowed: letters, digits, _ and -, at most 100 characters"), std::string::npos) << r.err;
      EXPECT_TRUE(r.out.empty()) << c.name << " " << mode;
      EXPECT_EQ(listEntries(tmp.path()), std::vector<std::string>{"box.obj"}) << c.name << " " << mode;
    }
  const RunResult ok = runSoftsub("fill box.obj --spacing 1 --name " + std::string(100, 'n'), tmp.path());
  EXPECT_EQ(ok.code, 0) << ok.err;
  EXPECT_NE(ok.out.find("<Name>" + std::string(100, 'n') + "</Name>"), std::string::npos);
}

}  // namespace
}  // namespace softsub::apptest
