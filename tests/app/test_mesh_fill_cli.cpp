// Mesh fills through `softsub run`: a scene filling a mesh next to it runs; a bad mesh or
// a path leaving the scene's folder exits 2 at the <Geometry> line and writes nothing.
#include <gtest/gtest.h>

#include <fstream>

#include "app_test_util.h"
#include "support/mesh_files.h"

namespace softsub::apptest {
namespace {

void writeText(const fs::path& file, const std::string& text) { scenarios::writeTextFile(file, text); }
using scenarios::boxObj;

// One fluid filling the mesh at geometry; <Geometry> is on line 7.
std::string meshScene(const std::string& geometry) {
  return "<Scene version=\"1\">\n<Environment><Width>10</Width><Height>10</Height><Depth>10</Depth>"
         "</Environment>\n<Fluid>\n<Name>goo</Name>\n<Fill>\n<Shape>mesh</Shape>\n<Geometry>" +
         geometry + "</Geometry>\n<Spacing>0.5</Spacing>\n</Fill>\n</Fluid>\n</Scene>\n";
}

TEST(MeshFillCli, SceneFillingAMeshRunsFromAnyFolder) {
  TempDir tmp;
  writeText(tmp / "shot/cubeGeo/cube.obj", boxObj(2.0));
  writeText(tmp / "shot/t.scene", meshScene("cubeGeo/cube.obj"));
  // Run from the parent folder: the mesh resolves against the scene's folder, not the cwd.
  const RunResult r = runSoftsub("run shot/t.scene --frames 2 --formats sim", tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  const std::vector<std::string> files = listFrameFiles(tmp / "shot/tSim");
  EXPECT_EQ(files.size(), 3u) << ::testing::PrintToString(files);  // frames 0, 1, 2
  const RunResult info = runSoftsub("info shot/t.scene", tmp.path());
  ASSERT_EQ(info.code, 0) << info.err;
  EXPECT_NE(info.out.find("goo: 64 particles"), std::string::npos) << info.out;  // 4^3 inside
}

// Exit 2, the message at the <Geometry> line, and nothing written next to the scene.
void expectRefused(const TempDir& tmp, const std::string& problem) {
  const std::vector<std::string> before = listFrameFiles(tmp.path());
  const RunResult r = runSoftsub("run t.scene --frames 2", tmp.path());
  EXPECT_EQ(r.code, 2) << r.err;
  const std::string head = "error: t.scene:7: Fluid 'goo'/Fill[1]/Geometry: ";
  EXPECT_EQ(r.err.rfind(head, 0), 0u) << r.err;
  EXPECT_NE(r.err.find(problem), std::string::npos) << r.err;
  EXPECT_EQ(listFrameFiles(tmp.path()), before);
  EXPECT_FALSE(fs::exists(tmp / "tSim"));
}

// A box or sphere fill that makes nothing is refused when the scene is read; a mesh
// fill's count is known once it is filled, and one that made nothing ran with an empty
// fluid, exit 0. Now exit 2 at the <Fill> line, before anything is written.
TEST(MeshFillCli, AMeshFillThatMakesNoParticlesExitsTwoAtTheFillLine) {
  TempDir tmp;
  writeText(tmp / "geo/tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");  // open: no inside
  writeText(tmp / "t.scene", meshScene("geo/tri.obj"));
  const RunResult r = runSoftsub("run t.scene --frames 2", tmp.path());
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(
      r.err.find("error: t.scene:5: Fluid 'goo'/Fill[1]: the mesh fill of 'geo/tri.obj' makes no particles"),
      std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(tmp / "tSim"));
}

TEST(MeshFillCli, GarbageMeshExitsTwoAtTheGeometryLine) {
  TempDir tmp;
  writeText(tmp / "geo/junk.obj", "this is not a mesh\n");
  writeText(tmp / "t.scene", meshScene("geo/junk.obj"));
  expectRefused(tmp, "cannot use the mesh 'geo/junk.obj'");
}

TEST(MeshFillCli, MissingMeshExitsTwoNotThree) {
  TempDir tmp;
  writeText(tmp / "t.scene", meshScene("geo/missing.obj"));
  expectRefused(tmp, "cannot use the mesh 'geo/missing.obj'");
}

TEST(MeshFillCli, PathsLeavingTheSceneFolderExitTwo) {
  TempDir tmp;
  writeText(tmp / "outside/cube.obj", boxObj(1.0));
  writeText(tmp / "scene/t.scene", meshScene("../outside/cube.obj"));
  {
    const RunResult r = runSoftsub("run t.scene --frames 2", tmp / "scene");
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_NE(r.err.find("leaves the scene's folder"), std::string::npos) << r.err;
  }
  writeText(tmp / "scene/t.scene", meshScene((tmp / "outside/cube.obj").string()));
  {
    const RunResult r = runSoftsub("run t.scene --frames 2", tmp / "scene");
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_NE(r.err.find("is an absolute path"), std::string::npos) << r.err;
  }
  std::error_code ec;
  fs::create_directory_symlink(tmp / "outside", tmp / "scene/linkGeo", ec);
  if (ec) GTEST_SKIP() << "cannot make a symbolic link: " << ec.message();
  writeText(tmp / "scene/t.scene", meshScene("linkGeo/cube.obj"));
  {
    const RunResult r = runSoftsub("run t.scene --frames 2", tmp / "scene");
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_EQ(r.err.rfind("error: t.scene:7: Fluid 'goo'/Fill[1]/Geometry: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find("outside the scene's folder"), std::string::npos) << r.err;
  }
  EXPECT_EQ(listEntries(tmp / "scene"), (std::vector<std::string>{"linkGeo", "t.scene"}));
}

}  // namespace
}  // namespace softsub::apptest
