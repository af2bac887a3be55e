// Surfaces: particles -> level set -> closed mesh, and the .vdb round trip (issue #5).
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <numbers>
#include <vector>

#include "cache/atomic_file.h"
#include "surface/surface.h"

namespace ss = softsub::surface;

namespace {

// Lattice points (spacing h) inside a ball of radius r around c.
std::vector<float> ball(double r, double h, std::array<double, 3> c = {0, 0, 0}) {
  std::vector<float> xyz;
  const int n = static_cast<int>(std::ceil(r / h));
  for (int i = -n; i <= n; ++i)
    for (int j = -n; j <= n; ++j)
      for (int k = -n; k <= n; ++k) {
        const double x = i * h, y = j * h, z = k * h;
        if (x * x + y * y + z * z <= r * r) {
          xyz.push_back(float(c[0] + x));
          xyz.push_back(float(c[1] + y));
          xyz.push_back(float(c[2] + z));
        }
      }
  return xyz;
}

}  // namespace

TEST(MeshChecks, TetrahedronVolumeAndClosure) {
  ss::SurfaceMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};  // counter-clockwise from outside
  EXPECT_NEAR(ss::enclosedVolume(m), 1.0 / 6.0, 1e-12);
  EXPECT_TRUE(ss::isClosedAndOriented(m));
  m.triangles[3] = {1, 3, 2};  // one face flipped
  EXPECT_FALSE(ss::isClosedAndOriented(m));
  m.triangles.pop_back();  // open
  EXPECT_FALSE(ss::isClosedAndOriented(m));
}

TEST(Surface, BallMeshesClosedWithTheBallsVolume) {
  const double h = 1.0, r = 6.0;
  const auto xyz = ball(r, h);
  const auto count = xyz.size() / 3;
  const ss::SurfaceMesh m = ss::meshParticles(xyz, h);
  ASSERT_FALSE(m.triangles.empty());
  EXPECT_EQ(m.normals.size(), m.vertices.size());
  EXPECT_TRUE(ss::isClosedAndOriented(m));
  const double v = ss::enclosedVolume(m);
  const double ballVolume = 4.0 / 3.0 * std::numbers::pi * r * r * r;
  const double restVolume = double(count) * h * h * h;  // count x particle cell volume
  std::printf("ball r=%g: %zu particles, mesh %.1f, ball %.1f, rest %.1f\n", r, count, v,
              ballVolume, restVolume);
  EXPECT_GT(v, 0.0) << "triangles face inwards";
  EXPECT_NEAR(v / restVolume, 1.0, 0.05);
  // Normals point away from the centre.
  for (std::size_t i = 0; i < m.vertices.size(); i += 97) {
    const auto& p = m.vertices[i];
    const auto& n = m.normals[i];
    EXPECT_GT(p[0] * n[0] + p[1] * n[1] + p[2] * n[2], 0.0f);
  }
}

TEST(Surface, FixedThresholdLetsALoneParticleFitItsSphere) {
  ss::SurfaceSettings fixed;
  fixed.preserveVolume = false;
  fixed.voxelSize = 0.1;
  const auto m = ss::meshParticles(std::vector<float>{0, 0, 0}, 1.0, fixed);
  EXPECT_TRUE(ss::isClosedAndOriented(m));
  const double r = std::cbrt(ss::enclosedVolume(m) * 3.0 / (4.0 * std::numbers::pi));
  EXPECT_NEAR(r, 0.5, 0.03);  // seed 3.5.1: the blob fits the particle's sphere
}

TEST(Surface, EmptyInputGivesEmptyMesh) {
  const std::vector<float> none;
  const auto ls = ss::LevelSet::fromParticles(none, 1.0);
  EXPECT_TRUE(ls.empty());
  const auto m = ls.mesh();
  EXPECT_TRUE(m.vertices.empty());
  EXPECT_TRUE(m.triangles.empty());
  EXPECT_TRUE(ss::isClosedAndOriented(m));
  const auto file = std::filesystem::temp_directory_path() / "softsub_surface_empty.vdb";
  ls.writeVdb(file);
  EXPECT_TRUE(ss::LevelSet::readVdb(file).empty());
  std::filesystem::remove(file);
}

TEST(Surface, OneParticleGivesASmallClosedBlob) {
  const std::vector<float> one{1.0f, 2.0f, 3.0f};
  const auto m = ss::meshParticles(one, 1.0);
  ASSERT_FALSE(m.triangles.empty());
  EXPECT_TRUE(ss::isClosedAndOriented(m));
  const double v = ss::enclosedVolume(m);
  EXPECT_GT(v, 0.0);
  EXPECT_LT(v, 4.0 / 3.0 * std::numbers::pi * 1.5 * 1.5 * 1.5);  // inside the blob radius
  // Its rest volume (particleSize^3), although at the default 2 voxels per particle the
  // blob is about a voxel in radius: the iso value is checked against the mesh itself
  // (the voxels' count alone gave 0.3).
  EXPECT_NEAR(v, 1.0, 0.02);
}

// A spray of lone drops, far apart, at the default voxel: each meshes at its rest volume
// (the voxels' count alone meshed 8 drops at 2.44 of 8), and a finer voxel agrees.
TEST(Surface, LoneDropsKeepTheirRestVolumeAtTheDefaultVoxel) {
  std::vector<float> spray;
  for (int k = 0; k < 8; ++k) {
    spray.push_back(static_cast<float>(5 * (k % 3)));
    spray.push_back(static_cast<float>(10 + 5 * (k / 3)));
    spray.push_back(static_cast<float>(k % 2 == 0 ? 0 : 5));
  }
  const auto coarse = ss::meshParticles(spray, 1.0);
  EXPECT_TRUE(ss::isClosedAndOriented(coarse));
  EXPECT_NEAR(ss::enclosedVolume(coarse), 8.0, 0.02 * 8.0);
  ss::SurfaceSettings fine;
  fine.voxelSize = 0.125;
  EXPECT_NEAR(ss::enclosedVolume(ss::meshParticles(spray, 1.0, fine)), 8.0, 0.02 * 8.0);
  // A drop beside a large body: one iso value per fluid, so the volume is the pair's in
  // total, within the tolerance.
  std::vector<float> both = ball(4.0, 1.0);
  const std::size_t inBall = both.size() / 3;
  both.insert(both.end(), {20.0f, 0.0f, 0.0f});
  EXPECT_NEAR(ss::enclosedVolume(ss::meshParticles(both, 1.0)), double(inBall + 1), 0.02 * double(inBall + 1));
}

TEST(Surface, NonFiniteParticlesAreSkippedAndBadSettingsRejected) {
  const std::vector<float> xyz{0, 0, 0, NAN, 1, 1, INFINITY, 0, 0};
  EXPECT_TRUE(ss::isClosedAndOriented(ss::meshParticles(xyz, 1.0)));
  EXPECT_THROW(ss::meshParticles(xyz, 0.0), std::invalid_argument);
  ss::SurfaceSettings bad;
  bad.threshold = 1.5;
  EXPECT_THROW(ss::meshParticles(xyz, 1.0, bad), std::invalid_argument);
  const std::vector<float> far{0, 0, 0, 1e12f, 0, 0};
  EXPECT_THROW(ss::meshParticles(far, 1.0), std::invalid_argument);
  // A voxel above kMaxVoxelSize (a ParticleSize of 3e38 made OpenVDB's mesh-to-volume
  // spin forever); at the bound itself the level set is made and written.
  EXPECT_THROW((void)ss::LevelSet::fromParticles(xyz, 3e38), std::invalid_argument);
  ss::SurfaceSettings coarse;
  coarse.voxelSize = ss::kMaxVoxelSize;
  const std::vector<float> huge{0, 0, 0, 1e31f, 0, 0};
  const ss::LevelSet atBound = ss::LevelSet::fromParticles(huge, 2 * ss::kMaxVoxelSize, coarse);
  EXPECT_FALSE(atBound.empty());
  EXPECT_TRUE(ss::isClosedAndOriented(atBound.mesh()));
  EXPECT_GT(atBound.activeVoxelCount(), 0u);  // the signed distance grid (what .vdb holds)
}

TEST(Surface, FarApartParticlesStaySparse) {
  // Two particles 10^5 particle sizes apart: a dense grid over their box would be 10^16
  // voxels; the sparse field holds two small blobs.
  const std::vector<float> xyz{0, 0, 0, 1e5f, 1e5f, 1e5f};
  const auto ls = ss::LevelSet::fromParticles(xyz, 1.0);
  EXPECT_LT(ls.activeVoxelCount(), 100000u);
  const auto m = ls.mesh();
  EXPECT_TRUE(ss::isClosedAndOriented(m));
  const auto one = ss::meshParticles(std::vector<float>{0, 0, 0}, 1.0);
  // Vertices are floats: at 10^5 their precision (~0.008) blurs the far blob's volume a little.
  EXPECT_NEAR(ss::enclosedVolume(m), 2.0 * ss::enclosedVolume(one), 0.05 * ss::enclosedVolume(m));
}

TEST(Surface, VdbReadsBackAndItsZeroCrossingIsTheMesh) {
  const auto xyz = ball(3.0, 1.0, {0.3, -0.2, 0.1});
  const auto ls = ss::LevelSet::fromParticles(xyz, 1.0);
  const auto m = ls.mesh();
  const auto file = std::filesystem::temp_directory_path() / "softsub_surface_ball.vdb";
  ls.writeVdb(file, "fluid");
  const auto back = ss::LevelSet::readVdb(file);
  // The file's UUID comes from its content (OpenVDB's is random): the same level set
  // written again is the same file, byte for byte, which a resumed run relies on.
  const std::string bytes = softsub::cache::readFileBytes(file);
  ss::LevelSet::fromParticles(xyz, 1.0).writeVdb(file, "fluid");
  EXPECT_EQ(softsub::cache::readFileBytes(file), bytes);
  ss::LevelSet::fromParticles(xyz, 1.0).writeVdb(file, "other");
  EXPECT_NE(softsub::cache::readFileBytes(file).substr(21, 36), bytes.substr(21, 36)) << "another grid, another id";
  EXPECT_EQ(bytes.substr(21 + 8, 1), "-");
  std::filesystem::remove(file);
  EXPECT_DOUBLE_EQ(back.voxelSize(), ls.voxelSize());
  EXPECT_EQ(back.activeVoxelCount(), ls.activeVoxelCount());
  double worst = 0.0;
  for (const auto& p : m.vertices) worst = std::max(worst, std::abs(back.sample(p[0], p[1], p[2])));
  EXPECT_LT(worst, back.voxelSize());
  EXPECT_LT(back.sample(0.3, -0.2, 0.1), 0.0);  // inside
  EXPECT_GT(back.sample(10, 10, 10), 0.0);      // outside
}

namespace {

std::vector<float> concat(std::vector<float> a, const std::vector<float>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

}  // namespace

TEST(Surface, BallsOfSeveralSizesKeepTheirRestVolume) {
  for (const double r : {3.0, 6.0, 10.0}) {
    const auto xyz = ball(r, 1.0);
    const double rest = double(xyz.size() / 3);
    const auto m = ss::meshParticles(xyz, 1.0);
    EXPECT_TRUE(ss::isClosedAndOriented(m)) << "r=" << r;
    const double v = ss::enclosedVolume(m);
    const double sphere = 4.0 / 3.0 * std::numbers::pi * r * r * r;
    std::printf("ball r=%g: %zu particles, mesh/rest %.4f, mesh/sphere %.4f\n", r, xyz.size() / 3,
                v / rest, v / sphere);
    EXPECT_NEAR(v / rest, 1.0, 0.05) << "r=" << r;
  }
}

// The merge test (seed 2.4.2: +41% for two blobs merging without volume control).
// Two lattice balls of radius 4 (257 particles each), touching (centres 2R apart), one
// particle size further apart (their blobs still overlap), and one particle size closer
// (interpenetrating as just after a merge). The merged mesh must stay within 5% of twice a
// lone ball's mesh and of twice its rest volume. Measured: +0.1%, -0.1%, +0.1% against the
// separate meshes (-0.8..-1.0% against rest); the per-fluid threshold (preserveVolume) is
// what holds it: without it the blobby sum gains volume as the blobs overlap.
TEST(Surface, TwoTouchingBallsMergeWithoutGainingVolume) {
  const double r = 4.0;
  const auto one = ball(r, 1.0);
  const double vOne = ss::enclosedVolume(ss::meshParticles(one, 1.0));
  const double restOne = double(one.size() / 3);
  for (const double gap : {2.0 * r, 2.0 * r + 1.0, 2.0 * r - 1.0}) {
    const auto two = concat(ball(r, 1.0, {-0.5 * gap, 0.1, 0.2}), ball(r, 1.0, {0.5 * gap, 0.1, 0.2}));
    const auto m = ss::meshParticles(two, 1.0);
    EXPECT_TRUE(ss::isClosedAndOriented(m));
    const double v = ss::enclosedVolume(m);
    std::printf("two balls r=%g, centres %g apart: merged %.1f, 2 x separate %.1f (%+.2f%%), "
                "2 x rest %.1f (%+.2f%%)\n",
                r, gap, v, 2 * vOne, 100.0 * (v / (2 * vOne) - 1.0), 2 * restOne,
                100.0 * (v / (2 * restOne) - 1.0));
    EXPECT_NEAR(v / (2.0 * vOne), 1.0, 0.05) << "centres " << gap << " apart";
    EXPECT_NEAR(v / (2.0 * restOne), 1.0, 0.05) << "centres " << gap << " apart";
  }
}

// A thin sheet (a 24 x 24 lattice slab two particles thick): closed, and its volume within
// 5% of the rest volume (measured +0.1%). Its faces fall exactly between two voxel planes:
// a plain voxel count picks the threshold a whole plane off (+15% before the sub-voxel
// volume estimate).
TEST(Surface, ThinSheetMeshesClosedNearItsRestVolume) {
  std::vector<float> xyz;
  for (int i = 0; i < 24; ++i)
    for (int j = 0; j < 24; ++j)
      for (int k = 0; k < 2; ++k) {
        xyz.push_back(float(i));
        xyz.push_back(float(j));
        xyz.push_back(float(k));
      }
  const auto m = ss::meshParticles(xyz, 1.0);
  EXPECT_TRUE(ss::isClosedAndOriented(m));
  const double rest = double(xyz.size() / 3);
  const double v = ss::enclosedVolume(m);
  std::printf("sheet 24x24x2: mesh/rest %.4f\n", v / rest);
  EXPECT_NEAR(v / rest, 1.0, 0.05);
}

// The seed's own example (2.4.2, after Desbrun): two blobs merging gain +41% without volume
// control. Here, with the fixed threshold, two particles 1.5 / 1.0 / 0.5 particle sizes
// apart mesh at +26% / +75% / +109% of two lone ones; with preserveVolume at +0.4% / +1.4%
// / +1.5% (fine voxels, so that a lone blob is well resolved).
TEST(Surface, TwoMergingBlobsKeepTheirVolumeOnlyWithPreservation) {
  ss::SurfaceSettings preserve, fixed;
  preserve.voxelSize = fixed.voxelSize = 0.1;
  fixed.preserveVolume = false;
  const auto lone = [](const ss::SurfaceSettings& s) {
    return ss::enclosedVolume(ss::meshParticles(std::vector<float>{0, 0, 0}, 1.0, s));
  };
  const double vPreserve = lone(preserve), vFixed = lone(fixed);
  for (const float d : {1.5f, 1.0f, 0.5f}) {
    const std::vector<float> two{0, 0, 0, d, 0, 0};
    EXPECT_NEAR(ss::enclosedVolume(ss::meshParticles(two, 1.0, preserve)) / (2 * vPreserve), 1.0, 0.05)
        << d << " apart";
    EXPECT_GT(ss::enclosedVolume(ss::meshParticles(two, 1.0, fixed)) / (2 * vFixed), 1.2) << d << " apart";
  }
}

namespace {

// n particles uniformly at random (fixed seed) in the box [-w, w]^3: a cloud that straddles
// the origin, so leaves and bins on both sides of zero are exercised.
std::vector<float> cloud(int n, double w, unsigned seed) {
  std::uint64_t state = seed;
  const auto uniform = [&] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return (static_cast<double>(state >> 11) / 9007199254740992.0 * 2.0 - 1.0) * w;
  };
  std::vector<float> xyz;
  for (int i = 0; i < 3 * n; ++i) xyz.push_back(static_cast<float>(uniform()));
  return xyz;
}

}  // namespace

TEST(Surface, SameMeshBitwiseForAnyThreadCount) {
  // The field is gathered per leaf in a fixed order and every reduction is fixed-order, so
  // the mesh must not depend on how many threads TBB runs.
  const auto xyz = cloud(4000, 9.0, 7);
  ss::SurfaceMesh reference;
  {
    const tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    reference = ss::meshParticles(xyz, 1.0);
  }
  ASSERT_GT(reference.triangles.size(), 1000u);
  for (const std::size_t threads : {2u, 3u}) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    const auto m = ss::meshParticles(xyz, 1.0);
    ASSERT_EQ(m.vertices.size(), reference.vertices.size()) << threads << " threads";
    EXPECT_EQ(0, std::memcmp(m.vertices.data(), reference.vertices.data(), m.vertices.size() * sizeof m.vertices[0]));
    EXPECT_EQ(0, std::memcmp(m.normals.data(), reference.normals.data(), m.normals.size() * sizeof m.normals[0]));
    EXPECT_EQ(m.triangles, reference.triangles) << threads << " threads";
  }
}

TEST(Surface, VerticesLieOnTheBruteForceIsoSurface) {
  // Reference check of the sparse, binned field: with the fixed threshold, every mesh
  // vertex is where the sum of all particles' kernels (summed here over every particle,
  // no grid) equals the threshold, up to the linear interpolation along a voxel edge.
  const auto xyz = cloud(300, 6.0, 11);
  ss::SurfaceSettings s;
  s.preserveVolume = false;
  s.voxelSize = 0.0625;
  const double radius = s.radiusScale * 1.0;
  const auto m = ss::meshParticles(xyz, 1.0, s);
  ASSERT_GT(m.vertices.size(), 1000u);
  double worst = 0.0;
  for (const auto& v : m.vertices) {
    double sum = 0.0;
    for (std::size_t i = 0; i < xyz.size(); i += 3) {
      const double dx = v[0] - xyz[i], dy = v[1] - xyz[i + 1], dz = v[2] - xyz[i + 2];
      const double u = std::max(0.0, 1.0 - (dx * dx + dy * dy + dz * dz) / (radius * radius));
      sum += u * u * u;
    }
    worst = std::max(worst, std::abs(sum - s.threshold));
  }
  EXPECT_LT(worst, 0.02) << "the field at a vertex differs from the threshold " << s.threshold;
}

namespace {

// The closed shells of a mesh (triangles joined by shared vertices) and the volume each
// encloses (negative: a cavity).
std::vector<double> shellVolumes(const ss::SurfaceMesh& m) {
  std::vector<std::uint32_t> parent(m.vertices.size());
  for (std::size_t i = 0; i < parent.size(); ++i) parent[i] = static_cast<std::uint32_t>(i);
  const auto find = [&](std::uint32_t a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  for (const auto& t : m.triangles) {
    parent[find(t[1])] = find(t[0]);
    parent[find(t[2])] = find(t[0]);
  }
  std::vector<double> byRoot(m.vertices.size(), 0.0);
  std::vector<bool> used(m.vertices.size(), false);
  for (const auto& t : m.triangles) {
    ss::SurfaceMesh one;
    one.vertices = {m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]};
    one.triangles = {{0, 1, 2}};
    byRoot[find(t[0])] += ss::enclosedVolume(one);
    used[find(t[0])] = true;
  }
  std::vector<double> out;
  for (std::size_t i = 0; i < used.size(); ++i)
    if (used[i]) out.push_back(byRoot[i]);
  return out;
}

// Lattice points (spacing h) in the box [lo, hi], less those within `hole` of its centre.
std::vector<float> block(std::array<double, 3> lo, std::array<double, 3> hi, double h, double hole = 0) {
  std::vector<float> xyz;
  const std::array<double, 3> c = {(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2};
  for (double x = lo[0]; x <= hi[0]; x += h)
    for (double y = lo[1]; y <= hi[1]; y += h)
      for (double z = lo[2]; z <= hi[2]; z += h) {
        const double dx = x - c[0], dy = y - c[1], dz = z - c[2];
        if (dx * dx + dy * dy + dz * dz < hole * hole) continue;
        xyz.insert(xyz.end(), {float(x), float(y), float(z)});
      }
  return xyz;
}

}  // namespace

// The default scene's blocks (a lattice of spacing 1.1 x the particle size) meshed with
// about 1,300 sub-voxel bubbles inside each fluid, where the field dips below its iso
// value between particles. Cavities smaller than one particle go; a real hole stays.
TEST(Surface, NoBubblesSmallerThanAParticleButRealHolesStay) {
  const ss::SurfaceMesh lattice = ss::meshParticles(block({-23, 9, -13.75}, {-1, 20, 13.75}, 1.1), 1.0, {});
  const std::vector<double> shells = shellVolumes(lattice);
  ASSERT_EQ(shells.size(), 1u);
  EXPECT_GT(shells[0], 0.0);
  EXPECT_TRUE(ss::isClosedAndOriented(lattice));

  const ss::SurfaceMesh hollow = ss::meshParticles(block({-8, -8, -8}, {8, 8, 8}, 1.1, 4.0), 1.0, {});
  std::vector<double> v = shellVolumes(hollow);
  std::sort(v.begin(), v.end());
  ASSERT_EQ(v.size(), 2u) << "the outside and the hole";
  EXPECT_LT(v[0], -100.0) << "the hole of radius 4 (268 units) is kept, a little smaller";
  EXPECT_GT(v[1], 0.0);
  EXPECT_TRUE(ss::isClosedAndOriented(hollow));
}
