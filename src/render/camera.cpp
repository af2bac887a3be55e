#include "render/camera.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace softsub::render {

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

Vec3 directionOf(double pitchDeg, double yawDeg) {
  const double p = pitchDeg * kDeg, y = yawDeg * kDeg;
  return {-std::sin(y) * std::cos(p), std::sin(p), -std::cos(y) * std::cos(p)};
}

}  // namespace

Vec3 Camera::forward() const { return directionOf(pitch, yaw); }

Vec3 Camera::right() const {
  const double y = yaw * kDeg;
  return {std::cos(y), 0, -std::sin(y)};
}

void Camera::moveForward(double distance) { eye += forward() * distance; }

void Camera::turn(double degrees) { yaw = std::remainder(yaw + degrees, 360.0); }

void Camera::orbit(double yawDegrees, double pitchDegrees, const Vec3& pivot) {
  const Vec3 offset = eye - pivot;
  const double r = offset.norm();
  if (r <= 0) return turn(yawDegrees);
  // The eye sits at pivot - r * forward; orbiting changes the angles of forward.
  lookAt(pivot);
  yaw = std::remainder(yaw + yawDegrees, 360.0);
  pitch = std::clamp(pitch + pitchDegrees, -89.0, 89.0);
  eye = pivot - forward() * r;
}

void Camera::zoom(double factor, const Vec3& pivot) {
  const Vec3 offset = eye - pivot;
  const double r = offset.norm();
  if (r <= 0) return;
  const double minimum = 1e-3 * std::max(1.0, r);
  eye = pivot + offset * (std::max(r * factor, minimum) / r);
}

void Camera::lookAt(const Vec3& target) {
  const Vec3 d = target - eye;
  const double n = d.norm();
  if (n <= 0) return;
  pitch = std::clamp(std::asin(std::clamp(d.y() / n, -1.0, 1.0)) / kDeg, -89.0, 89.0);
  if (std::hypot(d.x(), d.z()) > 1e-12 * n) yaw = std::atan2(-d.x(), -d.z()) / kDeg;
}

Eigen::Matrix4f Camera::view() const {
  const Vec3 f = forward();
  const Vec3 r = right();
  const Vec3 u = r.cross(f);
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.block<1, 3>(0, 0) = r.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -r.dot(eye);
  m(1, 3) = -u.dot(eye);
  m(2, 3) = f.dot(eye);
  return m.cast<float>();
}

Eigen::Matrix4f perspective(double fovYDegrees, double aspect, double near, double far) {
  const double t = 1.0 / std::tan(0.5 * fovYDegrees * kDeg);
  Eigen::Matrix4d p = Eigen::Matrix4d::Zero();
  p(0, 0) = t / aspect;
  p(1, 1) = t;
  p(2, 2) = (far + near) / (near - far);
  p(2, 3) = 2 * far * near / (near - far);
  p(3, 2) = -1;
  return p.cast<float>();
}

std::array<double, 2> clipRange(const Camera& camera, const Aabb& bounds) {
  if (bounds.empty()) return {0.01, 1000};
  double farthest = 0;
  for (int c = 0; c < 8; ++c) {
    const Vec3 corner{(c & 1) ? bounds.hi[0] : bounds.lo[0], (c & 2) ? bounds.hi[1] : bounds.lo[1],
                      (c & 4) ? bounds.hi[2] : bounds.lo[2]};
    farthest = std::max(farthest, (corner - camera.eye).norm());
  }
  // The floor reaches beyond the box and the reflection below it: keep a generous far.
  const double far = 3 * farthest + 1;
  return {std::max(far * 1e-5, 1e-4), far};
}

std::optional<std::array<double, 2>> projectToPixel(const Camera& camera, const Vec3& point, int width,
                                                     int height) {
  const Eigen::Vector4f v = camera.view() * Eigen::Vector4f(static_cast<float>(point.x()),
                                                            static_cast<float>(point.y()),
                                                            static_cast<float>(point.z()), 1.0f);
  if (v.z() >= 0) return std::nullopt;
  const double t = 1.0 / std::tan(0.5 * camera.fovY * kDeg);
  const double aspect = static_cast<double>(width) / height;
  const double ndcX = t / aspect * v.x() / -v.z();
  const double ndcY = t * v.y() / -v.z();
  return std::array<double, 2>{(ndcX + 1) * 0.5 * width, (1 - ndcY) * 0.5 * height};
}

Camera frameBounds(const Aabb& bounds, double aspect) {
  Camera c;
  if (bounds.empty()) return c;
  const Vec3 lo{bounds.lo[0], bounds.lo[1], bounds.lo[2]};
  const Vec3 hi{bounds.hi[0], bounds.hi[1], bounds.hi[2]};
  const Vec3 centre = 0.5 * (lo + hi);
  const double radius = std::max(0.5 * (hi - lo).norm(), 1e-3);
  const double halfFov = 0.5 * c.fovY * kDeg;
  const double fit = std::min(std::tan(halfFov), std::tan(halfFov) * aspect);
  const double distance = radius / fit * 1.1;
  c.pitch = -15;
  c.yaw = 0;
  c.eye = centre - c.forward() * distance;
  return c;
}

}  // namespace softsub::render
