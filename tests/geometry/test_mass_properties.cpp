// Primitive inertia tensors and the exact mesh mass properties, against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <utility>

#include "core/error.h"
#include "geometry/mass_properties.h"
#include "support/meshes.h"

namespace softsub::geometry {
namespace {

using scenarios::boxMesh;
using scenarios::sphereMesh;
using scenarios::torusMesh;

// Largest entry of |a - b| relative to the largest entry of |b|.
double relativeError(const Mat3& a, const Mat3& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

TEST(PrimitiveInertia, MatchTheirFormulas) {
  const double m = 3.0;
  EXPECT_TRUE(sphereInertia(m, 2.0).isApprox(Mat3::Identity() * 0.4 * m * 4.0));
  EXPECT_TRUE(cuboidInertia(m, 1, 2, 3)
                  .isApprox(Vec3(m / 12 * 13, m / 12 * 10, m / 12 * 5).asDiagonal().toDenseMatrix()));
  EXPECT_TRUE(cylinderInertia(m, 1, 2).isApprox(
      Vec3(m / 12 * (3 + 4), 0.5 * m, m / 12 * (3 + 4)).asDiagonal().toDenseMatrix()));
  const double r = 1.5, h = 4.0;
  const Mat3 cone = coneInertia(m, r, h);
  EXPECT_DOUBLE_EQ(cone(1, 1), 0.3 * m * r * r);
  // The seed's perpendicular term is about the apex; the centre of mass is 3h/4 below it.
  const double seedApex = 3.0 / 5 * m * h * h + 3.0 / 20 * m * r * r;
  EXPECT_NEAR(cone(0, 0), seedApex - m * (0.75 * h) * (0.75 * h), 1e-12 * seedApex);
  EXPECT_DOUBLE_EQ(cone(0, 0), cone(2, 2));
  EXPECT_EQ(cone(0, 1), 0.0);
}

TEST(MeshMassProperties, BoxEqualsTheCuboidFormula) {
  const double m = 2.5;
  const auto p = meshMassProperties(boxMesh(Vec3(-1, -1.5, -2), Vec3(1, 1.5, 2)), m);
  EXPECT_NEAR(p.volume, 24.0, 1e-12);
  EXPECT_LT(p.centerOfMass.norm(), 1e-12);
  EXPECT_LT(relativeError(p.inertia, cuboidInertia(m, 2, 3, 4)), 1e-9);
}

TEST(MeshMassProperties, OffsetBoxMovesTheCentreButNotTheTensor) {
  const double m = 7.0;
  const Vec3 lo(100.25, -40, 3000), size(0.5, 2, 1);
  const auto p = meshMassProperties(boxMesh(lo, lo + size), m);
  EXPECT_NEAR(p.volume, 1.0, 1e-9);
  EXPECT_LT((p.centerOfMass - (lo + 0.5 * size)).norm(), 1e-9);
  EXPECT_LT(relativeError(p.inertia, cuboidInertia(m, size.x(), size.y(), size.z())), 1e-9);
}

TEST(MeshMassProperties, RotatedBoxGivesTheRotatedTensor) {
  const double m = 1.25;
  auto mesh = boxMesh(Vec3(0, 0, 0), Vec3(1, 2, 3));
  const Mat3 R =
      (Eigen::AngleAxisd(0.7, Vec3(1, 2, -1).normalized()) * Eigen::AngleAxisd(-1.1, Vec3::UnitY()))
          .toRotationMatrix();
  const Vec3 shift(5, -2, 1);
  for (Vec3& v : mesh.vertices) v = R * v + shift;
  const auto p = meshMassProperties(mesh, m);
  EXPECT_NEAR(p.volume, 6.0, 1e-9);
  EXPECT_LT((p.centerOfMass - (R * Vec3(0.5, 1, 1.5) + shift)).norm(), 1e-9);
  EXPECT_LT(relativeError(p.inertia, R * cuboidInertia(m, 1, 2, 3) * R.transpose()), 1e-9);
}

TEST(MeshMassProperties, FineSphereConvergesToTwoFifthsMR2) {
  const double m = 4.0, r = 1.5;
  const Vec3 c(1, -2, 0.5);
  const double exact = 0.4 * m * r * r;
  double previous = 1.0;
  for (const int rings : {32, 64, 128}) {
    const auto p = meshMassProperties(sphereMesh(c, r, rings, 2 * rings), m);
    EXPECT_LT((p.centerOfMass - c).norm(), 1e-9 * r);
    double error = 0;
    for (int i = 0; i < 3; ++i) {
      error = std::max(error, std::abs(p.inertia(i, i) - exact) / exact);
      for (int j = 0; j < 3; ++j)
        if (i != j) {
          EXPECT_LT(std::abs(p.inertia(i, j)), 1e-9 * exact);
        }
    }
    // A polyhedron inscribed in the sphere: second order in the resolution.
    EXPECT_LT(error, 0.5 * previous) << rings << " rings";
    previous = error;
  }
  EXPECT_LT(previous, 1e-3);
}

TEST(MeshMassProperties, TorusMatchesItsClosedForm) {
  const double m = 2.0, R = 3.0, a = 1.0;
  const auto p = meshMassProperties(torusMesh(Vec3(0, 0, 0), R, a, 192, 96), m);
  const double axial = m * (R * R + 0.75 * a * a);
  const double perp = m * (0.5 * R * R + 0.625 * a * a);
  EXPECT_NEAR(p.volume, 2 * std::numbers::pi * std::numbers::pi * R * a * a, 2e-3 * p.volume);
  EXPECT_NEAR(p.inertia(1, 1), axial, 1e-3 * axial);
  EXPECT_NEAR(p.inertia(0, 0), perp, 1e-3 * perp);
  EXPECT_NEAR(p.inertia(2, 2), perp, 1e-3 * perp);
  EXPECT_LT(std::abs(p.inertia(0, 1)), 1e-9 * axial);
}

TEST(MeshMassProperties, InsideOutMeshGivesTheSameResult) {
  const auto mesh = sphereMesh(Vec3(0.3, 0, -1), 2.0, 16, 24);
  auto inverted = mesh;
  for (auto& t : inverted.triangles) std::swap(t[1], t[2]);
  const auto p = meshMassProperties(mesh, 3.0);
  const auto q = meshMassProperties(inverted, 3.0);
  EXPECT_NEAR(q.volume, p.volume, 1e-12 * p.volume);
  EXPECT_LT((q.centerOfMass - p.centerOfMass).norm(), 1e-12);
  EXPECT_LT(relativeError(q.inertia, p.inertia), 1e-12);
}

TEST(MeshMassProperties, OpenFlatOrEmptyMeshesThrow) {
  // A box missing its top: open.
  auto open = boxMesh(Vec3(0, 0, 0), Vec3(1, 1, 1));
  open.triangles.resize(open.triangles.size() - 2);
  EXPECT_THROW((void)meshMassProperties(open, 1.0, "open.obj"), InputError);
  try {
    (void)meshMassProperties(open, 1.0, "open.obj");
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "open.obj");
    EXPECT_NE(e.problem().find("not closed"), std::string::npos) << e.what();
  }
  // Two triangles back to back: closed but flat.
  TriangleMesh flat;
  flat.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  flat.triangles = {{0, 1, 2}, {0, 2, 1}};
  EXPECT_THROW((void)meshMassProperties(flat, 1.0), InputError);
  EXPECT_THROW((void)meshMassProperties(TriangleMesh{}, 1.0), InputError);
  EXPECT_THROW((void)meshMassProperties(boxMesh(Vec3(0, 0, 0), Vec3(1, 1, 1)), 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace softsub::geometry
