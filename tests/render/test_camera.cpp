// The camera's conventions and moves: pure math, checked against hand-derived values.
#include <gtest/gtest.h>

#include <cmath>

#include "render/camera.h"

namespace softsub::render {
namespace {

TEST(Camera, ZeroAnglesLookDownNegativeZ) {
  Camera c;
  EXPECT_NEAR(c.forward().x(), 0, 1e-12);
  EXPECT_NEAR(c.forward().y(), 0, 1e-12);
  EXPECT_NEAR(c.forward().z(), -1, 1e-12);
  EXPECT_NEAR(c.right().x(), 1, 1e-12);
}

TEST(Camera, PositiveAnglesLookUpAndTurnLeft) {
  Camera c;
  c.pitch = 30;
  EXPECT_NEAR(c.forward().y(), 0.5, 1e-12);
  c.pitch = 0;
  c.yaw = 90;
  EXPECT_NEAR(c.forward().x(), -1, 1e-12);  // turned left from -z is -x
  EXPECT_NEAR(c.forward().z(), 0, 1e-12);
}

TEST(Camera, ViewMatrixPutsTheEyeAtTheOriginLookingDownNegativeZ) {
  Camera c;
  c.eye = {1, 2, 3};
  c.pitch = -20;
  c.yaw = 35;
  const Eigen::Matrix4f v = c.view();
  const Eigen::Vector4f eye = v * Eigen::Vector4f(1, 2, 3, 1);
  EXPECT_NEAR(eye.head<3>().norm(), 0, 1e-5);
  const Vec3 ahead = c.eye + 5 * c.forward();
  const Eigen::Vector4f a = v * Eigen::Vector4f(float(ahead.x()), float(ahead.y()), float(ahead.z()), 1);
  EXPECT_NEAR(a.x(), 0, 1e-5);
  EXPECT_NEAR(a.y(), 0, 1e-5);
  EXPECT_NEAR(a.z(), -5, 1e-5);
}

TEST(Camera, ProjectionOfPointsAheadAndAside) {
  Camera c;
  c.eye = {0, 0, 10};
  // Straight ahead lands in the centre of the picture.
  const auto centre = projectToPixel(c, {0, 0, 0}, 200, 100);
  ASSERT_TRUE(centre);
  EXPECT_NEAR((*centre)[0], 100, 1e-6);
  EXPECT_NEAR((*centre)[1], 50, 1e-6);
  // A point at the top edge of the field of view lands on row 0.
  const double top = 10 * std::tan(22.5 * M_PI / 180);
  const auto edge = projectToPixel(c, {0, top, 0}, 200, 100);
  ASSERT_TRUE(edge);
  EXPECT_NEAR((*edge)[1], 0, 1e-3);
  // Right of the axis is right in the picture; behind the camera is nothing.
  EXPECT_GT((*projectToPixel(c, {1, 0, 0}, 200, 100))[0], 100);
  EXPECT_FALSE(projectToPixel(c, {0, 0, 20}, 200, 100));
}

TEST(Camera, OrbitKeepsTheDistanceAndLooksAtThePivot) {
  Camera c;
  c.eye = {0, 5, 20};
  const Vec3 pivot{1, 2, -1};
  const double before = (c.eye - pivot).norm();
  c.orbit(40, -15, pivot);
  EXPECT_NEAR((c.eye - pivot).norm(), before, 1e-9);
  const Vec3 toPivot = (pivot - c.eye).normalized();
  EXPECT_NEAR(toPivot.dot(c.forward()), 1, 1e-9);
}

TEST(Camera, ZoomScalesTheDistanceToThePivot) {
  Camera c;
  c.eye = {0, 0, 20};
  c.zoom(0.5, {0, 0, 0});
  EXPECT_NEAR(c.eye.z(), 10, 1e-12);
  c.zoom(3, {0, 0, 0});
  EXPECT_NEAR(c.eye.z(), 30, 1e-12);
}

TEST(Camera, MoveAndTurnFollowTheSeedKeys) {
  Camera c;
  c.eye = {0, 0, 0};
  c.moveForward(2);
  EXPECT_NEAR(c.eye.z(), -2, 1e-12);
  c.turn(-90);  // right arrow: turn right, now looking along +x
  EXPECT_NEAR(c.forward().x(), 1, 1e-12);
  c.moveForward(1);
  EXPECT_NEAR(c.eye.x(), 1, 1e-12);
}

TEST(Camera, FrameBoundsSeesEveryCorner) {
  Aabb box;
  box.add(-3, 0, -2);
  box.add(5, 4, 6);
  for (double aspect : {0.5, 1.0, 2.0}) {
    const Camera c = frameBounds(box, aspect);
    const int w = static_cast<int>(400 * aspect), h = 400;
    for (int k = 0; k < 8; ++k) {
      const Vec3 p{(k & 1) ? 5.0 : -3.0, (k & 2) ? 4.0 : 0.0, (k & 4) ? 6.0 : -2.0};
      const auto px = projectToPixel(c, p, w, h);
      ASSERT_TRUE(px);
      EXPECT_GE((*px)[0], 0);
      EXPECT_LE((*px)[0], w);
      EXPECT_GE((*px)[1], 0);
      EXPECT_LE((*px)[1], h);
    }
  }
}

}  // namespace
}  // namespace softsub::render
