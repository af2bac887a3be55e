#pragma once
// Closed triangle meshes built in code (no files): for the geometry tests and benchmarks.
// All are oriented counter-clockwise seen from outside.
#include <cmath>
#include <numbers>

#include "geometry/triangle_mesh.h"

namespace softsub::scenarios {

/// An axis-aligned box [lo, hi], 12 triangles.
inline geometry::TriangleMesh boxMesh(const Vec3& lo, const Vec3& hi) {
  geometry::TriangleMesh m;
  for (int k = 0; k < 8; ++k)
    m.vertices.emplace_back(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(), k & 4 ? hi.z() : lo.z());
  // Faces as quads (a, b, c, d) counter-clockwise from outside.
  const int quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& q : quads) {
    m.triangles.push_back({std::uint32_t(q[0]), std::uint32_t(q[1]), std::uint32_t(q[2])});
    m.triangles.push_back({std::uint32_t(q[0]), std::uint32_t(q[2]), std::uint32_t(q[3])});
  }
  return m;
}

/// A UV sphere of radius r around c with `rings` latitude bands and `segments` longitude
/// segments (poles are single vertices).
inline geometry::TriangleMesh sphereMesh(const Vec3& c, double r, int rings, int segments) {
  geometry::TriangleMesh m;
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

/// A torus around the y axis through c: major radius R, minor radius a.
inline geometry::TriangleMesh torusMesh(const Vec3& c, double R, double a, int major, int minor) {
  geometry::TriangleMesh m;
  const double pi = std::numbers::pi;
  for (int i = 0; i < major; ++i) {
    const double u = 2 * pi * i / major;
    for (int j = 0; j < minor; ++j) {
      const double v = 2 * pi * j / minor;
      const double rr = R + a * std::cos(v);
      m.vertices.push_back(c + Vec3(rr * std::cos(u), a * std::sin(v), -rr * std::sin(u)));
    }
  }
  auto at = [&](int i, int j) { return static_cast<std::uint32_t>((i % major) * minor + (j % minor)); };
  for (int i = 0; i < major; ++i)
    for (int j = 0; j < minor; ++j) {
      m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return m;
}

/// Signed volume by the divergence theorem (positive when oriented outwards).
inline double signedVolume(const geometry::TriangleMesh& m) {
  double v = 0;
  for (const auto& t : m.triangles)
    v += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]])) / 6.0;
  return v;
}

}  // namespace softsub::scenarios
