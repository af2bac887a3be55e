// Mesh fills with real files: a scene folder with meshes, read with readSceneFile (the
// path rules against the scene's folder, the mesh checked at the boundary) and compiled.
// The rules that need no file are rows of reader_error_rows.h.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"
#include "geometry/mesh_loader.h"
#include "scene/compile.h"
#include "scene/reader.h"
#include "scene/writer.h"
#include "scene_test_util.h"
#include "support/mesh_files.h"

namespace softsub::scene {
namespace {

namespace fs = std::filesystem;

using testing::readFileError;
using testing::TempFolder;

void writeText(const fs::path& file, const std::string& text) { scenarios::writeTextFile(file, text); }
using scenarios::boxObj;

// A scene with one fluid 'goo' filling the mesh at geometry.
std::string meshScene(const std::string& geometry, double spacing, const std::string& extra = "") {
  return "<Scene version=\"1\">\n<Fluid>\n<Name>goo</Name>\n<Fill>\n<Shape>mesh</Shape>\n"
         "<Geometry>" + geometry + "</Geometry>\n<Spacing>" + std::to_string(spacing) +
         "</Spacing>\n" + extra + "</Fill>\n</Fluid>\n</Scene>\n";
}

TEST(MeshFill, CubeFillsItsVolumeWithin3Percent) {
  TempFolder tmp;
  writeText(tmp.path() / "cubeGeo/cube.obj", boxObj(2.0));
  const fs::path scene = tmp.path() / "cube.scene";
  writeText(scene, meshScene("cubeGeo/cube.obj", 0.25));
  const SceneDesc d = readSceneFile(scene.string());
  EXPECT_EQ(fs::path(d.baseDir), fs::weakly_canonical(tmp.path()));
  ASSERT_EQ(d.fluids.size(), 1u);
  ASSERT_EQ(d.fluids[0].fills.size(), 1u);
  EXPECT_EQ(d.fluids[0].fills[0].shape, FillShape::Mesh);
  EXPECT_EQ(d.fluids[0].fills[0].geometry, "cubeGeo/cube.obj");
  EXPECT_FALSE(d.fluids[0].fills[0].surface);

  const Compiled c = compile(d);
  const double volume = static_cast<double>(c.state.particles.size()) * 0.25 * 0.25 * 0.25;
  EXPECT_NEAR(volume, 8.0, 0.03 * 8.0);
  ASSERT_EQ(c.model.fluids.size(), 1u);
  EXPECT_EQ(c.model.fluids[0].count, c.state.particles.size());
}

TEST(MeshFill, SurfaceSamplesOnlyNearTheSurface) {
  TempFolder tmp;
  writeText(tmp.path() / "cube.obj", boxObj(4.0));
  writeText(tmp.path() / "solid.scene", meshScene("cube.obj", 0.5));
  writeText(tmp.path() / "shell.scene", meshScene("cube.obj", 0.5, "<Surface>true</Surface>\n"));
  const SceneDesc solid = readSceneFile((tmp.path() / "solid.scene").string());
  const SceneDesc shell = readSceneFile((tmp.path() / "shell.scene").string());
  EXPECT_TRUE(shell.fluids[0].fills[0].surface);
  const std::size_t nSolid = compile(solid).state.particles.size();
  const std::size_t nShell = compile(shell).state.particles.size();
  EXPECT_GT(nShell, 0u);
  EXPECT_LT(nShell, nSolid);  // an 8^3 lattice: 512 inside, the outer layer 296
}

TEST(MeshFill, RoundTripsThroughTheWriterKeepingThePathAsWritten) {
  TempFolder tmp;
  writeText(tmp.path() / "geo/cube.obj", boxObj(1.0));
  writeText(tmp.path() / "a.scene", meshScene("geo/./cube.obj", 0.25, "<Surface>1</Surface>\n"));
  const SceneDesc d = readSceneFile((tmp.path() / "a.scene").string());
  const std::string text = writeSceneText(d);
  EXPECT_NE(text.find("<Geometry>geo/./cube.obj</Geometry>"), std::string::npos) << text;
  EXPECT_NE(text.find("<Surface>true</Surface>"), std::string::npos) << text;
  EXPECT_EQ(readSceneText(text, (tmp.path() / "again.scene").string()), d);
}

TEST(MeshFill, BoundCountsTowardTheParticleCap) {
  TempFolder tmp;
  writeText(tmp.path() / "cube.obj", boxObj(2.0));
  writeText(tmp.path() / "t.scene", meshScene("cube.obj", 0.25));  // 8^3 = 512 voxels
  EXPECT_NO_THROW((void)readSceneFile((tmp.path() / "t.scene").string(), {.maxParticles = 512}));
  const InputError e = readFileError(tmp.path() / "t.scene", {.maxParticles = 511});
  EXPECT_EQ(e.where().element, "Fluid 'goo'");
  EXPECT_NE(e.problem().find("more than the cap of 511"), std::string::npos) << e.what();
}

TEST(MeshFill, GarbageMeshIsAnInputErrorAtTheGeometryLine) {
  TempFolder tmp;
  writeText(tmp.path() / "geo/junk.obj", "this is not a mesh\n");
  writeText(tmp.path() / "t.scene", meshScene("geo/junk.obj", 0.5));
  const InputError e = readFileError(tmp.path() / "t.scene");
  EXPECT_EQ(e.where().line, 6);
  EXPECT_EQ(e.where().element, "Fluid 'goo'/Fill[1]/Geometry");
  EXPECT_NE(e.problem().find("cannot use the mesh 'geo/junk.obj'"), std::string::npos) << e.what();
}

TEST(MeshFill, MeshWithoutTrianglesIsAnInputError) {
  TempFolder tmp;
  writeText(tmp.path() / "points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  writeText(tmp.path() / "t.scene", meshScene("points.obj", 0.5));
  const InputError e = readFileError(tmp.path() / "t.scene");
  EXPECT_EQ(e.where().line, 6);
  EXPECT_NE(e.problem().find("cannot use the mesh 'points.obj'"), std::string::npos) << e.what();
}

TEST(MeshFill, MissingMeshIsAnInputErrorNotAnIoError) {
  TempFolder tmp;
  writeText(tmp.path() / "t.scene", meshScene("geo/missing.obj", 0.5));
  const InputError e = readFileError(tmp.path() / "t.scene");
  EXPECT_EQ(e.where().line, 6);
  EXPECT_NE(e.problem().find("'geo/missing.obj'"), std::string::npos) << e.what();
}

TEST(MeshFill, FolderInsteadOfAMeshIsAnInputError) {
  TempFolder tmp;
  fs::create_directories(tmp.path() / "geo/blob.obj");
  writeText(tmp.path() / "t.scene", meshScene("geo/blob.obj", 0.5));
  const InputError e = readFileError(tmp.path() / "t.scene");
  EXPECT_EQ(e.where().element, "Fluid 'goo'/Fill[1]/Geometry");
}

// A glTF cube [-1, 1]^3 whose buffer (8 float positions, 36 16-bit indices) is at `uri`.
std::string gltfCube(const std::string& uri) {
  return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],)"
         R"("meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],)"
         R"("buffers": [{"uri": ")" + uri + R"(", "byteLength": 168}],)"
         R"("bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 96}, {"buffer": 0, "byteOffset": 96, "byteLength": 72}],)"
         R"("accessors": [{"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3", "min": [-1, -1, -1], "max": [1, 1, 1]},)"
         R"({"bufferView": 1, "componentType": 5123, "count": 36, "type": "SCALAR"}]})";
}

void writeCubeBuffer(const fs::path& file) {
  std::string bytes;
  for (int k = 0; k < 8; ++k) {
    const float v[3] = {(k & 1) ? 1.f : -1.f, (k & 2) ? 1.f : -1.f, (k & 4) ? 1.f : -1.f};
    bytes.append(reinterpret_cast<const char*>(v), sizeof v);
  }
  const std::uint16_t faces[36] = {0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6, 0, 1, 5, 0, 5, 4,
                                   2, 6, 7, 2, 7, 3, 0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5};
  bytes.append(reinterpret_cast<const char*>(faces), sizeof faces);
  fs::create_directories(file.parent_path());
  std::ofstream(file, std::ios::binary) << bytes;
}

// The path rule holds for the files a mesh refers to as well: a glTF's buffer outside the
// scene's folder is refused and named (it used to be read), one inside is read; an OBJ's
// material library outside is not read, with a warning, and the mesh is still usable.
TEST(MeshFill, FilesAMeshRefersToMustLieInTheSceneFolderToo) {
  TempFolder tmp;
  writeCubeBuffer(tmp.path() / "outside.bin");
  writeCubeBuffer(tmp.path() / "scene/geo/cube.bin");
  writeText(tmp.path() / "scene/geo/out.gltf", gltfCube("../../outside.bin"));
  writeText(tmp.path() / "scene/geo/in.gltf", gltfCube("cube.bin"));
  writeText(tmp.path() / "scene/out.scene", meshScene("geo/out.gltf", 0.5));
  writeText(tmp.path() / "scene/in.scene", meshScene("geo/in.gltf", 0.5));

  const InputError e = readFileError(tmp.path() / "scene/out.scene");
  EXPECT_EQ(e.where().line, 6);
  EXPECT_NE(e.problem().find("refers to '" + (tmp.path() / "outside.bin").string() + "', outside the scene's folder"),
            std::string::npos)
      << e.what();
  // What is allowed is the loader's: what would fix the refusal, not "a readable mesh".
  EXPECT_NE(e.allowed().find("lie in the scene's folder too"), std::string::npos) << e.what();
  const SceneDesc in = readSceneFile((tmp.path() / "scene/in.scene").string());
  EXPECT_EQ(compile(in).state.particles.size(), 64U);  // a 2 x 2 x 2 cube at spacing 0.5

  // A buffer inside the folder that is a link to one outside: named with where it leads.
  std::error_code ec;
  fs::create_symlink(tmp.path() / "outside.bin", tmp.path() / "scene/geo/link.bin", ec);
  if (!ec) {
    writeText(tmp.path() / "scene/geo/link.gltf", gltfCube("link.bin"));
    writeText(tmp.path() / "scene/link.scene", meshScene("geo/link.gltf", 0.5));
    const InputError l = readFileError(tmp.path() / "scene/link.scene");
    EXPECT_NE(l.problem().find("link.bin' (a link to '" + (tmp.path() / "outside.bin").string() + "')"),
              std::string::npos)
        << l.what();
  }

  writeText(tmp.path() / "scene/geo/cube.obj", "mtllib ../../outside.mtl\n" + boxObj(1.0));
  writeText(tmp.path() / "outside.mtl", "newmtl a\nKd 1 0 0\n");
  geometry::MeshLoadReport report;
  const geometry::TriangleMesh mesh =
      geometry::loadMesh(tmp.path() / "scene/geo/cube.obj", &report, tmp.path() / "scene");
  EXPECT_EQ(mesh.triangles.size(), 12U);
  ASSERT_FALSE(report.warnings.empty());
  EXPECT_NE(report.warnings.back().find("did not read '" + (tmp.path() / "outside.mtl").string() + "'"),
            std::string::npos)
      << report.warnings.back();
  // Two refused files: both named.
  writeText(tmp.path() / "scene/geo/two.obj", "mtllib ../../outside.mtl\nmtllib ../../other.mtl\n" + boxObj(1.0));
  writeText(tmp.path() / "other.mtl", "newmtl b\nKd 0 1 0\n");
  geometry::MeshLoadReport two;
  (void)geometry::loadMesh(tmp.path() / "scene/geo/two.obj", &two, tmp.path() / "scene");
  ASSERT_FALSE(two.warnings.empty());
  EXPECT_NE(two.warnings.back().find("'" + (tmp.path() / "outside.mtl").string() + "' and '" +
                                     (tmp.path() / "other.mtl").string() + "'"),
            std::string::npos)
      << two.warnings.back();
  // Without a folder to keep to (softsub fill's own mesh), everything is read.
  geometry::MeshLoadReport free;
  (void)geometry::loadMesh(tmp.path() / "scene/geo/cube.obj", &free);
  for (const std::string& w : free.warnings) EXPECT_EQ(w.find("did not read"), std::string::npos) << w;
}

TEST(MeshFill, SymlinkLeavingTheSceneFolderIsRefused) {
  TempFolder tmp;
  writeText(tmp.path() / "outside/cube.obj", boxObj(1.0));
  writeText(tmp.path() / "scene/inside/cube.obj", boxObj(1.0));
  std::error_code ec;
  fs::create_directory_symlink(tmp.path() / "outside", tmp.path() / "scene/linkGeo", ec);
  if (ec) GTEST_SKIP() << "cannot make a symbolic link: " << ec.message();
  fs::create_symlink("inside/cube.obj", tmp.path() / "scene/cube.obj", ec);
  ASSERT_FALSE(ec) << ec.message();

  writeText(tmp.path() / "scene/t.scene", meshScene("linkGeo/cube.obj", 0.25));
  const InputError e = readFileError(tmp.path() / "scene/t.scene");
  EXPECT_EQ(e.where().line, 6);
  EXPECT_EQ(e.where().element, "Fluid 'goo'/Fill[1]/Geometry");
  EXPECT_NE(e.problem().find("outside the scene's folder"), std::string::npos) << e.what();
  EXPECT_NE(e.allowed().find("a path inside the scene's folder"), std::string::npos);

  // A link that stays inside the folder is fine.
  writeText(tmp.path() / "scene/ok.scene", meshScene("cube.obj", 0.25));
  EXPECT_NO_THROW((void)readSceneFile((tmp.path() / "scene/ok.scene").string()));
}

TEST(MeshFill, SceneInASubfolderResolvesAgainstItsOwnFolder) {
  TempFolder tmp;
  writeText(tmp.path() / "shots/a/geo/cube.obj", boxObj(1.0));
  writeText(tmp.path() / "shots/a/t.scene", meshScene("geo/cube.obj", 0.25));
  const SceneDesc d = readSceneFile((tmp.path() / "shots/a/t.scene").string());
  EXPECT_EQ(compile(d).state.particles.size(), 64u);  // 4^3 lattice points inside the unit cube
  // The sibling's folder is outside this scene's folder.
  writeText(tmp.path() / "shots/b/t.scene", meshScene("../a/geo/cube.obj", 0.25));
  EXPECT_NE(readFileError(tmp.path() / "shots/b/t.scene").problem().find("leaves the scene's folder"),
            std::string::npos);
}

}  // namespace
}  // namespace softsub::scene
