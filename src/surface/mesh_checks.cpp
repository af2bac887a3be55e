// Mesh checks that need no OpenVDB: enclosed volume and edge closure/orientation.
#include "surface/surface.h"

#include <algorithm>
#include <unordered_map>

namespace softsub::surface {

double enclosedVolume(const SurfaceMesh& mesh) {
  // Sum of signed tetrahedra (origin, a, b, c): (a . (b x c)) / 6, in double.
  double sum = 0.0;
  for (const auto& t : mesh.triangles) {
    const auto& a = mesh.vertices[t[0]];
    const auto& b = mesh.vertices[t[1]];
    const auto& c = mesh.vertices[t[2]];
    const double cx = double(b[1]) * c[2] - double(b[2]) * c[1];
    const double cy = double(b[2]) * c[0] - double(b[0]) * c[2];
    const double cz = double(b[0]) * c[1] - double(b[1]) * c[0];
    sum += a[0] * cx + a[1] * cy + a[2] * cz;
  }
  return sum / 6.0;
}

bool isClosedAndOriented(const SurfaceMesh& mesh) {
  const auto n = static_cast<std::uint64_t>(mesh.vertices.size());
  // Directed edge (from, to) -> how many triangles run along it that way.
  std::unordered_map<std::uint64_t, int> directed;
  directed.reserve(mesh.triangles.size() * 3);
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      const std::uint64_t a = t[static_cast<std::size_t>(k)];
      const std::uint64_t b = t[static_cast<std::size_t>((k + 1) % 3)];
      if (a >= n || b >= n || a == b) return false;
      if (++directed[(a << 32) | b] > 1) return false;  // same direction twice: flipped or non-manifold
    }
  }
  // Each directed edge needs its reverse exactly once: then every undirected edge has
  // exactly two triangles, running along it in opposite directions.
  return std::all_of(directed.begin(), directed.end(), [&](const auto& e) {
    const std::uint64_t a = e.first >> 32;
    const std::uint64_t b = e.first & 0xffffffffULL;
    const auto it = directed.find((b << 32) | a);
    return it != directed.end() && it->second == 1;
  });
}

}  // namespace softsub::surface
