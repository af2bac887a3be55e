#pragma once
/// Axis-aligned bounding box of points.
#include <algorithm>
#include <limits>

namespace softsub {

/// An axis-aligned box; empty() until a point is added.
struct Aabb {
  double lo[3] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                  std::numeric_limits<double>::infinity()};
  double hi[3] = {-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                  -std::numeric_limits<double>::infinity()};

  /// True when no point has been added.
  [[nodiscard]] bool empty() const { return lo[0] > hi[0]; }
  /// Grows the box to contain (x, y, z).
  void add(double x, double y, double z) {
    lo[0] = std::min(lo[0], x); hi[0] = std::max(hi[0], x);
    lo[1] = std::min(lo[1], y); hi[1] = std::max(hi[1], y);
    lo[2] = std::min(lo[2], z); hi[2] = std::max(hi[2], z);
  }
};

}  // namespace softsub
