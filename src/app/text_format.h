#pragma once
/// Small number and box formatting shared by the commands' human-readable output.
#include <cstdint>
#include <string>
#include <string_view>

#include "core/aabb.h"

namespace softsub::app {

/// 10000 -> "10,000".
std::string groupThousands(std::uint64_t n);

/// A count and its noun, grouped and pluralised: (1, "frame") -> "1 frame",
/// (10000, "particle") -> "10,000 particles".
std::string countOf(std::uint64_t n, std::string_view noun);

/// Seconds as "m:ss" (or "h:mm:ss" from one hour on).
std::string clockTime(double seconds);

/// "x [lo, hi]  y [lo, hi]  z [lo, hi]", or "(empty)".
std::string describeBox(const Aabb& box);

}  // namespace softsub::app
