// Mesh → particles: the volume a fill covers, where its points lie, and what it does with
// meshes that are open, duplicated, inverted, degenerate or too large.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include "core/error.h"
#include "geometry/fill.h"
#include "support/meshes.h"

namespace softsub::geometry {
namespace {

using scenarios::boxMesh;
using scenarios::signedVolume;
using scenarios::sphereMesh;
using scenarios::torusMesh;

MeshFillResult fill(const TriangleMesh& m, double spacing, bool surfaceOnly = false) {
  MeshFillOptions o;
  o.spacing = spacing;
  o.surfaceOnly = surfaceOnly;
  return fillMesh(m, o);
}

double filledVolume(const MeshFillResult& r, double spacing) {
  return static_cast<double>(r.points.size()) * spacing * spacing * spacing;
}

TriangleMesh merged(TriangleMesh a, const TriangleMesh& b) {
  const auto offset = static_cast<std::uint32_t>(a.vertices.size());
  a.vertices.insert(a.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (const auto& t : b.triangles) a.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  return a;
}

TEST(FillMesh, BoxOnTheLatticeIsFilledExactly) {
  const auto r = fill(boxMesh(Vec3(0, 0, 0), Vec3(20, 20, 20)), 1.0);
  EXPECT_EQ(r.points.size(), 8000u);
  EXPECT_EQ(r.votedVoxels, 0u);
  EXPECT_EQ(r.testedVoxels, 8000u);
  EXPECT_TRUE(r.warnings.empty());
  // Deterministic order: x fastest, then y, then z; points are voxel centres.
  EXPECT_EQ(r.points.front(), Vec3(0.5, 0.5, 0.5));
  EXPECT_EQ(r.points[1], Vec3(1.5, 0.5, 0.5));
  EXPECT_EQ(r.points[20], Vec3(0.5, 1.5, 0.5));
  EXPECT_EQ(r.points.back(), Vec3(19.5, 19.5, 19.5));
}

TEST(FillMesh, BoxOffTheLatticeHasItsVolumeWithinThreePercent) {
  const Vec3 lo(0.37, -3.3, 1.9), hi(60.1, 41.75, 50.2);
  const double spacing = 1.0;
  const auto mesh = boxMesh(lo, hi);
  const auto r = fill(mesh, spacing);
  const double volume = signedVolume(mesh);
  EXPECT_NEAR(filledVolume(r, spacing) / volume, 1.0, 0.03);
  EXPECT_EQ(r.votedVoxels, 0u);
  for (const Vec3& p : r.points) {
    EXPECT_TRUE((p.array() >= lo.array()).all() && (p.array() <= hi.array()).all()) << p.transpose();
  }
}

TEST(FillMesh, SphereHasItsVolumeWithinThreePercentAndNoPointOutside) {
  const Vec3 c(1.3, -2.1, 0.7);
  const double spacing = 0.5, radius = 10 * spacing;
  const auto mesh = sphereMesh(c, radius, 64, 128);
  const auto r = fill(mesh, spacing);
  EXPECT_NEAR(filledVolume(r, spacing) / signedVolume(mesh), 1.0, 0.03);
  EXPECT_LT(r.votedVoxels, r.points.size() / 100);
  EXPECT_TRUE(r.warnings.empty());
  for (const Vec3& p : r.points) EXPECT_LE((p - c).norm(), radius + spacing);
}

TEST(FillMesh, TorusHasItsVolumeWithinThreePercentAndNoPointOutside) {
  const Vec3 c(-4.0, 2.5, 3.25);
  const double spacing = 0.25, major = 3.0, minor = 1.25;
  const auto mesh = torusMesh(c, major, minor, 96, 48);
  const auto r = fill(mesh, spacing);
  EXPECT_NEAR(filledVolume(r, spacing) / signedVolume(mesh), 1.0, 0.03);
  EXPECT_LT(r.votedVoxels, r.points.size() / 100);
  for (const Vec3& p : r.points) {
    const Vec3 q = p - c;
    const double ring = std::hypot(q.x(), q.z()) - major;  // the torus is around the y axis
    EXPECT_LE(std::hypot(ring, q.y()), minor + spacing);
  }
}

// A cavity whose faces run exactly through voxel centres: every axis decides the tie the same way.
TEST(FillMesh, NestedBoxIsACavityAndFacesThroughCentresAgreeOnEveryAxis) {
  const auto mesh =
      merged(boxMesh(Vec3(0, 0, 0), Vec3(10, 10, 10)), boxMesh(Vec3(2.5, 2.5, 2.5), Vec3(7.5, 7.5, 7.5)));
  const auto r = fill(mesh, 1.0);
  EXPECT_EQ(r.points.size(), 1000u - 125u);
  EXPECT_EQ(r.votedVoxels, 0u);
  for (const Vec3& p : r.points) EXPECT_FALSE((p.array() > 2.5).all() && (p.array() < 7.5).all());
}

TEST(FillMesh, DuplicatedInvertedOrReorderedTrianglesFillTheSame) {
  const auto box = boxMesh(Vec3(-0.3, 0.2, 0.45), Vec3(6.8, 5.1, 4.4));
  const auto reference = fill(box, 0.25);
  ASSERT_FALSE(reference.points.empty());

  auto doubled = box;
  doubled.triangles.insert(doubled.triangles.end(), box.triangles.begin(), box.triangles.end());
  auto inverted = box;
  for (auto& t : inverted.triangles) std::swap(t[1], t[2]);
  auto rotated = box;  // same triangles, vertex order rotated: other rounding, same surface
  for (auto& t : rotated.triangles) t = {t[1], t[2], t[0]};
  auto soup = box;  // no shared vertices, as STL files come
  soup.vertices.clear();
  soup.triangles.clear();
  for (const auto& t : box.triangles) {
    const auto base = static_cast<std::uint32_t>(soup.vertices.size());
    for (std::uint32_t i : t) soup.vertices.push_back(box.vertices[i]);
    soup.triangles.push_back({base, base + 1, base + 2});
  }
  for (const auto* m : {&doubled, &inverted, &rotated, &soup}) {
    const auto r = fill(*m, 0.25);
    EXPECT_EQ(r.points, reference.points);
    EXPECT_EQ(r.votedVoxels, 0u);
  }

  const auto sphere = sphereMesh(Vec3(0, 0, 0), 3.0, 24, 48);
  auto sphereDoubled = sphere;
  sphereDoubled.triangles.insert(sphereDoubled.triangles.end(), sphere.triangles.begin(),
                                 sphere.triangles.end());
  EXPECT_EQ(fill(sphereDoubled, 0.2).points, fill(sphere, 0.2).points);
}

TEST(FillMesh, OpenBoxGivesASaneResultAndAWarning) {
  const Vec3 lo(0.1, 0.2, 0.3), hi(8.1, 6.2, 5.3);
  const auto closed = boxMesh(lo, hi);
  const auto full = fill(closed, 0.5);
  // boxMesh's first quad (two triangles) is the x = lo face.
  auto open = closed;
  open.triangles.erase(open.triangles.begin(), open.triangles.begin() + 2);
  const auto r = fill(open, 0.5);
  EXPECT_LE(r.points.size(), full.points.size());
  EXPECT_GT(r.points.size(), full.points.size() / 2);
  EXPECT_GT(r.votedVoxels, 0u);
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_NE(r.warnings.front().find("disagree"), std::string::npos) << r.warnings.front();

  // The x = hi face missing instead: the +x rays see no exit; still nothing outside the box.
  auto openHi = closed;
  openHi.triangles.erase(openHi.triangles.begin() + 2, openHi.triangles.begin() + 4);
  const auto rHi = fill(openHi, 0.5);
  EXPECT_LE(rHi.points.size(), full.points.size());
  for (const Vec3& p : rHi.points)
    EXPECT_TRUE((p.array() >= lo.array()).all() && (p.array() <= hi.array()).all());
}

TEST(FillMesh, SphereWithAHoleStaysInsideTheSphere) {
  const Vec3 c(0, 0, 0);
  auto mesh = sphereMesh(c, 5.0, 32, 64);
  mesh.triangles.erase(mesh.triangles.begin(), mesh.triangles.begin() + 64 + 128);  // the north cap
  const auto r = fill(mesh, 0.25);
  const auto closed = fill(sphereMesh(c, 5.0, 32, 64), 0.25);
  EXPECT_LE(r.points.size(), closed.points.size());
  EXPECT_GT(r.points.size(), closed.points.size() * 9 / 10);
  for (const Vec3& p : r.points) EXPECT_LE(p.norm(), 5.0 + 0.25);
}

TEST(FillMesh, SurfaceOnlySphereLiesOnTheSurfaceWithAboutAreaOverSpacingSquaredPoints) {
  const Vec3 c(0.3, 0.1, -0.2);
  const double spacing = 0.5, radius = 10 * spacing;
  const auto r = fill(sphereMesh(c, radius, 64, 128), spacing, true);
  const double expected = 4 * std::numbers::pi * radius * radius / (spacing * spacing);
  EXPECT_NEAR(static_cast<double>(r.points.size()) / expected, 1.0, 0.1);
  EXPECT_EQ(r.votedVoxels, 0u);
  for (const Vec3& p : r.points) EXPECT_LE(std::abs((p - c).norm() - radius), spacing);
}

TEST(FillMesh, SurfaceOnlyBoxOnTheLatticeHasNoHoles) {
  // Faces on voxel boundaries put the centres exactly spacing/2 away: both sides count.
  const auto r = fill(boxMesh(Vec3(0, 0, 0), Vec3(10, 10, 10)), 1.0, true);
  EXPECT_EQ(r.points.size(), 1000u - 512u);
}

TEST(FillMesh, IsDeterministic) {
  const auto mesh = torusMesh(Vec3(0.1, 0.2, 0.3), 3.0, 1.0, 48, 24);
  EXPECT_EQ(fill(mesh, 0.2).points, fill(mesh, 0.2).points);
  EXPECT_EQ(fill(mesh, 0.2, true).points, fill(mesh, 0.2, true).points);
}

TEST(FillMesh, RefusesTooManyParticlesBeforeAllocating) {
  const auto huge = boxMesh(Vec3(-1e6, -1e6, -1e6), Vec3(1e6, 1e6, 1e6));
  EXPECT_EQ(meshFillBound(huge, 1e-3), std::numeric_limits<std::uint64_t>::max());
  const auto start = std::chrono::steady_clock::now();
  EXPECT_THROW(fill(huge, 1e-3), InputError);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1));

  const auto box = boxMesh(Vec3(0, 0, 0), Vec3(10, 10, 10));
  EXPECT_EQ(meshFillBound(box, 1.0), 1000u);
  MeshFillOptions o;
  o.maxParticles = 999;
  try {
    fillMesh(box, o);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(e.allowed().find("999"), std::string::npos) << e.what();
  }
  o.maxParticles = 1000;
  EXPECT_EQ(fillMesh(box, o).points.size(), 1000u);
}

TEST(FillMesh, RefusesBadSpacingAndEmptyOrBrokenMeshes) {
  const auto box = boxMesh(Vec3(0, 0, 0), Vec3(1, 1, 1));
  EXPECT_THROW(fill(box, 0.0), InputError);
  EXPECT_THROW(fill(box, -1.0), InputError);
  EXPECT_THROW(fill(box, std::nan("")), InputError);
  EXPECT_THROW(fill(box, std::numeric_limits<double>::infinity()), InputError);
  EXPECT_THROW(fill(TriangleMesh{}, 1.0), InputError);
  EXPECT_EQ(meshFillBound(TriangleMesh{}, 1.0), 0u);
  auto badIndex = box;
  badIndex.triangles.push_back({0, 1, 8});
  EXPECT_THROW(fill(badIndex, 0.5), InputError);
  auto notFinite = box;
  notFinite.vertices[3].x() = std::nan("");
  EXPECT_THROW(fill(notFinite, 0.5), InputError);
}

TEST(FillMesh, DegenerateTrianglesAreSkippedWithoutCrashing) {
  TriangleMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(2, 2, 2), Vec3(3, 0, 1)};
  m.triangles = {{0, 1, 2}, {0, 0, 3}, {3, 3, 3}, {2, 1, 0}};
  for (bool surface : {false, true}) {
    const auto r = fill(m, 0.25, surface);
    EXPECT_TRUE(r.points.empty());
    EXPECT_FALSE(r.warnings.empty());
  }
  // A closed box with some zero-area triangles added fills as the box, with a note.
  auto box = boxMesh(Vec3(0, 0, 0), Vec3(4, 4, 4));
  const auto reference = fill(box, 0.5);
  box.triangles.push_back({0, 0, 7});
  box.vertices.push_back(Vec3(2, 2, 2));
  box.vertices.push_back(Vec3(3, 3, 3));
  box.triangles.push_back({0, 8, 9});  // collinear through the inside
  const auto r = fill(box, 0.5);
  EXPECT_EQ(r.points, reference.points);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings.front().find("zero area"), std::string::npos);
}

}  // namespace
}  // namespace softsub::geometry

namespace softsub::geometry {
namespace {

// A box with a thin plate on top (a table: a thick leg under a top thinner than the
// spacing): the volume fill finds no lattice point in the plate, thinParts samples its
// surface there, and leaves the thick part exactly as it was.
TEST(FillMesh, ThinPartsSampleWhatIsThinnerThanTheSpacingAndLeaveTheRestAlone) {
  const double s = 0.5;
  const auto leg = boxMesh(Vec3(0, 0, 0), Vec3(2, 3, 2));
  const auto top = boxMesh(Vec3(-3, 3, -3), Vec3(5, 3.2, 5));  // 0.2 thick
  const auto table = merged(leg, top);
  MeshFillOptions o;
  o.spacing = s;
  const MeshFillResult plain = fillMesh(table, o);
  o.thinParts = true;
  const MeshFillResult thin = fillMesh(table, o);
  // Without thinParts nothing lies above the leg's top (y = 3) but the points of the leg.
  std::size_t plainInTop = 0;
  for (const Vec3& p : plain.points) plainInTop += p.y() > 3 && (p.x() < 0 || p.x() > 2 || p.z() < 0 || p.z() > 2);
  EXPECT_EQ(plainInTop, 0U);
  ASSERT_GT(thin.thinVoxels, 0U);
  EXPECT_EQ(thin.points.size(), plain.points.size() + thin.thinVoxels);
  EXPECT_EQ(plain.thinVoxels, 0U);
  // Every plain point is kept, and every added one lies within s/2 of the plate (its
  // surface samples) and covers it: each cell of a 0.5 grid over the plate has one.
  std::size_t kept = 0, added = 0;
  std::vector<int> covered(16 * 16, 0);
  for (const Vec3& p : thin.points) {
    const bool old = std::find(plain.points.begin(), plain.points.end(), p) != plain.points.end();
    kept += old ? 1 : 0;
    if (old) continue;
    ++added;
    EXPECT_GT(p.y(), 3 - s / 2 - 1e-9);
    EXPECT_LT(p.y(), 3.2 + s / 2 + 1e-9);
    EXPECT_GE(p.x(), -3 - s / 2);
    EXPECT_LE(p.x(), 5 + s / 2);
    const int cx = std::clamp(static_cast<int>(std::floor((p.x() + 3) / s)), 0, 15);
    const int cz = std::clamp(static_cast<int>(std::floor((p.z() + 3) / s)), 0, 15);
    covered[static_cast<std::size_t>(cx + 16 * cz)] = 1;
  }
  EXPECT_EQ(kept, plain.points.size());
  EXPECT_EQ(added, thin.thinVoxels);
  // The plate's cells above the leg are covered by the leg's own points instead.
  for (int cz = 0; cz < 16; ++cz)
    for (int cx = 0; cx < 16; ++cx) {
      const bool overLeg = cx >= 5 && cx <= 10 && cz >= 5 && cz <= 10;
      if (!overLeg) {
        EXPECT_TRUE(covered[static_cast<std::size_t>(cx + 16 * cz)]) << cx << ' ' << cz;
      }
    }
  // A body thick everywhere gets nothing added.
  MeshFillOptions thick;
  thick.spacing = s;
  thick.thinParts = true;
  const MeshFillResult cube = fillMesh(boxMesh(Vec3(0.1, 0.2, 0.3), Vec3(4.1, 3.2, 2.3)), thick);
  EXPECT_EQ(cube.thinVoxels, 0U);
  EXPECT_EQ(cube.points.size(), fill(boxMesh(Vec3(0.1, 0.2, 0.3), Vec3(4.1, 3.2, 2.3)), s).points.size());
}

// A plate modelled at an angle (a chute, a tray, a blade): the lattice's few points inside
// it must not hide the surface samples around them. Every point of the plate's mid-surface
// lies within 0.9 spacings of a particle (a particle of that size cannot pass: the
// lattice's own worst is half its cell's diagonal, 0.87), at any angle and thickness.
// Before, each lone lattice point inside such a plate hid the surface samples around it:
// 1.6 spacings at 20 degrees, 0.2 thick.
double largestGapOnTiltedPlate(double degrees, double thickness, double s, std::size_t* thin = nullptr,
                               std::size_t* points = nullptr) {
  const double a = degrees * std::numbers::pi / 180, c = std::cos(a), sn = std::sin(a);
  TriangleMesh plate = boxMesh(Vec3(-3, -thickness / 2, -3), Vec3(3, thickness / 2, 3));
  for (Vec3& v : plate.vertices) v = Vec3(c * v.x() - sn * v.y(), sn * v.x() + c * v.y(), v.z());
  MeshFillOptions o;
  o.spacing = s;
  o.thinParts = true;
  const MeshFillResult r = fillMesh(plate, o);
  if (thin != nullptr) *thin = r.thinVoxels;
  if (points != nullptr) *points = r.points.size();
  double gap = 0;
  for (double u = -2.5; u <= 2.5; u += 0.05)
    for (double w = -2.5; w <= 2.5; w += 0.05) {
      const Vec3 q(c * u, sn * u, w);
      double nearest = 1e9;
      for (const Vec3& p : r.points) nearest = std::min(nearest, (p - q).norm());
      gap = std::max(gap, nearest);
    }
  return gap;
}

TEST(FillMesh, ThinPartsCoverAPlateModelledAtAnAngle) {
  const double s = 0.5;
  for (const double degrees : {0.0, 20.0, 30.0, 45.0})
    for (const double thickness : {0.2, 0.4, 0.6, 0.8})
      EXPECT_LE(largestGapOnTiltedPlate(degrees, thickness, s), 0.9 * s) << degrees << " degrees, " << thickness;
  // A thick slab at an angle is the lattice's alone, even where its staircase leaves the
  // surface more than 0.9 s from a lattice point; so is a box whose size is not a whole
  // number of particles (its lattice stops up to a particle short of its high faces).
  std::size_t thin = 1;
  EXPECT_LE(largestGapOnTiltedPlate(30, 2.0, s, &thin), 0.9 * s);
  EXPECT_EQ(thin, 0U);
  MeshFillOptions o;
  o.spacing = 0.6;
  o.thinParts = true;
  EXPECT_EQ(fillMesh(boxMesh(Vec3(0, 0, 0), Vec3(2, 2, 2)), o).thinVoxels, 0U);
}

// A mesh at most one spacing thick along an axis gets its one layer of lattice points
// in its middle there: from the low face they lay s/2 off it, outside a part thinner
// than that, and a rod thin on two axes had neither an inside point nor a surface sample
// (as a body, one particle at its centre; as a fill, none).
TEST(FillMesh, ARodThinnerThanTheSpacingOnTwoAxesIsFilledAlongItsLength) {
  const Vec3 lo(-2, 1, 0.5), hi(2, 1.02, 0.52);
  for (const bool surfaceOnly : {false, true}) {
    const MeshFillResult r = fill(boxMesh(lo, hi), 0.2, surfaceOnly);
    ASSERT_EQ(r.points.size(), 20u) << surfaceOnly;
    for (std::size_t i = 0; i < r.points.size(); ++i) {
      EXPECT_NEAR(r.points[i].x(), -1.9 + 0.2 * static_cast<double>(i), 1e-9) << surfaceOnly;
      EXPECT_NEAR(r.points[i].y(), 1.01, 1e-9) << surfaceOnly;
      EXPECT_NEAR(r.points[i].z(), 0.51, 1e-9) << surfaceOnly;
    }
  }
}

TEST(LatticeShell, KeepsTheOuterLayersOfACube) {
  std::vector<Vec3> cube;
  for (int z = 0; z < 6; ++z)
    for (int y = 0; y < 6; ++y)
      for (int x = 0; x < 6; ++x) cube.emplace_back(0.5 * x + 0.25, 0.5 * y - 3, 0.5 * z);
  EXPECT_EQ(latticeShell(cube, 0.5, 1).size(), 216U - 64U);  // the 4^3 core goes
  const std::vector<Vec3> two = latticeShell(cube, 0.5, 2);
  EXPECT_EQ(two.size(), 216U - 8U);                          // the 2^3 core goes
  for (const Vec3& p : two) {                                // and it is the core that went
    const Vec3 k = (p - Vec3(0.25, -3, 0)) / 0.5;
    const bool core = k.minCoeff() > 1.5 && k.maxCoeff() < 3.5;
    EXPECT_FALSE(core) << p.transpose();
  }
  EXPECT_TRUE(latticeShell({}, 0.5, 2).empty());
}

// A 2 x 1 x 3 box filled at 0.5 (4 x 2 x 6 lattice points, the outer layers a quarter
// particle inside the faces), turned 30 degrees about z: a point on k outer layers lies
// under k faces (one on a face, two on an edge, three at a corner) and gets their outward
// normals, turned with the box, whichever way the mesh is wound.
TEST(SurfaceFaces, AFacesEdgesAndCornersPointsGetTheirFacesOutwardNormals) {
  const double s = 0.5, a = 30 * std::numbers::pi / 180;
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(a, Vec3::UnitZ()).toRotationMatrix();
  TriangleMesh box = boxMesh(Vec3(-1, -0.5, -1.5), Vec3(1, 0.5, 1.5));
  std::vector<Vec3> points;
  std::vector<std::array<int, 3>> index;
  for (int z = 0; z < 6; ++z)
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < 4; ++x) {
        points.push_back(turn * Vec3(-0.75 + s * x, -0.25 + s * y, -1.25 + s * z));
        index.push_back({x, y, z});
      }
  for (Vec3& v : box.vertices) v = turn * v;
  TriangleMesh insideOut = box;
  for (auto& t : insideOut.triangles) std::swap(t[1], t[2]);
  for (const TriangleMesh* mesh : {&box, &insideOut}) {
    const std::vector<SurfaceFaces> faces = surfaceFaces(*mesh, points, 0.8 * s, 5, true);
    ASSERT_EQ(faces.size(), points.size());
    const int last[3] = {3, 1, 5};
    std::size_t counts[4] = {0, 0, 0, 0};
    for (std::size_t k = 0; k < points.size(); ++k) {
      std::vector<Vec3> expected;
      for (int c = 0; c < 3; ++c)
        if (index[k][c] == 0 || index[k][c] == last[c])
          expected.push_back((index[k][c] == 0 ? -1.0 : 1.0) * (turn * Vec3::Unit(c)));
      // y has two layers, both outer: every point lies under the top or the bottom.
      ASSERT_EQ(faces[k].count, expected.size()) << "point " << k;
      ++counts[faces[k].count];
      for (const Vec3& e : expected) {
        bool found = false;
        for (int g = 0; g < faces[k].count; ++g)
          found = found || ((faces[k].normal[g] - e).norm() < 1e-12 && faces[k].sides[g] == 1);
        EXPECT_TRUE(found) << "point " << k << ": no outward face " << e.transpose();
      }
    }
    EXPECT_EQ(counts[1], 2U * 2 * 4);  // the 2 x 4 inner points of the top and of the bottom
    EXPECT_EQ(counts[3], 8U);          // the corners
    EXPECT_EQ(counts[2], 48U - 16U - 8U);
  }
}

// A thin plate's middle layer lies under both sides, one plane: a face either way; at its
// rim, that face and the rim's. An open mesh has no inside: its faces point either way. A
// primitive sphere (11.25 degrees a segment) has no face at 5 degrees, nor at 15 (its
// facets meet at less than 30 degrees: a curve, not an edge); a point far from every
// triangle has none.
TEST(SurfaceFaces, AThinPlatesSidesAndAnOpenMeshPointBothWaysAndASphereHasNone) {
  const TriangleMesh plate = boxMesh(Vec3(-3, -0.1, -3), Vec3(3, 0.1, 3));
  const std::vector<Vec3> points = {Vec3(0, 0, 0), Vec3(1.3, 0.05, -2.1), Vec3(2.9, 0, 0), Vec3(0, 2, 0),
                                    Vec3(0, 0.35, 0)};
  const std::vector<SurfaceFaces> f = surfaceFaces(plate, points, 0.4, 5, true);
  for (int k : {0, 1}) {
    ASSERT_EQ(f[k].count, 1) << k;
    EXPECT_NEAR(std::abs(f[k].normal[0].y()), 1.0, 1e-12);
    EXPECT_EQ(f[k].sides[0], 2);
  }
  ASSERT_EQ(f[2].count, 2);  // 0.1 from the rim: the plate's sides and the rim's face
  EXPECT_EQ(f[3].count, 0);  // nothing within 0.4
  ASSERT_EQ(f[4].count, 1);  // only the top side within 0.4: out of the plate
  EXPECT_EQ(f[4].sides[0], 1);
  EXPECT_NEAR(f[4].normal[0].y(), 1.0, 1e-12);
  TriangleMesh open = plate;
  open.triangles.resize(open.triangles.size() - 2);  // one face fewer
  EXPECT_EQ(surfaceFaces(open, points, 0.4, 5, false)[4].sides[0], 2);

  const TriangleMesh ball = sphereMesh(Vec3::Zero(), 2.0, 16, 32);
  std::vector<Vec3> shell;
  for (int k = 0; k < 200; ++k) {
    const double t = 0.1 + 2.9 * k / 200.0, p = 2.399963 * k;  // a spiral over the sphere
    shell.push_back(1.8 * Vec3(std::sin(t) * std::cos(p), std::cos(t), std::sin(t) * std::sin(p)));
  }
  for (const SurfaceFaces& g : surfaceFaces(ball, shell, 0.4, 5, true)) EXPECT_EQ(g.count, 0);
  // At 15 degrees neighbouring facets are one face: where a point sees only those, it
  // gets one, pointing out within 15 degrees of the sphere's own normal there.
  const std::vector<SurfaceFaces> coarse = surfaceFaces(ball, shell, 0.4, 15, true);
  std::size_t flat = 0;
  for (std::size_t k = 0; k < shell.size(); ++k) {
    EXPECT_LE(coarse[k].count, 1);
    if (coarse[k].count != 1) continue;
    ++flat;
    EXPECT_EQ(coarse[k].sides[0], 1);
    EXPECT_GT(coarse[k].normal[0].dot(shell[k].normalized()), std::cos(15 * std::numbers::pi / 180));
  }
  EXPECT_GT(flat, 0U);
}

}  // namespace
}  // namespace softsub::geometry
