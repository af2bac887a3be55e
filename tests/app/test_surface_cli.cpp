// The fluids' surfaces end to end: `run --formats ...,mesh,vdb` and `softsub mesh` on a
// recorded folder.
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "app_test_util.h"
#include "cache/obj_format.h"
#include "surface/surface.h"

namespace softsub::apptest {
namespace {

/// The decoded OBJ as the surface module's mesh type, for its checks.
surface::SurfaceMesh asSurfaceMesh(const cache::ObjectMesh& obj) {
  surface::SurfaceMesh m;
  for (const auto& v : obj.vertices)
    m.vertices.push_back({static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])});
  for (const auto& n : obj.normals)
    m.normals.push_back({static_cast<float>(n[0]), static_cast<float>(n[1]), static_cast<float>(n[2])});
  m.triangles = obj.triangles;
  return m;
}

std::string frameName(int frame) { return "honey.000" + std::to_string(frame); }

TEST(SurfaceCli, RunWritesClosedMeshesOfTheFluidsVolumeAndLevelSets) {
  TempDir tmp;
  const fs::path scene = examplesDir() / "honey-drop.scene";
  const RunResult r = runSoftsub("run -q --frames 2 --formats sim,mesh,vdb --out " + quote(tmp / "o") + " " +
                                     quote(scene),
                                 tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  const double count = fluidCounts(scene).at(0);  // honey-drop: ParticleSize 1
  EXPECT_EQ(listFrameFiles(tmp / "o/mesh"),
            (std::vector<std::string>{"honey.0000.obj", "honey.0001.obj", "honey.0002.obj"}));
  for (int f = 0; f <= 2; ++f) {
    const fs::path obj = tmp / "o/mesh" / (frameName(f) + ".obj");
    const cache::ObjectMesh decoded = cache::decodeObj(readFile(obj), obj.string());
    EXPECT_EQ(decoded.name, "honey");
    ASSERT_EQ(decoded.normals.size(), decoded.vertices.size());
    const surface::SurfaceMesh mesh = asSurfaceMesh(decoded);
    ASSERT_FALSE(mesh.triangles.empty());
    EXPECT_TRUE(surface::isClosedAndOriented(mesh)) << obj;
    EXPECT_NEAR(surface::enclosedVolume(mesh), count, 0.05 * count) << obj;
    const surface::LevelSet back = surface::LevelSet::readVdb(tmp / "o/vdb" / (frameName(f) + ".vdb"));
    EXPECT_FALSE(back.empty());
    EXPECT_NEAR(back.voxelSize(), 0.5, 1e-6);  // half the particle size (1), the default
  }
  // Nothing half-written is left behind.
  EXPECT_EQ(listFrameFiles(tmp / "o/vdb").size(), 3u);
}

TEST(SurfaceCli, VoxelSizeReachesTheLevelSetsAndIsCheckedFirst) {
  TempDir tmp;
  const fs::path scene = examplesDir() / "honey-drop.scene";  // ParticleSize 1
  const RunResult r = runSoftsub("run -q --frames 0 --formats vdb --voxel-size 0.25 --out " + quote(tmp / "o") + " " +
                                     quote(scene),
                                 tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NEAR(surface::LevelSet::readVdb(tmp / "o/vdb" / (frameName(0) + ".vdb")).voxelSize(), 0.25, 1e-9);
  // Without a surface format, and below blob radius / 64 (1.5 / 64): refused, nothing made.
  for (const std::string bad : {"--formats sim --voxel-size 0.25", "--formats mesh --voxel-size 0.01",
                                "--formats sim --blob-radius 2", "--formats mesh --blob-radius 9"}) {
    const RunResult refused =
        runSoftsub("run -q --frames 0 " + bad + " --out " + quote(tmp / "bad") + " " + quote(scene), tmp.path());
    EXPECT_EQ(refused.code, 2) << bad << ": " << refused.err;
    EXPECT_TRUE(refused.err.find("--voxel-size") != std::string::npos ||
                refused.err.find("--blob-radius") != std::string::npos)
        << refused.err;
    EXPECT_FALSE(fs::exists(tmp / "bad")) << bad;
  }
}

// NaN passes every "<" and ">" test, so a range check written that way let it through
// to the surface stage ("internal error", exit 1, half-made folders). Every command's
// surface options refuse it, and the infinities, before anything is made.
TEST(SurfaceCli, NotANumberOrInfiniteSurfaceOptionsAreRefusedFirst) {
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "honey-drop.scene", tmp.path());
  ASSERT_EQ(runSoftsub("run -q --frames 0 --formats sim " + quote(scene), tmp.path()).code, 0);
  const fs::path recorded = tmp / "honey-dropSim";
  const std::vector<std::string> before = listEntries(recorded);
  struct Case {
    std::string args;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"run --formats mesh --voxel-size nan --out o", "--voxel-size: nan is not a number (allowed: a finite number >= 0)"},
      {"run --formats vdb --voxel-size -nan --out o", "--voxel-size: -nan is not a number"},
      {"run --formats mesh --voxel-size inf --out o", "--voxel-size: inf is out of range"},
      {"run --formats mesh --blob-radius nan --out o", "--blob-radius: nan is not a number (allowed: 1 to 5)"},
      {"render --surface --voxel-size nan --out o", "--voxel-size: nan is not a number"},
      {"render --surface --blob-radius NaN --out o", "--blob-radius: NaN is not a number"},
  };
  for (const Case& c : cases) {
    const RunResult r = runSoftsub(c.args + " " + quote(scene), tmp.path());
    EXPECT_EQ(r.code, 2) << c.args << ": " << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << ": " << r.err;
    EXPECT_FALSE(fs::exists(tmp / "o")) << c.args;
  }
  for (const std::string bad : {"--voxel-size nan", "--formats vdb --voxel-size nan", "--blob-radius nan"}) {
    const RunResult r = runSoftsub("mesh " + bad + " " + quote(recorded), tmp.path());
    EXPECT_EQ(r.code, 2) << bad << ": " << r.err;
    EXPECT_NE(r.err.find("is not a number"), std::string::npos) << bad << ": " << r.err;
    EXPECT_EQ(listEntries(recorded), before) << bad;
  }
}

/// Writes `text` to `path`.
void writeText(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

/// A scene of one fluid 'a' with the given explicit particles and extra elements.
std::string oneFluid(const std::string& particleSize, const std::string& particles, const std::string& simulation = "") {
  return "<Scene version=\"1\"><Simulation><Substeps>1</Substeps><Frames>2</Frames>" + simulation +
         "</Simulation><Fluid><Name>a</Name><ParticleSize>" + particleSize + "</ParticleSize><Particles>" + particles +
         "</Particles></Fluid></Scene>\n";
}

/// A scene the surfaces cannot take is refused before anything is made, by `run` with
/// each list of `formats` (exit 2, the message holds `problem` and `(allowed: <allowed>)`)
/// and by `render --surface` (exit 2); neither leaves its output folder.
void expectSurfacesRefusedFirst(const TempDir& tmp, const fs::path& scene,
                                const std::vector<std::string>& formats, const std::string& problem,
                                const std::string& allowed) {
  SCOPED_TRACE(scene.filename().string());
  for (const std::string& f : formats) {
    const RunResult r = runSoftsub("run --formats " + f + " --out o " + quote(scene), tmp.path());
    EXPECT_EQ(r.code, 2) << f << ": " << r.err;
    EXPECT_NE(r.err.find(problem), std::string::npos) << f << ": " << r.err;
    EXPECT_NE(r.err.find("(allowed: " + allowed + ")"), std::string::npos) << f << ": " << r.err;
    EXPECT_FALSE(fs::exists(tmp / "o")) << f;
  }
  const RunResult render = runSoftsub("render --surface --frames 0 --out r " + quote(scene), tmp.path());
  EXPECT_EQ(render.code, 2) << render.err;
  EXPECT_FALSE(fs::exists(tmp / "r"));
}

/// `run --formats mesh,vdb --voxel-size <voxel>` on `scene` is refused (exit 2) with a
/// message holding `problem`, before its folder is made.
void expectVoxelRefused(const TempDir& tmp, const fs::path& scene, const std::string& voxel,
                        const std::string& problem) {
  const RunResult r =
      runSoftsub("run --formats mesh,vdb --voxel-size " + voxel + " --out o " + quote(scene), tmp.path());
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find(problem), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(tmp / "o"));
}

// The default voxel is half the particle size; below 2e-5 OpenVDB refuses the grid's
// transform ("internal error: ArithmeticError", exit 1, empty mesh/ and vdb/ folders).
// It is now refused before anything is made, naming the particle size and the way out.
TEST(SurfaceCli, AParticleSizeTooSmallForTheGridIsRefusedFirst) {
  TempDir tmp;
  const fs::path scene = tmp / "tiny.scene";
  writeText(scene, oneFluid("1e-5", "0 0 0  1e-5 0 0"));
  expectSurfacesRefusedFirst(tmp, scene, {"mesh", "vdb", "sim,mesh,vdb"},
                             "tiny.scene: Fluid 'a'/ParticleSize: 1e-05 is too small for surfaces",
                             "ParticleSize >= 4e-05 with surfaces, or --voxel-size 2e-05 or more");
  expectVoxelRefused(tmp, scene, "1e-5", "--voxel-size: 1e-05 is too small for fluid 'a'");
  expectVoxelRefused(tmp, scene, "1e-5", "never below 2e-05");
  // The documented bound itself, 4e-5 (3.9999999e-5 in single precision), was refused.
  writeText(tmp / "edge.scene", oneFluid("4e-5", "0 0 0  4e-5 0 0"));
  const RunResult edge = runSoftsub("run --frames 0 --formats mesh --out e edge.scene", tmp.path());
  EXPECT_EQ(edge.code, 0) << edge.err;
  // Without surfaces the particle size is fine, and a voxel of 2e-5 meshes it.
  EXPECT_EQ(runSoftsub("run --formats sim --out s " + quote(scene), tmp.path()).code, 0);
  const RunResult meshed = runSoftsub("run --formats mesh --voxel-size 2e-5 --out m " + quote(scene), tmp.path());
  EXPECT_EQ(meshed.code, 0) << meshed.err;
  EXPECT_TRUE(fs::exists(tmp / "m/mesh/a.0002.obj"));
}

// A ParticleSize of 3e38 (in the schema's range) made `--formats vdb` spin forever in
// OpenVDB (a black-box fuzzer found it): voxels above 1e30 are now refused first, and a
// particle size no voxel fits is named as such.
TEST(SurfaceCli, AParticleSizeTooLargeForTheGridIsRefusedFirst) {
  TempDir tmp;
  const fs::path scene = tmp / "huge.scene";
  writeText(scene, oneFluid("3e38", "0 0 0  1e38 0 0"));
  expectSurfacesRefusedFirst(tmp, scene, {"vdb", "mesh", "sim,mesh,vdb"},
                             "huge.scene: Fluid 'a'/ParticleSize: 3e+38 is too large for surfaces",
                             "ParticleSize <= 4.26667e+31 with surfaces at blob radius 1.5");
  writeText(tmp / "big.scene", oneFluid("1e31", "0 0 0  1e31 0 0"));
  expectSurfacesRefusedFirst(
      tmp, tmp / "big.scene", {"vdb"},
      "big.scene: Fluid 'a'/ParticleSize: 1e+31 is too large for surfaces: the default voxel",
      "ParticleSize <= 2e+30 with surfaces, or --voxel-size 2.34375e+29 to 1e+30");
  expectVoxelRefused(
      tmp, tmp / "big.scene", "1e37",
      "--voxel-size: 1e+37 is above the largest voxel the surfaces' grid takes (allowed: at most "
      "1e+30)");
  const RunResult fits =
      runSoftsub("run --frames 0 --formats vdb --voxel-size 1e30 --out v big.scene", tmp.path());
  EXPECT_EQ(fits.code, 0) << fits.err;
  EXPECT_TRUE(fs::exists(tmp / "v/vdb/a.0000.vdb"));
}

// A voxel coarser than the blob radius put the surface most of a voxel off, or left it
// empty, with no word: now a warning says so (the run still writes what was asked).
TEST(SurfaceCli, AVoxelCoarserThanTheBlobIsWarnedAbout) {
  TempDir tmp;
  const fs::path scene = tmp / "blob.scene";
  writeText(scene, oneFluid("1", "0 1 0  1 1 0"));
  const RunResult coarse =
      runSoftsub("run --frames 0 --formats mesh --voxel-size 5 --out c " + quote(scene), tmp.path());
  EXPECT_EQ(coarse.code, 0) << coarse.err;
  EXPECT_NE(coarse.err.find("warning: --voxel-size 5 is coarser than fluid 'a''s blob radius (1.5)"),
            std::string::npos)
      << coarse.err;
  const RunResult quiet =
      runSoftsub("run -q --frames 0 --formats mesh --voxel-size 5 --out c " + quote(scene), tmp.path());
  EXPECT_EQ(quiet.code, 0) << quiet.err;
  EXPECT_EQ(quiet.err.find("--voxel-size"), std::string::npos) << "-q: " << quiet.err;
  const RunResult fine =
      runSoftsub("run --frames 0 --formats mesh --voxel-size 1.5 --out f " + quote(scene), tmp.path());
  EXPECT_EQ(fine.code, 0) << fine.err;
  EXPECT_EQ(fine.err.find("--voxel-size"), std::string::npos) << fine.err;
}

// The surface grid indexes voxels with 32-bit integers: a particle more than 2^30 voxels
// from the origin cannot be meshed. In the scene it is bad input, refused before anything
// is written (it was "internal error", exit 1, after frame 0's .sim and an empty mesh/).
TEST(SurfaceCli, AParticleBeyondTheGridsReachInTheSceneIsRefusedFirst) {
  TempDir tmp;
  const fs::path scene = tmp / "far.scene";
  writeText(scene, oneFluid("1", "0 1 0  1e12 0 0"));
  expectSurfacesRefusedFirst(
      tmp, scene, {"sim,mesh", "vdb"},
      "far.scene: Fluid 'a'/Particles: particle id 1 at (1e+12, 0, 0) is too far from the origin",
      "|x|, |y|, |z| <= 5.36871e+08 with surfaces; or a larger --voxel-size");
  // A coarser voxel reaches farther.
  EXPECT_EQ(runSoftsub("run --frames 0 --formats mesh --voxel-size 2000 --out c " + quote(scene), tmp.path()).code, 0);
}

// A particle that flies beyond the grid during the run: exit 4 like a blow-up, naming the
// frame, fluid and particle; the frames before it are complete.
TEST(SurfaceCli, AParticleThatFliesBeyondTheGridsReachStopsTheRunClearly) {
  TempDir tmp;
  const fs::path scene = tmp / "fly.scene";
  writeText(scene, oneFluid("1", "0 1 0  536000000 0 0", "<Gravity>1e9 0 0</Gravity>"));
  const RunResult r = runSoftsub("run --speed-limit 0 --formats sim,mesh --out o " + quote(scene), tmp.path());
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_NE(r.err.find("\nerror: frame 1: fluid 'a', particle id 1 is at ("), std::string::npos) << r.err;  // after the stability warning
  EXPECT_NE(r.err.find("too far from the origin for the surface's voxel grid (|x|, |y|, |z| <= 5.36871e+08"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("frames 0..0 are complete"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(tmp / "o/manifest/fly.0000.manifest"));
  EXPECT_TRUE(fs::exists(tmp / "o/mesh/a.0000.obj"));
  EXPECT_FALSE(fs::exists(tmp / "o/mesh/a.0001.obj"));
}

// Total area of a triangle mesh.
double area(const surface::SurfaceMesh& m) {
  double a = 0;
  for (const auto& t : m.triangles) {
    const auto& p = m.vertices[t[0]];
    const auto& q = m.vertices[t[1]];
    const auto& r = m.vertices[t[2]];
    const double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]}, v[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
    const double c[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    a += 0.5 * std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
  }
  return a;
}

TEST(SurfaceCli, ALargerBlobRadiusSmoothsTheSurfaceAndKeepsTheVolume) {
  // The smoothing option: a larger blob radius blends the particles' bumps away, so the
  // same (preserved) volume is wrapped in less area.
  TempDir tmp;
  const fs::path scene = examplesDir() / "honey-drop.scene";
  const double count = fluidCounts(scene).at(0);  // ParticleSize 1: rest volume = count
  double areas[2] = {0, 0};
  int k = 0;
  for (const std::string radius : {"1.5", "3.0"}) {
    const fs::path out = tmp / ("r" + radius);
    const RunResult r = runSoftsub("run -q --frames 0 --formats mesh --blob-radius " + radius + " --out " + quote(out) +
                                       " " + quote(scene),
                                   tmp.path());
    ASSERT_EQ(r.code, 0) << r.err;
    const fs::path obj = out / "mesh" / (frameName(0) + ".obj");
    const surface::SurfaceMesh mesh = asSurfaceMesh(cache::decodeObj(readFile(obj), obj.string()));
    EXPECT_TRUE(surface::isClosedAndOriented(mesh)) << radius;
    EXPECT_NEAR(surface::enclosedVolume(mesh), count, 0.05 * count) << radius;
    areas[k++] = area(mesh);
  }
  EXPECT_LT(areas[1], 0.97 * areas[0]) << "blob radius 1.5: area " << areas[0] << ", 3.0: " << areas[1];
}

TEST(SurfaceCli, MeshCommandOnARecordedFolderGivesTheSameBytes) {
  TempDir tmp;
  fs::create_directories(tmp / "a");
  fs::create_directories(tmp / "b");
  const fs::path a = copyInto(examplesDir() / "honey-drop.scene", tmp / "a");
  const fs::path b = copyInto(examplesDir() / "honey-drop.scene", tmp / "b");
  ASSERT_EQ(runSoftsub("run -q --frames 2 --formats sim,mesh " + quote(a), tmp.path()).code, 0);
  ASSERT_EQ(runSoftsub("run -q --frames 2 --formats sim " + quote(b), tmp.path()).code, 0);
  const RunResult r = runSoftsub("mesh " + quote(tmp / "b/honey-dropSim"), tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "");  // not a terminal: no progress, no summary
  for (int f = 0; f <= 2; ++f) {
    const std::string name = "honey-dropSim/mesh/" + frameName(f) + ".obj";
    EXPECT_EQ(readFile(tmp / "b" / name), readFile(tmp / "a" / name)) << name;
  }
  EXPECT_FALSE(fs::exists(tmp / "b/honey-dropSim/vdb"));
  // --formats vdb and a voxel size: level sets of that voxel.
  ASSERT_EQ(runSoftsub("mesh --formats vdb --voxel-size 0.5 " + quote(tmp / "b/honey-dropSim"), tmp.path()).code, 0);
  EXPECT_NEAR(surface::LevelSet::readVdb(tmp / "b/honey-dropSim/vdb/honey.0002.vdb").voxelSize(), 0.5, 1e-9);
}

// A recorded folder away from its scene: without the sizes every fluid is meshed at
// ParticleSize 1, which a warning says (also where stderr is not a terminal) naming the
// file looked for; --scene gives the run's bytes back. A bad --scene is an error, and one
// without the recording's fluid is warned about.
TEST(SurfaceCli, MeshAwayFromItsSceneWarnsAndTakesTheSceneFromAnOption) {
  TempDir tmp;
  // A particle size other than the default 1, so that the sizes show in the surfaces.
  std::string text = readFile(examplesDir() / "honey-drop.scene");
  const std::size_t size = text.find("<ParticleSize>1</ParticleSize>");
  ASSERT_NE(size, std::string::npos);
  text.replace(size, 30, "<ParticleSize>0.7</ParticleSize>");
  const fs::path scene = tmp / "honey-drop.scene";
  std::ofstream(scene) << text;
  ASSERT_EQ(runSoftsub("run -q --frames 1 --formats sim,mesh " + quote(scene), tmp.path()).code, 0);
  const std::string runs = readFile(tmp / "honey-dropSim/mesh/honey.0001.obj");
  fs::create_directories(tmp / "elsewhere");
  fs::rename(tmp / "honey-dropSim", tmp / "elsewhere/take1");
  const RunResult bare = runSoftsub("mesh " + quote(tmp / "elsewhere/take1"), tmp.path());
  ASSERT_EQ(bare.code, 0) << bare.err;
  EXPECT_NE(
      bare.err.find("warning: no usable scene file at " + (tmp / "elsewhere/honey-drop.scene").string() +
                    ": every fluid is meshed at ParticleSize 1"),
      std::string::npos)
      << bare.err;
  EXPECT_TRUE(readFile(tmp / "elsewhere/take1/mesh/honey.0001.obj") != runs) << "meshed at the scene's sizes";
  EXPECT_EQ(runSoftsub("mesh -q " + quote(tmp / "elsewhere/take1"), tmp.path()).err, "");
  const RunResult named =
      runSoftsub("mesh --scene " + quote(scene) + " " + quote(tmp / "elsewhere/take1"), tmp.path());
  ASSERT_EQ(named.code, 0) << named.err;
  EXPECT_EQ(named.err, "");
  EXPECT_TRUE(readFile(tmp / "elsewhere/take1/mesh/honey.0001.obj") == runs) << "not the run's surfaces";
  const RunResult missing =
      runSoftsub("mesh --scene nope.scene " + quote(tmp / "elsewhere/take1"), tmp.path());
  EXPECT_NE(missing.code, 0);
  EXPECT_NE(missing.err.find("nope.scene"), std::string::npos) << missing.err;
  // A scene that reads but has no fluid of the recording (renamed since the run): the
  // same sizes as no scene, which a warning says, naming the fluids (a black-box review:
  // silently 5.4 times the volume).
  std::string renamed = text;
  renamed.replace(renamed.find("<Name>honey</Name>"), 18, "<Name>syrup</Name>");
  std::ofstream(tmp / "renamed.scene") << renamed;
  const RunResult other = runSoftsub(
      "mesh --scene " + quote(tmp / "renamed.scene") + " " + quote(tmp / "elsewhere/take1"), tmp.path());
  ASSERT_EQ(other.code, 0) << other.err;
  EXPECT_NE(
      other.err.find("warning: the scene file " + (tmp / "renamed.scene").generic_string() +
                     " has no fluid 'honey' of the recording (its fluids: 'syrup'): drawn and meshed with "
                     "the default colour and ParticleSize 1"),
      std::string::npos)
      << other.err;
  EXPECT_TRUE(readFile(tmp / "elsewhere/take1/mesh/honey.0001.obj") != runs) << "meshed at the scene's sizes";
}

// Surfaces are named after their fluid: meshing one scene of a shared folder would have
// written over another scene's surfaces of the same fluid name (which its manifests
// list, so that run then read as incomplete). Refused, as run refuses it.
TEST(SurfaceCli, MeshRefusesToWriteOverAnotherScenesSurfaces) {
  TempDir tmp;
  const fs::path a = copyInto(examplesDir() / "honey-drop.scene", tmp.path());
  std::ofstream(tmp / "honeyB.scene") << readFile(a);  // the same fluid, honey
  ASSERT_EQ(runSoftsub("run -q --frames 1 --formats sim,mesh --out mix " + quote(a), tmp.path()).code, 0);
  ASSERT_EQ(runSoftsub("run -q --frames 1 --formats sim --out mix honeyB.scene", tmp.path()).code, 0);
  const std::string before = readFile(tmp / "mix/mesh/honey.0001.obj");
  const RunResult r =
      runSoftsub("mesh --scene honeyB.scene " + quote(tmp / "mix/honeyB.0000.sim"), tmp.path());
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("a file of scene 'honey-drop'"), std::string::npos) << r.err;
  EXPECT_TRUE(readFile(tmp / "mix/mesh/honey.0001.obj") == before) << "written over";
}

// `mesh` rewrote surfaces the run's manifests list, at other sizes, and left the
// manifests as they were: `info` then found no complete frame, and `run --resume`
// started over, writing the old surfaces back. The manifests follow the new files, and
// a fresh run removes what `mesh` added, with the rest of the earlier run.
TEST(SurfaceCli, MeshKeepsTheRunsFramesCompleteAndResumable) {
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "honey-drop.scene", tmp.path());
  ASSERT_EQ(runSoftsub("run -q --frames 2 --formats sim,mesh " + quote(scene), tmp.path()).code, 0);
  const fs::path sim = tmp / "honey-dropSim";
  const std::string coarse = readFile(sim / "mesh/honey.0001.obj");
  ASSERT_EQ(runSoftsub("mesh -q --formats mesh,vdb --voxel-size 0.25 " + quote(sim), tmp.path()).code, 0);
  const std::string fine = readFile(sim / "mesh/honey.0001.obj");
  ASSERT_NE(fine, coarse);
  const RunResult info = runSoftsub("info " + quote(sim), tmp.path());
  EXPECT_NE(info.out.find("frames 0..2 complete"), std::string::npos) << info.out;
  EXPECT_NE(readFile(sim / "manifest/honey-drop.0001.manifest").find("vdb/honey.0001.vdb"),
            std::string::npos);
  const RunResult resumed =
      runSoftsub("run --frames 2 --formats sim,mesh --resume " + quote(scene), tmp.path());
  ASSERT_EQ(resumed.code, 0) << resumed.err;
  EXPECT_EQ(readFile(sim / "mesh/honey.0001.obj"), fine) << "the resume rewrote a complete frame";
  ASSERT_EQ(runSoftsub("run -q --frames 2 --formats sim " + quote(scene), tmp.path()).code, 0);
  EXPECT_FALSE(fs::exists(sim / "mesh/honey.0001.obj"));
  EXPECT_FALSE(fs::exists(sim / "vdb/honey.0001.vdb"));
}

// A frame cut after the run (its .sim no longer the size its manifest lists): mesh
// wrote the frames before it, then failed on it (exit 2, half the surfaces written).
// It and the later frames are left out now; a damaged first frame is refused first.
TEST(SurfaceCli, MeshLeavesOutFramesChangedSinceTheRun) {
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "honey-drop.scene", tmp.path());
  ASSERT_EQ(runSoftsub("run -q --frames 2 --formats sim " + quote(scene), tmp.path()).code, 0);
  const fs::path sim = tmp / "honey-dropSim";
  const auto cut = [&](const fs::path& file) {
    const std::string bytes = readFile(file);
    std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes.substr(0, bytes.size() / 2);
  };
  cut(sim / "honey-drop.0001.sim");
  const RunResult r = runSoftsub("mesh " + quote(sim), tmp.path());
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(sim / "mesh/honey.0000.obj"));
  EXPECT_FALSE(fs::exists(sim / "mesh/honey.0001.obj"));
  EXPECT_FALSE(fs::exists(sim / "mesh/honey.0002.obj"));
  fs::remove_all(sim / "mesh");
  cut(sim / "honey-drop.0000.sim");
  const RunResult first = runSoftsub("mesh " + quote(sim), tmp.path());
  EXPECT_EQ(first.code, 2) << first.err;
  EXPECT_NE(first.err.find("its manifest lists (changed since the run wrote it)"), std::string::npos)
      << first.err;
  EXPECT_FALSE(fs::exists(sim / "mesh"));
}

TEST(SurfaceCli, MeshDrawsProgressAndASummaryAtATerminal) {
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "honey-drop.scene", tmp.path());
  ASSERT_EQ(runSoftsub("run -q --frames 2 --formats sim " + quote(scene), tmp.path()).code, 0);
  const RunResult r = runSoftsubInTerminal("mesh " + quote(tmp / "honey-dropSim"), tmp.path());
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("\rframe 0/2 (1 of 3) | 847 particles | meshing"), std::string::npos) << r.out;
  const std::size_t last = r.out.find("\rframe 2/2 (3 of 3) | 847 particles | ");
  ASSERT_NE(last, std::string::npos) << r.out;
  const std::size_t done = r.out.find("\r\ndone: 3 frames meshed, ");
  ASSERT_NE(done, std::string::npos) << r.out;
  EXPECT_LT(last, done);
  EXPECT_EQ(listFrameFiles(tmp / "honey-dropSim/mesh").size(), 3u);
}

TEST(SurfaceCli, MeshRefusesNonSurfaceFormatsAndMissingFrames) {
  TempDir tmp;
  fs::create_directories(tmp / "empty");
  // Every bad list, the ones run's parser refuses too (empty, unknown, "none,"), lists
  // what mesh takes, never run's formats.
  for (const std::string bad : {"sim", "''", "xyz", "none", "none,", "mesh,", "all"}) {
    const RunResult r = runSoftsub("mesh --formats " + bad + " " + quote(tmp / "empty"), tmp.path());
    EXPECT_EQ(r.code, 2) << bad << ": " << r.err;
    EXPECT_EQ(r.err.rfind("error: command line: --formats: ", 0), 0u) << bad << ": " << r.err;
    EXPECT_NE(r.err.find("(allowed: mesh, vdb or mesh,vdb)\n"), std::string::npos) << bad << ": " << r.err;
    EXPECT_EQ(r.err.find("pdc"), std::string::npos) << bad << ": " << r.err;
  }
  const RunResult r = runSoftsub("mesh " + quote(tmp / "empty"), tmp.path());
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_TRUE(listEntries(tmp / "empty").empty());
}

}  // namespace
}  // namespace softsub::apptest
