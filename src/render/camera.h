#pragma once
/// The viewer's and renderer's camera: the seed's `<Camera>` (an eye point and two
/// angles) plus the moves the viewer's keys and mouse make. Pure math, no OpenGL.
#include <array>
#include <optional>

#include <Eigen/Core>

#include "core/aabb.h"
#include "core/math.h"

namespace softsub::render {

/// A pinhole camera. With both angles 0 it looks along -z with +y up; `pitch` (the
/// scene's VerticalAngle) tilts it up for positive values, `yaw` (HorizontalAngle)
/// turns it left, about +y, for positive values. Angles in degrees.
struct Camera {
  Vec3 eye{0, 10, 40};  ///< position, scene units
  double pitch = 0;     ///< degrees, in [-89, 89]
  double yaw = 0;       ///< degrees
  double fovY = 45;     ///< vertical field of view, degrees

  /// Unit view direction.
  [[nodiscard]] Vec3 forward() const;
  /// Unit vector to the right of the view, horizontal.
  [[nodiscard]] Vec3 right() const;
  /// Moves the eye along the view direction (arrow keys up/down).
  void moveForward(double distance);
  /// Turns left by `degrees` about the vertical axis through the eye (arrow keys left/right).
  void turn(double degrees);
  /// Orbits the eye about `pivot` by yaw/pitch increments and looks at it (left drag).
  void orbit(double yawDegrees, double pitchDegrees, const Vec3& pivot);
  /// Moves the eye towards `pivot` (factor < 1) or away from it (factor > 1) (wheel).
  void zoom(double factor, const Vec3& pivot);
  /// Points the camera at `target` from where it is.
  void lookAt(const Vec3& target);
  /// The world-to-view matrix.
  [[nodiscard]] Eigen::Matrix4f view() const;
};

/// The OpenGL perspective projection (right-handed view, depth to [-1, 1]).
[[nodiscard]] Eigen::Matrix4f perspective(double fovYDegrees, double aspect, double near, double far);

/// Near and far clip distances that hold `bounds` (and a floor around it) seen from `camera`.
[[nodiscard]] std::array<double, 2> clipRange(const Camera& camera, const Aabb& bounds);

/// Where `point` lands in a width x height picture (x to the right, y down, pixel centres
/// at +0.5); nothing when it is behind the camera.
[[nodiscard]] std::optional<std::array<double, 2>> projectToPixel(const Camera& camera, const Vec3& point,
                                                                   int width, int height);

/// A camera that looks at `bounds` from the front (+z side), slightly above, so the
/// whole box is in view at `aspect`: for recorded folders without a scene camera.
[[nodiscard]] Camera frameBounds(const Aabb& bounds, double aspect);

}  // namespace softsub::render
