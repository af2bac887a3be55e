#include "geometry/primitives.h"

#include <cmath>
#include <cstdint>
#include <numbers>

namespace softsub::geometry {

TriangleMesh boxMesh(const Vec3& lo, const Vec3& hi) {
  TriangleMesh m;
  for (int k = 0; k < 8; ++k)
    m.vertices.emplace_back(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(), k & 4 ? hi.z() : lo.z());
  // Faces as quads (a, b, c, d) counter-clockwise from outside.
  static constexpr std::uint32_t kQuads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                                 {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& q : kQuads) {
    m.triangles.push_back({q[0], q[1], q[2]});
    m.triangles.push_back({q[0], q[2], q[3]});
  }
  return m;
}

TriangleMesh sphereMesh(const Vec3& c, double r, int rings, int segments) {
  TriangleMesh m;
  const double pi = std::numbers::pi;
  m.vertices.push_back(c + Vec3(0, r, 0));  // north pole: 0
  for (int i = 1; i < rings; ++i) {
    const double theta = pi * i / rings;
    for (int j = 0; j < segments; ++j) {
      const double phi = 2 * pi * j / segments;
      m.vertices.push_back(c + r * Vec3(std::sin(theta) * std::cos(phi), std::cos(theta),
                                        -std::sin(theta) * std::sin(phi)));
    }
  }
  const auto south = static_cast<std::uint32_t>(m.vertices.size());
  m.vertices.push_back(c + Vec3(0, -r, 0));
  auto at = [&](int ring, int seg) {  // ring 1..rings-1
    return static_cast<std::uint32_t>(1 + (ring - 1) * segments + (seg % segments));
  };
  for (int j = 0; j < segments; ++j) m.triangles.push_back({0, at(1, j), at(1, j + 1)});
  for (int i = 1; i < rings - 1; ++i)
    for (int j = 0; j < segments; ++j) {
      m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  for (int j = 0; j < segments; ++j) m.triangles.push_back({south, at(rings - 1, j + 1), at(rings - 1, j)});
  return m;
}

TriangleMesh frustumMesh(double r0, double y0, double r1, double y1, int segments) {
  TriangleMesh m;
  const double pi = std::numbers::pi;
  // A ring of `segments` vertices, or one vertex for radius 0; returns its first index.
  auto ring = [&](double r, double y) {
    const auto first = static_cast<std::uint32_t>(m.vertices.size());
    if (r <= 0) {
      m.vertices.emplace_back(0, y, 0);
      return first;
    }
    for (int j = 0; j < segments; ++j) {
      const double phi = 2 * pi * j / segments;
      m.vertices.emplace_back(r * std::cos(phi), y, -r * std::sin(phi));
    }
    return first;
  };
  const std::uint32_t b = ring(r0, y0), t = ring(r1, y1);
  const auto n = static_cast<std::uint32_t>(segments);
  auto bot = [&](std::uint32_t j) { return r0 > 0 ? b + j % n : b; };
  auto top = [&](std::uint32_t j) { return r1 > 0 ? t + j % n : t; };
  for (std::uint32_t j = 0; j < n; ++j) {  // the side, as quads split in two (one if a ring is an apex)
    if (r0 > 0) m.triangles.push_back({bot(j), bot(j + 1), top(j + 1)});
    if (r1 > 0) m.triangles.push_back({bot(j), top(j + 1), top(j)});
  }
  // Caps as fans around their centres.
  if (r0 > 0) {
    const auto c = static_cast<std::uint32_t>(m.vertices.size());
    m.vertices.emplace_back(0, y0, 0);
    for (std::uint32_t j = 0; j < n; ++j) m.triangles.push_back({c, bot(j + 1), bot(j)});
  }
  if (r1 > 0) {
    const auto c = static_cast<std::uint32_t>(m.vertices.size());
    m.vertices.emplace_back(0, y1, 0);
    for (std::uint32_t j = 0; j < n; ++j) m.triangles.push_back({c, top(j), top(j + 1)});
  }
  return m;
}

}  // namespace softsub::geometry
