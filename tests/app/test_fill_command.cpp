// `softsub fill`: a mesh file to a PLY point cloud or a <Fluid> block.
#include <gtest/gtest.h>

#include <fstream>

#include "app_test_util.h"
#include "cache/ply_format.h"
#include "scene/reader.h"

namespace softsub::apptest {
namespace {

// A closed unit-oriented box [0,a]^3 as an OBJ with quads.
void writeBoxObj(const fs::path& file, double a) {
  std::ofstream out(file);
  for (int k = 0; k < 8; ++k) out << "v " << (k & 1 ? a : 0) << ' ' << (k & 2 ? a : 0) << ' ' << (k & 4 ? a : 0) << '\n';
  // 1-based, counter-clockwise from outside.
  out << "f 1 5 7 3\nf 2 4 8 6\nf 1 2 6 5\nf 3 7 8 4\nf 1 3 4 2\nf 5 6 8 7\n";
}

TEST(FillCommand, WritesAPlyWhoseCountMatchesTheVolume) {
  TempDir tmp;
  writeBoxObj(tmp / "box.obj", 4.0);
  const RunResult r = runSoftsub("fill box.obj --spacing 0.5 --out box.ply", tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  const cache::PlyCloud cloud = cache::readPlyFile(tmp / "box.ply");
  EXPECT_NEAR(static_cast<double>(cloud.vertexCount), 4.0 * 4 * 4 / (0.5 * 0.5 * 0.5), 0.03 * 512);
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
}

TEST(FillCommand, BadInputExitsTwoMissingFileThree) {
  TempDir tmp;
  writeBoxObj(tmp / "box.obj", 2.0);
  EXPECT_EQ(runSoftsub("fill box.obj --spacing 0 --out x.ply", tmp.path()).code, 2);
  EXPECT_EQ(runSoftsub("fill box.obj --spacing -1", tmp.path()).code, 2);
  EXPECT_EQ(runSoftsub("fill box.obj", tmp.path()).code, 2);  // --spacing is required
  EXPECT_EQ(runSoftsub("fill missing.obj --spacing 1", tmp.path()).code, 3);
  {
    std::ofstream(tmp / "junk.obj") << "this is not a mesh\n";
  }
  EXPECT_EQ(runSoftsub("fill junk.obj --spacing 1", tmp.path()).code, 2);
  EXPECT_EQ(listEntries(tmp.path()), (std::vector<std::string>{"box.obj", "junk.obj"}));
}

}  // namespace
}  // namespace softsub::apptest
