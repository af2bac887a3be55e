#include "rigid/body.h"

#include <cmath>
#include <numbers>

namespace softsub::rigid {

Quat rotationFromEulerDegrees(const Vec3& degrees) {
  const double k = std::numbers::pi / 180.0;
  const Quat qx(Eigen::AngleAxisd(degrees.x() * k, Vec3::UnitX()));
  const Quat qy(Eigen::AngleAxisd(degrees.y() * k, Vec3::UnitY()));
  const Quat qz(Eigen::AngleAxisd(degrees.z() * k, Vec3::UnitZ()));
  return (qz * qy * qx).normalized();
}

void integratePose(const BodyInfo& info, BodyState& s, const Vec3& velocity, const Vec3& omega, double dt) {
  if (!info.dynamic) return;
  s.position += velocity * dt;
  const double angle = omega.norm() * dt;
  if (angle > 0) {
    const Quat turn(Eigen::AngleAxisd(angle, omega.normalized()));
    s.orientation = (turn * s.orientation).normalized();
  }
}

double kineticEnergy(const BodyInfo& info, const BodyState& s) {
  if (!info.dynamic) return 0;
  const Vec3 w = angularVelocity(info, s);
  return 0.5 * info.mass * s.velocity.squaredNorm() + 0.5 * w.dot(s.angularMomentum);
}

}  // namespace softsub::rigid
