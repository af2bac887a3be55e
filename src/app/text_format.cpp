#include "text_format.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace softsub::app {

std::string groupThousands(std::uint64_t n) {
  std::string digits = std::to_string(n);
  std::string out;
  const std::size_t lead = digits.size() % 3 == 0 ? 3 : digits.size() % 3;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i >= lead && (i - lead) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

std::string countOf(std::uint64_t n, std::string_view noun) {
  return fmt::format("{} {}{}", groupThousands(n), noun, n == 1 ? "" : "s");
}

std::string clockTime(double seconds) {
  const auto s = static_cast<std::int64_t>(std::llround(std::max(0.0, seconds)));
  if (s >= 3600) return fmt::format("{}:{:02}:{:02}", s / 3600, (s / 60) % 60, s % 60);
  return fmt::format("{}:{:02}", s / 60, s % 60);
}

std::string describeBox(const Aabb& box) {
  if (box.empty()) return "(empty)";
  return fmt::format("x [{:.4g}, {:.4g}]  y [{:.4g}, {:.4g}]  z [{:.4g}, {:.4g}]", box.lo[0], box.hi[0],
                     box.lo[1], box.hi[1], box.lo[2], box.hi[2]);
}

}  // namespace softsub::app
