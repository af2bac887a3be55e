// Lattice fills: exact counts without generating, the documented positions and order.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <tuple>

#include "scene/fill.h"

namespace softsub::scene {
namespace {

FillDesc box(Vec3 min, Vec3 max, double spacing) {
  FillDesc f;
  f.shape = FillShape::Box;
  f.min = min;
  f.max = max;
  f.spacing = spacing;
  return f;
}

FillDesc sphere(Vec3 center, double radius, double spacing) {
  FillDesc f;
  f.shape = FillShape::Sphere;
  f.center = center;
  f.radius = radius;
  f.spacing = spacing;
  return f;
}

std::vector<Vec3> generate(const FillDesc& f) {
  std::vector<Vec3> out;
  generateFill(f, out);
  return out;
}

TEST(Fill, BoxCountsFloorOfExtentOverSpacing) {
  EXPECT_EQ(fillCount(box({0, 0, 0}, {1, 1, 1}, 1)), 1U);
  EXPECT_EQ(fillCount(box({0, 0, 0}, {1, 1, 1}, 0.5)), 8U);
  EXPECT_EQ(fillCount(box({0, 0, 0}, {2, 3, 4}, 1)), 24U);
  EXPECT_EQ(fillCount(box({0, 0, 0}, {1.9, 1, 1}, 1)), 1U);
  // 0.3 / 0.1 is 2.9999999999999996 in doubles: the 1e-9 slack makes it 3.
  EXPECT_EQ(fillCount(box({0, 0, 0}, {0.3, 0.3, 0.3}, 0.1)), 27U);
  EXPECT_EQ(fillCount(box({0, 0, 0}, {0.5, 1, 1}, 1)), 0U);
}

TEST(Fill, BoxPointsAreCellCentresXFastest) {
  const auto p = generate(box({1, 2, 3}, {3, 4, 4}, 1));
  ASSERT_EQ(p.size(), 4U);
  EXPECT_EQ(p[0], Vec3(1.5, 2.5, 3.5));
  EXPECT_EQ(p[1], Vec3(2.5, 2.5, 3.5));
  EXPECT_EQ(p[2], Vec3(1.5, 3.5, 3.5));
  EXPECT_EQ(p[3], Vec3(2.5, 3.5, 3.5));
}

TEST(Fill, SphereCountsLatticePointsInTheBall) {
  // Points of Z^3 with i^2 + j^2 + k^2 <= n: 1, 7, 19, 27, 33, 57 for n = 0 .. 5.
  EXPECT_EQ(fillCount(sphere({0, 0, 0}, 0.5, 1)), 1U);
  EXPECT_EQ(fillCount(sphere({0, 0, 0}, 1, 1)), 7U);
  EXPECT_EQ(fillCount(sphere({0, 0, 0}, std::sqrt(2.0), 1)), 19U);
  EXPECT_EQ(fillCount(sphere({0, 0, 0}, std::sqrt(3.0), 1)), 27U);
  EXPECT_EQ(fillCount(sphere({5, 5, 5}, 4, 2)), 33U);
  EXPECT_EQ(fillCount(sphere({0, 0, 0}, std::sqrt(5.0), 1)), 57U);
}

TEST(Fill, SphereCentreIsAPointAndOrderIsXFastest) {
  const Vec3 c(1, -2, 0.5);
  const auto p = generate(sphere(c, 1, 0.5));
  ASSERT_EQ(p.size(), fillCount(sphere(c, 1, 0.5)));
  EXPECT_NE(std::find(p.begin(), p.end(), c), p.end());
  for (const Vec3& q : p) EXPECT_LE((q - c).norm(), 1 + 1e-12);
  const auto key = [](const Vec3& v) { return std::tuple(v.z(), v.y(), v.x()); };
  EXPECT_TRUE(std::is_sorted(p.begin(), p.end(), [&](const Vec3& a, const Vec3& b) {
    return key(a) < key(b);
  }));
}

TEST(Fill, GenerateAppends) {
  std::vector<Vec3> out{{9, 9, 9}};
  generateFill(box({0, 0, 0}, {2, 1, 1}, 1), out);
  ASSERT_EQ(out.size(), 3U);
  EXPECT_EQ(out[0], Vec3(9, 9, 9));
}

TEST(Fill, CountEqualsGeneratedOnRandomFills) {
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> coord(-10, 10);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int n = 0; n < 400; ++n) {
    const double spacing = 0.05 + unit(rng) * 2;
    FillDesc f;
    if (n % 2 == 0) {
      const Vec3 lo(coord(rng), coord(rng), coord(rng));
      // Extents near whole multiples of the spacing exercise the floor and its slack.
      Vec3 extent;
      for (int a = 0; a < 3; ++a) {
        extent[a] = unit(rng) < 0.5 ? spacing * std::floor(unit(rng) * 12) : unit(rng) * 6;
      }
      f = box(lo, lo + extent, spacing);
    } else {
      const double radius = unit(rng) < 0.5 ? spacing * std::floor(unit(rng) * 8) : unit(rng) * 5;
      f = sphere({coord(rng), coord(rng), coord(rng)}, radius, spacing);
    }
    EXPECT_EQ(fillCount(f), generate(f).size()) << "fill " << n;
  }
}

TEST(Fill, CountsSaturateInsteadOfOverflowing) {
  constexpr auto kMax = std::numeric_limits<std::uint64_t>::max();
  EXPECT_EQ(fillCount(box({0, 0, 0}, {1, 1, 1}, 1e-300)), kMax);
  EXPECT_EQ(fillCount(box({0, 0, 0}, {1, 1, 1}, 1e-7)), kMax);  // 1e21 overflows the product
  EXPECT_EQ(fillCount(box({0, 0, 0}, {1e300, 1e300, 1e300}, 1e-300)), kMax);
  EXPECT_EQ(fillCount(sphere({0, 0, 0}, 1e300, 1e-300)), kMax);
  // Beyond the exact reach a sphere is counted by its volume, instantly.
  const std::uint64_t big = fillCount(sphere({0, 0, 0}, 1e6, 1));
  EXPECT_NEAR(static_cast<double>(big), 4.0 / 3.0 * std::numbers::pi * 1e18, 1e16);
}

TEST(Fill, ExactSphereCountIsFastAtTheLargestReach) {
  const auto start = std::chrono::steady_clock::now();
  const std::uint64_t n = fillCount(sphere({0, 0, 0}, kMaxExactSphereReach, 1));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double volume = 4.0 / 3.0 * std::numbers::pi * std::pow(kMaxExactSphereReach, 3);
  EXPECT_NEAR(static_cast<double>(n), volume, volume * 1e-3);
  EXPECT_LT(seconds, 5.0);
}

TEST(Fill, InvalidAndMeshFillsCountZero) {
  EXPECT_EQ(fillCount(box({0, 0, 0}, {1, 1, 1}, 0)), 0U);
  EXPECT_EQ(fillCount(box({0, 0, 0}, {1, 1, 1}, -1)), 0U);
  EXPECT_EQ(fillCount(box({0, 0, 0}, {1, 1, 1}, std::nan(""))), 0U);
  EXPECT_EQ(fillCount(box({0, 0, 0}, {std::nan(""), 1, 1}, 1)), 0U);
  EXPECT_EQ(fillCount(sphere({0, 0, 0}, -1, 1)), 0U);
  FillDesc mesh;
  mesh.shape = FillShape::Mesh;
  mesh.geometry = "a.obj";
  EXPECT_EQ(fillCount(mesh), 0U);
  std::vector<Vec3> out;
  EXPECT_THROW(generateFill(mesh, out), std::invalid_argument);
}

}  // namespace
}  // namespace softsub::scene
