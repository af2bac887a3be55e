// The test meshes themselves: closed, outward, the volume their shape should have.
#include <gtest/gtest.h>

#include <map>
#include <numbers>

#include "support/meshes.h"

namespace softsub::scenarios {
namespace {

// Every directed edge appears once and its reverse once: closed and consistently oriented.
void expectClosedOriented(const geometry::TriangleMesh& m) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
  for (const auto& [e, n] : edges) {
    EXPECT_EQ(n, 1);
    EXPECT_EQ(edges.count({e.second, e.first}), 1u);
  }
}

TEST(TestMeshes, AreClosedOutwardAndHaveTheirVolume) {
  const auto box = boxMesh(Vec3(0, 0, 0), Vec3(2, 3, 4));
  expectClosedOriented(box);
  EXPECT_NEAR(signedVolume(box), 24.0, 1e-12);
  const auto sphere = sphereMesh(Vec3(1, 2, 3), 2.0, 64, 128);
  expectClosedOriented(sphere);
  EXPECT_NEAR(signedVolume(sphere), 4.0 / 3.0 * std::numbers::pi * 8.0, 0.01 * 33.5);
  const auto torus = torusMesh(Vec3(0, 0, 0), 3.0, 1.0, 96, 48);
  expectClosedOriented(torus);
  EXPECT_NEAR(signedVolume(torus), 2 * std::numbers::pi * std::numbers::pi * 3.0, 0.01 * 59.2);
}

}  // namespace
}  // namespace softsub::scenarios
