#pragma once
// Closed triangle meshes built in code (no files): for the geometry tests and benchmarks.
// All are oriented counter-clockwise seen from outside.
#include <cmath>
#include <numbers>

#include "geometry/primitives.h"
#include "geometry/triangle_mesh.h"

namespace softsub::scenarios {

using geometry::boxMesh;
using geometry::sphereMesh;

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
