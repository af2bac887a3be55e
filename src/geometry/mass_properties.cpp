#include "geometry/mass_properties.h"

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <unordered_map>

#include <fmt/format.h>

#include "core/error.h"

namespace softsub::geometry {

Mat3 sphereInertia(double m, double r) { return Mat3::Identity() * (0.4 * m * r * r); }

Mat3 coneInertia(double m, double r, double h) {
  const double axial = 3.0 / 10.0 * m * r * r;
  const double perp = 3.0 / 20.0 * m * r * r + 3.0 / 80.0 * m * h * h;
  return Vec3(perp, axial, perp).asDiagonal();
}

Mat3 cuboidInertia(double m, double w, double h, double d) {
  const double k = m / 12.0;
  return Vec3(k * (h * h + d * d), k * (w * w + d * d), k * (w * w + h * h)).asDiagonal();
}

Mat3 cylinderInertia(double m, double r, double h) {
  const double axial = 0.5 * m * r * r;
  const double perp = m / 12.0 * (3 * r * r + h * h);
  return Vec3(perp, axial, perp).asDiagonal();
}

namespace {

/// Number of directed edges whose reverse is missing (counted with multiplicity). Zero
/// exactly when the triangles form a closed surface, the condition for the divergence
/// theorem to give a volume that does not depend on the origin.
std::size_t unmatchedEdges(const TriangleMesh& mesh) {
  // Key: (min, max) vertex pair; value: uses min->max minus uses max->min.
  std::unordered_map<std::uint64_t, long> balance;
  balance.reserve(mesh.triangles.size() * 2);
  for (const auto& t : mesh.triangles) {
    if (t[0] >= mesh.vertices.size() || t[1] >= mesh.vertices.size() || t[2] >= mesh.vertices.size())
      throw std::invalid_argument("meshMassProperties: triangle index out of range");
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[static_cast<std::size_t>(k)];
      const std::uint32_t b = t[static_cast<std::size_t>((k + 1) % 3)];
      if (a == b) continue;
      const std::uint64_t key = edgeKey(a, b);
      balance[key] += a < b ? 1 : -1;
    }
  }
  std::size_t unmatched = 0;
  for (const auto& [key, n] : balance) unmatched += static_cast<std::size_t>(std::labs(n));
  return unmatched;
}

}  // namespace

MassProperties meshMassProperties(const TriangleMesh& mesh, double mass, const std::string& source) {
  if (!(mass > 0) || !std::isfinite(mass))
    throw std::invalid_argument(fmt::format("meshMassProperties: mass {} is not positive and finite", mass));
  const InputLocation where{source, 0, "mesh"};
  if (mesh.triangles.empty()) throw InputError(where, "the mesh has no triangles");
  if (const std::size_t open = unmatchedEdges(mesh); open > 0)
    throw InputError(where,
                     fmt::format("the mesh is not closed ({} edges have no opposite edge), so it "
                                 "encloses no definite volume",
                                 open),
                     "a closed (watertight) triangle mesh");

  // Integrate relative to the centre of the bounds, so that a mesh far from the origin
  // loses no precision to cancellation.
  const Aabb box = mesh.bounds();
  const Vec3 lo(box.lo[0], box.lo[1], box.lo[2]);
  const Vec3 hi(box.hi[0], box.hi[1], box.hi[2]);
  const Vec3 ref = 0.5 * (lo + hi);

  // Each triangle (a, b, c) with the reference point spans a tetrahedron of signed volume
  // a·(b×c)/6; summing them (divergence theorem) gives the volume integrals of 1, x and
  // x xᵀ over the solid. For a tetrahedron with one vertex at the origin:
  //   ∫ x dV = V (a + b + c) / 4,   ∫ x xᵀ dV = V/20 (a aᵀ + b bᵀ + c cᵀ + s sᵀ), s = a+b+c.
  double volume = 0;
  Vec3 first = Vec3::Zero();
  Mat3 second = Mat3::Zero();
  for (const auto& t : mesh.triangles) {
    const Vec3 a = mesh.vertices[t[0]] - ref;
    const Vec3 b = mesh.vertices[t[1]] - ref;
    const Vec3 c = mesh.vertices[t[2]] - ref;
    const double v = a.dot(b.cross(c)) / 6.0;
    const Vec3 s = a + b + c;
    volume += v;
    first += v / 4.0 * s;
    second += v / 20.0 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
  }
  // An inside-out mesh negates every integral; flip them all back.
  if (volume < 0) {
    volume = -volume;
    first = -first;
    second = -second;
  }
  const double extent = (hi - lo).maxCoeff();
  if (!(volume > 1e-12 * extent * extent * extent))
    throw InputError(where, fmt::format("the mesh encloses no volume ({:g})", volume),
                     "a closed triangle mesh around a solid");

  MassProperties out;
  out.volume = volume;
  const Vec3 com = first / volume;  // relative to ref
  out.centerOfMass = ref + com;
  // Second moment about the centre of mass (parallel-axis shift), then the inertia
  // tensor I = tr(C) Id - C, scaled by the density.
  const Mat3 central = second - volume * (com * com.transpose());
  const double density = mass / volume;
  out.inertia = density * (central.trace() * Mat3::Identity() - central);
  out.inertia = 0.5 * (out.inertia + out.inertia.transpose());  // exactly symmetric
  return out;
}

}  // namespace softsub::geometry
