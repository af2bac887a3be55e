// Objects with mesh files: a scene folder with meshes, read with readSceneFile. The
// Geometry path rules are the mesh fills' (one code path); a dynamic mesh-shaped body
// must be closed; the mesh's voxel bound at the object's particle size counts toward the
// particle cap. The rules that need no file are rows of reader_error_rows.h.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <sstream>

#include "core/error.h"
#include "scene/compile.h"
#include "scene/reader.h"
#include "scene/writer.h"
#include "scene_test_util.h"
#include "support/mesh_files.h"

namespace softsub::scene {
namespace {

namespace fs = std::filesystem;

using scenarios::boxObj;
using testing::readFileError;
using testing::TempFolder;

void writeText(const fs::path& file, const std::string& text) { scenarios::writeTextFile(file, text); }

// The unit box [0,1]^3 with its top face missing: an open mesh.
std::string openBoxObj() {
  std::string s;
  for (int k = 0; k < 8; ++k) {
    s += "v " + std::to_string(k & 1) + ' ' + std::to_string((k & 2) >> 1) + ' ' +
         std::to_string((k & 4) >> 2) + '\n';
  }
  return s + "f 1 5 7 3\nf 2 4 8 6\nf 1 2 6 5\nf 1 3 4 2\nf 5 6 8 7\n";
}

// A scene with a fluid and one object; the object's <Geometry> is on line 5.
std::string objectScene(const std::string& geometry, const std::string& extra = "") {
  return "<Scene version=\"1\">\n"
         "<Fluid><Name>w</Name><Fill><Shape>box</Shape><Max>2 2 2</Max></Fill></Fluid>\n"
         "<Object>\n"
         "<Name>body</Name>\n"
         "<Geometry>" + geometry + "</Geometry>\n" + extra +
         "</Object>\n"
         "</Scene>\n";
}

// A body's particles sit centred in its shape: the lattice starts at the mesh's low
// corner, and a 2-unit box at particle size 0.6 had its particles reach its low faces and
// stop 0.2 short of its high ones (it rested 0.2 deep in the floor on three faces).
TEST(ObjectMesh, BodyParticlesAreCentredInTheShapeWhateverTheParticleSize) {
  for (const double size : {0.6, 0.5, 0.45}) {
    const std::string text = "<Scene version=\"1\">\n<Object><Name>box</Name><Shape>box</Shape><Size>2 2 2</Size>"
                             "<ParticleSize>" + std::to_string(size) + "</ParticleSize></Object>\n</Scene>\n";
    const Compiled c = compile(readSceneText(text, "t.scene"));
    const rigid::BodySet& b = c.model.bodies;
    ASSERT_GT(b.particleCount(), 0U);
    for (const std::vector<float>* axis : {&b.ox, &b.oy, &b.oz}) {
      const auto [lo, hi] = std::minmax_element(axis->begin(), axis->end());
      EXPECT_NEAR(*lo + *hi, 0.0, 1e-5) << size;        // centred on the box's centre of mass
      EXPECT_LE(*hi + 0.5 * size, 1.0 + 0.5 * size) << size;  // within half a particle of the faces
      EXPECT_GE(*hi + 0.5 * size, 1.0 - 0.5 * size) << size;
    }
  }
}

// A body with a part thinner than its particles (a table: a leg 3 high, 6 particles of
// 0.5, under a top 0.2 thick) is not centred: the top's surface samples stick out of the
// mesh by up to half a particle, so centring on them sank the leg's particles 0.15 below
// its foot and the table stood 0.15 above the floor. Its lattice stays flush with the
// foot, as a body of whole particles is.
TEST(ObjectMesh, ABodyWithThinPartsKeepsItsLatticeFlushWithItsThickParts) {
  TempFolder tmp;
  std::string obj;
  int base = 0;
  for (const auto& [lo, hi] : {std::pair{Vec3(0, 0, 0), Vec3(2, 3, 2)}, std::pair{Vec3(-3, 3, -3), Vec3(5, 3.2, 5)}}) {
    for (int k = 0; k < 8; ++k)
      obj += fmt::format("v {} {} {}\n", k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(), k & 4 ? hi.z() : lo.z());
    for (const char* face : {"1 5 7 3", "2 4 8 6", "1 2 6 5", "3 7 8 4", "1 3 4 2", "5 6 8 7"}) {
      obj += "f";
      std::istringstream corners(face);
      for (int v = 0; corners >> v;) obj += fmt::format(" {}", v + base);
      obj += "\n";
    }
    base += 8;
  }
  writeText(tmp.path() / "table.obj", obj);
  writeText(tmp.path() / "t.scene", objectScene("table.obj", "<ParticleSize>0.5</ParticleSize>\n"));
  const Compiled c = compile(readSceneFile((tmp.path() / "t.scene").string()));
  const rigid::BodySet& b = c.model.bodies;
  ASSERT_EQ(b.bodies.size(), 1U);
  const double lowest = *std::min_element(b.oy.begin(), b.oy.end()) - b.bodies[0].originInBody.y();
  EXPECT_NEAR(lowest, 0.25, 1e-5) << "the foot's particles sit half a particle above the foot";
  const double highest = *std::max_element(b.oy.begin(), b.oy.end()) - b.bodies[0].originInBody.y();
  EXPECT_NEAR(highest, 3.25, 1e-5) << "the top's samples, within half a particle of the top";
}

TEST(ObjectMesh, ClosedMeshIsAMeshShapedBodyAndRoundTrips) {
  TempFolder tmp;
  writeText(tmp.path() / "bodyGeo/cube.obj", boxObj(1.0));
  writeText(tmp.path() / "t.scene", objectScene("bodyGeo/./cube.obj", "<Mass>3</Mass>\n"));
  const SceneDesc d = readSceneFile((tmp.path() / "t.scene").string());
  ASSERT_EQ(d.objects.size(), 1u);
  const ObjectDesc& o = d.objects[0];
  EXPECT_EQ(o.name, "body");
  EXPECT_EQ(o.geometry, "bodyGeo/./cube.obj");  // kept as written
  EXPECT_EQ(o.shape, ObjectShape::Mesh);
  EXPECT_TRUE(o.size.empty());
  EXPECT_EQ(o.particleSize, 0);  // automatic
  EXPECT_EQ(o.mass, 3);
  EXPECT_TRUE(o.isDynamic);
  EXPECT_EQ(o.line, 3);

  const std::string text = writeSceneText(d);
  EXPECT_NE(text.find("<Geometry>bodyGeo/./cube.obj</Geometry>"), std::string::npos) << text;
  EXPECT_EQ(readSceneText(text, (tmp.path() / "again.scene").string()), d);
}

TEST(ObjectMesh, DefaultNamesCountObjectsFromOne) {
  TempFolder tmp;
  writeText(tmp.path() / "cube.obj", boxObj(1.0));
  writeText(tmp.path() / "t.scene",
            "<Scene version=\"1\">\n"
            "<Object><Geometry>cube.obj</Geometry></Object>\n"
            "<Object><Name>named</Name><Shape>sphere</Shape><Size>1</Size></Object>\n"
            "<Object><Shape>box</Shape><Geometry>cube.obj</Geometry></Object>\n"
            "</Scene>\n");
  const SceneDesc d = readSceneFile((tmp.path() / "t.scene").string());
  ASSERT_EQ(d.objects.size(), 3u);
  EXPECT_EQ(d.objects[0].name, "object1");
  EXPECT_EQ(d.objects[1].name, "named");
  EXPECT_EQ(d.objects[2].name, "object3");
  // A primitive Shape with Geometry: the mesh gives the particles, the primitive the
  // inertia; Size may be left to the mesh.
  EXPECT_EQ(d.objects[2].shape, ObjectShape::Box);
  EXPECT_TRUE(d.objects[2].size.empty());
  EXPECT_EQ(readSceneText(writeSceneText(d), (tmp.path() / "again.scene").string()), d);
}

TEST(ObjectMesh, OpenMeshCannotBeADynamicMeshShapedBody) {
  TempFolder tmp;
  writeText(tmp.path() / "geo/open.obj", openBoxObj());
  writeText(tmp.path() / "t.scene", objectScene("geo/open.obj"));
  const InputError e = readFileError(tmp.path() / "t.scene");
  EXPECT_EQ(e.where().file, (tmp.path() / "t.scene").string());
  EXPECT_EQ(e.where().line, 5);
  EXPECT_EQ(e.where().element, "Object 'body'/Geometry");
  EXPECT_NE(e.problem().find("the mesh 'geo/open.obj' cannot be a dynamic body: the mesh is not closed"),
            std::string::npos)
      << e.what();
  EXPECT_NE(e.allowed().find("a closed (watertight) triangle mesh"), std::string::npos) << e.what();
  EXPECT_NE(e.allowed().find("<IsDynamic>false</IsDynamic>"), std::string::npos) << e.what();
}

TEST(ObjectMesh, OpenMeshIsFineStaticOrWithAPrimitiveShape) {
  TempFolder tmp;
  writeText(tmp.path() / "open.obj", openBoxObj());
  writeText(tmp.path() / "static.scene", objectScene("open.obj", "<IsDynamic>false</IsDynamic>\n"));
  EXPECT_FALSE(readSceneFile((tmp.path() / "static.scene").string()).objects[0].isDynamic);
  writeText(tmp.path() / "box.scene", objectScene("open.obj", "<Shape>box</Shape>\n<Size>1 1 1</Size>\n"));
  const SceneDesc d = readSceneFile((tmp.path() / "box.scene").string());
  EXPECT_EQ(d.objects[0].shape, ObjectShape::Box);
  EXPECT_EQ(d.objects[0].size, (std::vector<double>{1, 1, 1}));
}

TEST(ObjectMesh, BoundAtTheScaledParticleSizeCountsTowardTheCap) {
  TempFolder tmp;
  writeText(tmp.path() / "cube.obj", boxObj(2.0));
  // The fluid makes 8 particles; the 2-unit cube at ParticleSize 0.25 a grid of 8^3 = 512.
  writeText(tmp.path() / "t.scene", objectScene("cube.obj", "<ParticleSize>0.25</ParticleSize>\n"));
  EXPECT_NO_THROW((void)readSceneFile((tmp.path() / "t.scene").string(), {.maxParticles = 520}));
  InputError e = readFileError(tmp.path() / "t.scene", {.maxParticles = 519});
  EXPECT_EQ(e.where().line, 3);
  EXPECT_EQ(e.where().element, "Object 'body'");
  EXPECT_NE(e.problem().find("may make 520 particles"), std::string::npos) << e.what();
  EXPECT_NE(e.problem().find("more than the cap of 519"), std::string::npos) << e.what();
  // Scaled by 2: a 4-unit cube, 16^3 = 4096 voxels.
  writeText(tmp.path() / "scaled.scene",
            objectScene("cube.obj", "<ParticleSize>0.25</ParticleSize>\n<UniformScale>2</UniformScale>\n"));
  EXPECT_NO_THROW((void)readSceneFile((tmp.path() / "scaled.scene").string(), {.maxParticles = 4104}));
  e = readFileError(tmp.path() / "scaled.scene", {.maxParticles = 4103});
  EXPECT_NE(e.problem().find("may make 4104 particles"), std::string::npos) << e.what();
  // Automatic particle size: 1/20 of the largest extent, so about 20^3 whatever the scale.
  writeText(tmp.path() / "auto.scene", objectScene("cube.obj", "<UniformScale>1000</UniformScale>\n"));
  EXPECT_NO_THROW((void)readSceneFile((tmp.path() / "auto.scene").string(), {.maxParticles = 21 * 21 * 21 + 8}));
  EXPECT_NE(readFileError(tmp.path() / "auto.scene", {.maxParticles = 19 * 19 * 19 + 8}).problem().find(
                "more than the cap"),
            std::string::npos);
}

TEST(ObjectMesh, PathRulesAreTheMeshFills) {
  TempFolder tmp;
  writeText(tmp.path() / "outside/cube.obj", boxObj(1.0));
  writeText(tmp.path() / "scene/junk.obj", "not a mesh\n");
  writeText(tmp.path() / "scene/escape.scene", objectScene("../outside/cube.obj"));
  InputError e = readFileError(tmp.path() / "scene/escape.scene");
  EXPECT_EQ(e.where().line, 5);
  EXPECT_EQ(e.where().element, "Object 'body'/Geometry");
  EXPECT_NE(e.problem().find("leaves the scene's folder"), std::string::npos) << e.what();

  writeText(tmp.path() / "scene/junk.scene", objectScene("junk.obj"));
  e = readFileError(tmp.path() / "scene/junk.scene");
  EXPECT_EQ(e.where().line, 5);
  EXPECT_NE(e.problem().find("cannot use the mesh 'junk.obj'"), std::string::npos) << e.what();

  std::error_code ec;
  fs::create_directory_symlink(tmp.path() / "outside", tmp.path() / "scene/linkGeo", ec);
  if (ec) GTEST_SKIP() << "cannot make a symbolic link: " << ec.message();
  writeText(tmp.path() / "scene/link.scene", objectScene("linkGeo/cube.obj"));
  e = readFileError(tmp.path() / "scene/link.scene");
  EXPECT_EQ(e.where().element, "Object 'body'/Geometry");
  EXPECT_NE(e.problem().find("outside the scene's folder"), std::string::npos) << e.what();
}

TEST(ObjectMesh, PairMayNameAnObjectAndAFluid) {
  TempFolder tmp;
  writeText(tmp.path() / "cube.obj", boxObj(1.0));
  writeText(tmp.path() / "t.scene",
            "<Scene version=\"1\">\n"
            "<Interactions><Pair><A>body</A><B>w</B><Linear/><RelativeVelocity>3</RelativeVelocity></Pair>"
            "<FluidObject><LennardJones/></FluidObject></Interactions>\n"
            "<Fluid><Name>w</Name><Fill><Shape>box</Shape><Max>2 2 2</Max></Fill></Fluid>\n"
            "<Object><Name>body</Name><Geometry>cube.obj</Geometry></Object>\n"
            "</Scene>\n");
  const SceneDesc d = readSceneFile((tmp.path() / "t.scene").string());
  ASSERT_EQ(d.interactions.pairs.size(), 1u);
  EXPECT_EQ(d.interactions.pairs[0].a, "body");
  EXPECT_EQ(d.interactions.pairs[0].b, "w");
  EXPECT_EQ(d.interactions.pairs[0].interaction.relativeVelocity, 3);
  EXPECT_TRUE(std::holds_alternative<forces::LennardJones>(d.interactions.fluidObject.function));
  // A FluidObject without RelativeVelocity keeps FluidObject's default, 2.
  EXPECT_EQ(d.interactions.fluidObject.relativeVelocity, 2);
}

}  // namespace
}  // namespace softsub::scene
