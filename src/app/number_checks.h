#pragma once
/// Command-line checks for floating-point options. CLI11's Range and NonNegativeNumber
/// compare with < and >, which NaN passes; these refuse NaN and the infinities too.
#include <limits>
#include <string>

#include <CLI/CLI.hpp>

namespace softsub::app {

/// A finite number in [least, most]; `allowed` says so in words, in the error
/// ("nan is not a number (allowed: 1 to 5)") and in --help after the type.
[[nodiscard]] CLI::Validator finiteNumberIn(double least, double most, const std::string& allowed);

/// A finite number >= 0.
[[nodiscard]] CLI::Validator finiteNonNegative();

/// A particle count cap: >= 1 ("0 is out of range (allowed: a whole number >= 1)", not
/// CLI::PositiveNumber's range up to the largest double written out in 309 digits).
[[nodiscard]] CLI::Validator particleCap();

}  // namespace softsub::app
