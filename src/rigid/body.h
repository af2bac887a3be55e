#pragma once
/// Rigid bodies made of particles: what never changes about a body (BodyInfo, in the
/// Model), its pose and momenta (BodyState, in the State), and the body-space offsets of
/// its particles (BodySet). A body's particles live in the one ParticleStore with the
/// fluids; their positions and velocities there are written from the body's state.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/math.h"

namespace softsub::rigid {

/// Constant properties of one body.
struct BodyInfo {
  std::string name;               ///< unique; used in `.sim` and error messages
  bool dynamic = true;            ///< false: never moves (infinite mass)
  double mass = 1;                ///< total mass (> 0)
  double inverseMass = 1;         ///< 1 / mass, 0 for a static body
  Mat3 inverseInertia = Mat3::Identity();  ///< body space, about the centre of mass; 0 for static
  double restitution = 0.5;       ///< NormalAttenuation e
  double friction = 0.1;          ///< TangentAttenuation, the Coulomb coefficient at rest
  double particleRadius = 0.5;    ///< half the particle diameter
  std::uint32_t firstId = 0;      ///< its particles have ids firstId .. firstId + count - 1
  std::uint32_t count = 0;        ///< number of particles
  double farthest = 0;            ///< its farthest particle's distance from the centre of mass
  /// Where the geometry's origin sits in body space (body space = centre of mass at 0,
  /// axes of the geometry): the `.sim` transform's translation is x + R * this.
  Vec3 originInBody{0, 0, 0};
  double uniformScale = 1;        ///< the scene's UniformScale (the `.sim` scale)
  std::string geometryFile;       ///< the mesh file written beside the frames (`<scene>Geo/...`)
};

/// Pose and momenta of one body. The angular momentum, not the angular velocity, is
/// the state: free rotation then conserves it exactly, and impulses add to it exactly.
struct BodyState {
  Vec3 position{0, 0, 0};          ///< centre of mass, world
  Quat orientation = Quat::Identity();  ///< body → world
  Vec3 velocity{0, 0, 0};          ///< of the centre of mass
  Vec3 angularMomentum{0, 0, 0};   ///< about the centre of mass, world axes
};

/// What one contact pushed with in the last substep, kept for the next (warm start): the
/// sequential impulses then start from last substep's answer instead of from zero, so a
/// stack or a heavy body on a light one is held by impulses that converge over substeps,
/// not only within one. Part of the State (checkpoints keep it, so a resumed run
/// continues bit for bit).
struct ContactMemory {
  std::int32_t a = 0, b = -1;  ///< body indices (b = -1: a wall)
  std::int32_t wall = -1;      ///< the wall when b = -1 (Contact::wall)
  Vec3 pointInA{0, 0, 0};      ///< the contact point, body a's own axes, from its centre of mass
  Vec3 force{0, 0, 0};         ///< the impulse on a (normal and friction, world axes) divided by the substep
};

/// The inverse inertia tensor in world space, R I⁻¹ Rᵀ (the seed's similarity transform).
[[nodiscard]] inline Mat3 worldInverseInertia(const BodyInfo& b, const BodyState& s) {
  const Mat3 r = s.orientation.toRotationMatrix();
  return r * b.inverseInertia * r.transpose();
}

/// Angular velocity, world axes: I_world⁻¹ L.
[[nodiscard]] inline Vec3 angularVelocity(const BodyInfo& b, const BodyState& s) {
  return worldInverseInertia(b, s) * s.angularMomentum;
}

/// Rotation from the scene's Euler angles in degrees, applied X first, then Y, then Z
/// (world axes): R = Rz * Ry * Rx.
[[nodiscard]] Quat rotationFromEulerDegrees(const Vec3& degrees);

/// The flat faces one body particle lies under, body space (BodySet::faces).
struct BodyFaces {
  std::array<std::array<float, 3>, 3> normal{};  ///< unit
  /// Per face: 1 the normal points out of the body; 2 it may point either way (a thin
  /// part's particles lie under both of its sides).
  std::array<std::uint8_t, 3> sides{};
  std::uint8_t count = 0;
};

/// Every body's constant data plus its particles' body-space offsets.
struct BodySet {
  std::vector<BodyInfo> bodies;
  std::uint32_t firstEntity = 0;  ///< particle owner of body b is firstEntity + b
  std::uint32_t firstId = 0;      ///< lowest particle id of any body (bodies' ids are contiguous)
  /// Body-space offset of particle id (firstId + k) from its body's centre of mass.
  std::vector<float> ox, oy, oz;
  /// Per particle id (firstId + k): the flat faces of the body's mesh it lies under
  /// (geometry::surfaceFaces, body space): one under a face, two at an edge, three at a
  /// corner, none on a curved surface or inside. Contacts take a face's normal instead
  /// of the line between particle centres, which leans wherever two lattices do not line
  /// up. Empty: no particle has faces.
  std::vector<BodyFaces> faces;

  [[nodiscard]] bool empty() const { return bodies.empty(); }
  /// Total body particles.
  [[nodiscard]] std::size_t particleCount() const { return ox.size(); }
};

/// Advances a pose by dt with the current velocities: x += v dt, and q turned by the
/// angular velocity w for dt exactly (the rotation of angle |w| dt about w), normalised.
void integratePose(const BodyInfo& info, BodyState& s, const Vec3& velocity, const Vec3& omega, double dt);

/// Turns a body through dt of torque-free rotation, its angular momentum L (world) kept:
/// the exact rotations about its three principal axes (each at the angle its own part of
/// L gives it, about the axis as it turns), composed symmetrically: the axis of least
/// moment for the whole dt in the middle, the other two for dt / 2 on each side. The
/// energy's error stays bounded however long the body spins (the scheme is symplectic),
/// including a thin rod spinning fast about its axis, whose moments differ five
/// thousandfold; a turn by the angular velocity, even the midpoint's, gained energy
/// there (a rod dropped on the floor, 29 → 332 in 3 s).
void turnFree(const BodyInfo& info, BodyState& s, double dt);

/// Kinetic energy (translation + rotation) of a body.
[[nodiscard]] double kineticEnergy(const BodyInfo& info, const BodyState& s);

}  // namespace softsub::rigid
