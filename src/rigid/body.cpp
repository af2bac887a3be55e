#include "rigid/body.h"

#include <cmath>
#include <numbers>

#include <Eigen/Eigenvalues>

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

void turnFree(const BodyInfo& info, BodyState& s, double dt) {
  if (!info.dynamic || info.inverseInertia.isZero()) return;
  // Principal axes (the columns of v, a proper rotation) and inverse moments, ascending:
  // the last is the axis of least moment, the fastest for a given L.
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(info.inverseInertia);
  Mat3 v = eig.eigenvectors();
  if (v.determinant() < 0) v.col(0) = -v.col(0);
  const Vec3 k = eig.eigenvalues();
  const Quat toPrincipal(v);
  // L in the principal axes as they turn; the body's turn gathers in those axes.
  Vec3 lp = (s.orientation * toPrincipal).conjugate() * s.angularMomentum;
  Quat turn = Quat::Identity();
  const auto about = [&](int axis, double t) {
    const double angle = k[axis] * lp[axis] * t;
    if (angle == 0) return;
    const Quat r(Eigen::AngleAxisd(angle, Vec3::Unit(axis)));
    turn = turn * r;          // about the body's own axis: applied on the right
    lp = r.conjugate() * lp;  // L stays put in the world, so turns back in the body
  };
  about(0, 0.5 * dt);
  about(1, 0.5 * dt);
  about(2, dt);
  about(1, 0.5 * dt);
  about(0, 0.5 * dt);
  s.orientation = (s.orientation * toPrincipal * turn * toPrincipal.conjugate()).normalized();
}

double kineticEnergy(const BodyInfo& info, const BodyState& s) {
  if (!info.dynamic) return 0;
  const Vec3 w = angularVelocity(info, s);
  return 0.5 * info.mass * s.velocity.squaredNorm() + 0.5 * w.dot(s.angularMomentum);
}

}  // namespace softsub::rigid
