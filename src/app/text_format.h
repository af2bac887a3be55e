#pragma once
/// Small number and box formatting shared by the commands' human-readable output.
#include <cstdint>
#include <string>

#include "core/aabb.h"

namespace softsub::app {

/// 10000 -> "10,000".
std::string groupThousands(std::uint64_t n);

/// Seconds as "m:ss" (or "h:mm:ss" from one hour on).
std::string clockTime(double seconds);

/// "x [lo, hi]  y [lo, hi]  z [lo, hi]", or "(empty)".
std::string describeBox(const Aabb& box);

}  // namespace softsub::app
