#pragma once
/// Vector and quaternion types for descriptions, bodies and cold code. The hot loops
/// work on the float arrays of ParticleStore instead.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace softsub {

using Vec3 = Eigen::Vector3d;      ///< a point, direction or colour in scene units
using Vec3f = Eigen::Vector3f;     ///< single-precision vector (particle data)
using Quat = Eigen::Quaterniond;   ///< a rotation (w x y z)
using Mat3 = Eigen::Matrix3d;      ///< an inertia tensor or rotation matrix

}  // namespace softsub
