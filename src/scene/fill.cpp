#include "scene/fill.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace softsub::scene {

namespace {

constexpr std::uint64_t kSaturated = std::numeric_limits<std::uint64_t>::max();

// 2^64 as a double: anything at or above it does not fit in uint64.
constexpr double kTwoTo64 = 18446744073709551616.0;

std::uint64_t toCount(double n) {
  if (!(n >= 1)) return 0;  // also NaN
  if (n >= kTwoTo64) return kSaturated;
  return static_cast<std::uint64_t>(n);
}

std::uint64_t saturatingMul(std::uint64_t a, std::uint64_t b) {
  if (a != 0 && b > kSaturated / a) return kSaturated;
  return a * b;
}

std::uint64_t saturatingAdd(std::uint64_t a, std::uint64_t b) {
  return b > kSaturated - a ? kSaturated : a + b;
}

bool validSpacing(double s) { return std::isfinite(s) && s > 0; }

// Points along one box axis: floor((hi - lo)/spacing + 1e-9).
std::uint64_t boxAxisCount(double lo, double hi, double spacing) {
  if (!validSpacing(spacing) || !std::isfinite(lo) || !std::isfinite(hi)) return 0;
  return toCount(std::floor((hi - lo) / spacing + 1e-9));
}

// The sphere lattice in units of Spacing: point (i, j, k) is inside when
// i^2 + j^2 + k^2 <= limit2. Counting and generating share this one predicate.
struct SphereLattice {
  double reachReal = 0;    // Radius (1 + 1e-12) / Spacing
  std::int64_t reach = 0;  // floor(reachReal): largest |i| that can be inside
  double limit2 = 0;       // reachReal^2

  explicit SphereLattice(const FillDesc& f) {
    if (!validSpacing(f.spacing) || !std::isfinite(f.radius) || f.radius < 0) return;
    reachReal = f.radius * (1 + 1e-12) / f.spacing;
    limit2 = reachReal * reachReal;
    if (reachReal <= kMaxExactSphereReach) reach = static_cast<std::int64_t>(std::floor(reachReal));
  }
  [[nodiscard]] bool exact() const { return reachReal <= kMaxExactSphereReach; }
  [[nodiscard]] bool inside(std::int64_t i, std::int64_t j, std::int64_t k) const {
    return static_cast<double>(i * i + j * j + k * k) <= limit2;
  }
  // Largest k >= 0 with (i, j, k) inside, or -1 when (i, j, 0) is outside.
  [[nodiscard]] std::int64_t columnTop(std::int64_t i, std::int64_t j) const {
    const double rest = limit2 - static_cast<double>(i * i + j * j);
    if (rest < 0) return inside(i, j, 0) ? 0 : -1;
    auto k = static_cast<std::int64_t>(std::floor(std::sqrt(rest)));
    // sqrt and the predicate may disagree by one at the boundary: follow the predicate.
    while (inside(i, j, k + 1)) ++k;
    while (k >= 0 && !inside(i, j, k)) --k;
    return k;
  }
};

std::uint64_t sphereCount(const FillDesc& f) {
  if (!validSpacing(f.spacing) || !std::isfinite(f.radius) || f.radius < 0 ||
      !f.center.allFinite()) {
    return 0;
  }
  const SphereLattice lattice(f);
  if (!lattice.exact()) {
    const double r = lattice.reachReal;
    return toCount(4.0 / 3.0 * 3.14159265358979323846 * r * r * r);
  }
  // Columns along k, counted for i, j >= 0 and mirrored: 4 copies off both axes,
  // 2 on one axis, 1 on the k axis.
  std::uint64_t total = 0;
  for (std::int64_t i = 0; i <= lattice.reach; ++i) {
    for (std::int64_t j = 0; j <= lattice.reach; ++j) {
      const std::int64_t top = lattice.columnTop(i, j);
      if (top < 0) break;  // columns only shrink as j grows
      const auto column = static_cast<std::uint64_t>(2 * top + 1);
      const std::uint64_t copies = (i == 0 ? 1U : 2U) * (j == 0 ? 1U : 2U);
      total += column * copies;
    }
  }
  return total;
}

}  // namespace

std::uint64_t fillCount(const FillDesc& fill) {
  switch (fill.shape) {
    case FillShape::Box: {
      std::uint64_t n = 1;
      for (int a = 0; a < 3; ++a) n = saturatingMul(n, boxAxisCount(fill.min[a], fill.max[a], fill.spacing));
      return n;
    }
    case FillShape::Sphere: return sphereCount(fill);
    case FillShape::Mesh: return 0;
  }
  return 0;
}

void generateFill(const FillDesc& fill, std::vector<Vec3>& out) {
  const std::uint64_t n = fillCount(fill);
  if (fill.shape == FillShape::Mesh) {
    throw std::invalid_argument("mesh fills need mesh loading, which arrives with issue #3");
  }
  if (n == 0) return;
  out.reserve(static_cast<std::size_t>(saturatingAdd(out.size(), n)));
  const double s = fill.spacing;
  if (fill.shape == FillShape::Box) {
    const std::uint64_t nx = boxAxisCount(fill.min.x(), fill.max.x(), s);
    const std::uint64_t ny = boxAxisCount(fill.min.y(), fill.max.y(), s);
    const std::uint64_t nz = boxAxisCount(fill.min.z(), fill.max.z(), s);
    for (std::uint64_t k = 0; k < nz; ++k) {
      for (std::uint64_t j = 0; j < ny; ++j) {
        for (std::uint64_t i = 0; i < nx; ++i) {
          out.emplace_back(fill.min.x() + (static_cast<double>(i) + 0.5) * s,
                           fill.min.y() + (static_cast<double>(j) + 0.5) * s,
                           fill.min.z() + (static_cast<double>(k) + 0.5) * s);
        }
      }
    }
    return;
  }
  const SphereLattice lattice(fill);
  if (!lattice.exact()) throw std::length_error("sphere fill too large to generate");
  const std::int64_t r = lattice.reach;
  for (std::int64_t k = -r; k <= r; ++k) {
    for (std::int64_t j = -r; j <= r; ++j) {
      for (std::int64_t i = -r; i <= r; ++i) {
        if (lattice.inside(i, j, k)) {
          out.push_back(fill.center + Vec3(static_cast<double>(i), static_cast<double>(j),
                                           static_cast<double>(k)) * s);
        }
      }
    }
  }
}

}  // namespace softsub::scene
