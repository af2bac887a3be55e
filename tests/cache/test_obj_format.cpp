// The rigid bodies' OBJ files: exact round trips, 1-based faces, refusal of bad input,
// and the frame writer writing each mesh once, only with `.sim` output.
#include <gtest/gtest.h>

#include "cache/atomic_file.h"
#include "cache/cache_test_support.h"
#include "cache/frame_writer.h"
#include "cache/obj_format.h"
#include "core/error.h"

namespace softsub::cache {
namespace {

ObjectMesh tetrahedron() {
  ObjectMesh m;
  m.name = "tet";
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.1, 0.2, 1.0 / 3.0}};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  return m;
}

TEST(ObjFormat, RoundTripsExactlyWithOneBasedFaces) {
  const ObjectMesh m = tetrahedron();
  const std::string text = encodeObj(m);
  EXPECT_NE(text.find("\nf 1 3 2\n"), std::string::npos) << text;
  const ObjectMesh back = decodeObj(text, "t.obj");
  EXPECT_EQ(back.name, "tet");
  EXPECT_EQ(back.vertices, m.vertices);  // shortest round-trip numbers: bit-exact
  EXPECT_EQ(back.triangles, m.triangles);
}

// The fluid surfaces' OBJ: vn lines and f a//a faces, read back exactly; other packages'
// f a/t/n faces keep their vertex.
TEST(ObjFormat, NormalsRoundTripAndFacesWithSlashesRead) {
  ObjectMesh m;
  m.name = "honey";
  m.comment = "fluid surface";
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.normals = {{0, 0, 1}, {0, 0.6, 0.8}, {0.1, 0, 1}};
  m.triangles = {{0, 1, 2}};
  const std::string text = encodeObj(m);
  EXPECT_NE(text.find("# softsub fluid surface: 3 vertices, 1 triangles\n"), std::string::npos);
  EXPECT_NE(text.find("vn 0 0.6 0.8\n"), std::string::npos);
  EXPECT_NE(text.find("f 1//1 2//2 3//3\n"), std::string::npos);
  const ObjectMesh back = decodeObj(text, "s.obj");
  EXPECT_EQ(back.vertices, m.vertices);
  EXPECT_EQ(back.normals, m.normals);
  EXPECT_EQ(back.triangles, m.triangles);
  EXPECT_EQ(decodeObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/4/7 2/5/8 3/6/9\n", "t.obj").triangles, m.triangles);
  m.normals.pop_back();
  EXPECT_THROW(static_cast<void>(encodeObj(m)), std::invalid_argument);
}

TEST(ObjFormat, RefusesBadInput) {
  ObjectMesh bad = tetrahedron();
  bad.triangles.push_back({0, 1, 9});
  EXPECT_THROW(static_cast<void>(encodeObj(bad)), std::invalid_argument);
  EXPECT_THROW(static_cast<void>(decodeObj("v 1 2\n", "a.obj")), InputError);
  EXPECT_THROW(static_cast<void>(decodeObj("v 0 0 0\nf 0 1 1\n", "b.obj")), InputError);
  EXPECT_THROW(static_cast<void>(decodeObj("v 0 0 0\nf 1 1 2\n", "c.obj")), InputError);
  try {
    static_cast<void>(decodeObj("# c\nv 0 0 x\n", "d.obj"));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "d.obj");
    EXPECT_EQ(e.where().line, 2);
  }
}

TEST(ObjFormat, FrameWriterWritesEachMeshOnceBesideTheFrames) {
  test::ScratchDir dir;
  FrameWriter writer(dir.path() / "out", "demo", Formats{true, false, false});
  writer.setObjectMeshes({tetrahedron()});
  FrameSnapshot frame = test::makeFrame();
  writer.onFrame(frame);
  const std::filesystem::path obj = dir.path() / "out" / geometryFileName("demo", "tet");
  EXPECT_EQ(geometryFileName("demo", "tet"), "demoGeo/tet.obj");
  ASSERT_TRUE(std::filesystem::exists(obj));
  EXPECT_EQ(readFileBytes(obj), encodeObj(tetrahedron()));
  EXPECT_EQ(writer.lastWritten().size(), 2U);  // the mesh, then the frame
  frame.frame = 1;
  writer.onFrame(frame);
  EXPECT_EQ(writer.lastWritten().size(), 1U);  // the frame only

  // Without .sim output nothing names the meshes: none is written.
  FrameWriter plyOnly(dir.path() / "ply", "demo", Formats{false, false, true});
  plyOnly.setObjectMeshes({tetrahedron()});
  plyOnly.onFrame(frame);
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "ply" / "demoGeo"));
}

}  // namespace
}  // namespace softsub::cache
