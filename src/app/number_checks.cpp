#include "number_checks.h"

#include <cmath>

#include <fmt/format.h>

namespace softsub::app {

CLI::Validator finiteNumberIn(double least, double most, const std::string& allowed) {
  return CLI::Validator(
      [least, most, allowed](std::string& text) -> std::string {
        double v = 0;
        if (!CLI::detail::lexical_cast(text, v))
          return fmt::format("{} is not a number (allowed: {})", text, allowed);
        // NaN fails every comparison, so it is refused by name, not by the range.
        if (std::isnan(v)) return fmt::format("{} is not a number (allowed: {})", text, allowed);
        if (!std::isfinite(v) || v < least || v > most)
          return fmt::format("{} is out of range (allowed: {})", text, allowed);
        return {};
      },
      allowed);
}

CLI::Validator finiteNonNegative() {
  return finiteNumberIn(0.0, std::numeric_limits<double>::max(), "a finite number >= 0");
}

CLI::Validator particleCap() { return finiteNumberIn(1.0, 1.8e19, "a whole number >= 1"); }

}  // namespace softsub::app
