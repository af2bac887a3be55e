// Body basics: Euler angles, pose integration, world inertia, primitives' meshes.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "geometry/mass_properties.h"
#include "geometry/primitives.h"
#include "rigid/body.h"
#include "support/meshes.h"

namespace softsub::rigid {
namespace {

TEST(Body, EulerAnglesTurnXThenYThenZ) {
  // X by 90° takes +y to +z; then Y by 90° takes +z to +x.
  const Quat q = rotationFromEulerDegrees(Vec3(90, 90, 0));
  EXPECT_TRUE((q * Vec3::UnitY()).isApprox(Vec3::UnitX(), 1e-12)) << (q * Vec3::UnitY()).transpose();
  // Z alone by 90° takes +x to +y.
  EXPECT_TRUE((rotationFromEulerDegrees(Vec3(0, 0, 90)) * Vec3::UnitX()).isApprox(Vec3::UnitY(), 1e-12));
}

TEST(Body, PoseTurnsByOmegaDtExactly) {
  BodyInfo info;
  BodyState s;
  const Vec3 w(0, 2.0, 0);  // rad/s about y
  for (int k = 0; k < 100; ++k) integratePose(info, s, Vec3(1, 0, 0), w, 0.01);
  EXPECT_NEAR(s.position.x(), 1.0, 1e-12);
  const double angle = Eigen::AngleAxisd(s.orientation).angle();
  EXPECT_NEAR(angle, 2.0, 1e-9);
  EXPECT_NEAR(s.orientation.norm(), 1.0, 1e-12);
}

TEST(Body, StaticBodiesNeverMove) {
  BodyInfo info;
  info.dynamic = false;
  BodyState s;
  integratePose(info, s, Vec3(1, 2, 3), Vec3(1, 1, 1), 1.0);
  EXPECT_EQ(s.position, Vec3::Zero());
  EXPECT_EQ(kineticEnergy(info, s), 0.0);
}

TEST(Body, WorldInverseInertiaIsTheSimilarityTransform) {
  BodyInfo info;
  info.inverseInertia = Vec3(1, 2, 3).asDiagonal();
  BodyState s;
  s.orientation = Quat(Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitZ()));
  const Mat3 w = worldInverseInertia(info, s);
  // Turning 90° about z swaps the x and y axes' moments.
  EXPECT_NEAR(w(0, 0), 2, 1e-12);
  EXPECT_NEAR(w(1, 1), 1, 1e-12);
  EXPECT_NEAR(w(2, 2), 3, 1e-12);
  s.angularMomentum = Vec3(0, 0, 6);
  EXPECT_TRUE(angularVelocity(info, s).isApprox(Vec3(0, 0, 18), 1e-12));
}

TEST(Primitives, FrustumsAreClosedOutwardAndHaveTheirVolume) {
  const double pi = std::numbers::pi;
  const geometry::TriangleMesh cyl = geometry::frustumMesh(1, -1, 1, 1, 64);
  const double cylArea = 0.5 * 64 * std::sin(2 * pi / 64);  // polygon area, r = 1
  EXPECT_NEAR(scenarios::signedVolume(cyl), cylArea * 2, 1e-9);
  const geometry::TriangleMesh cone = geometry::frustumMesh(1, -0.25, 0, 0.75, 64);
  EXPECT_NEAR(scenarios::signedVolume(cone), cylArea / 3, 1e-9);
  // Closed: the mesh mass properties accept them, and the cone's centre of mass is on its
  // axis a quarter of the height above its base.
  const geometry::MassProperties p = geometry::meshMassProperties(cone, 1.0);
  EXPECT_NEAR(p.centerOfMass.y(), 0.0, 1e-9);
  EXPECT_NEAR(p.centerOfMass.x(), 0.0, 1e-9);
}

}  // namespace
}  // namespace softsub::rigid
