#pragma once
/// A triangle mesh as the geometry module uses it: shared vertices, index triples.
#include <array>
#include <cstdint>
#include <vector>

#include "core/aabb.h"
#include "core/math.h"

namespace softsub::geometry {

/// One key for the edge between vertices a and b, whichever way a triangle runs it.
[[nodiscard]] inline std::uint64_t edgeKey(std::uint32_t a, std::uint32_t b) {
  return a < b ? (std::uint64_t{a} << 32) | b : (std::uint64_t{b} << 32) | a;
}

/// Triangles over shared vertices. Counter-clockwise seen from outside is the
/// orientation the mass properties assume for a closed mesh (positive volume).
struct TriangleMesh {
  std::vector<Vec3> vertices;                          ///< scene units
  std::vector<std::array<std::uint32_t, 3>> triangles; ///< indices into vertices

  /// The box around every vertex (empty for an empty mesh).
  [[nodiscard]] Aabb bounds() const {
    Aabb box;
    for (const Vec3& v : vertices) box.add(v.x(), v.y(), v.z());
    return box;
  }
};

}  // namespace softsub::geometry
