#pragma once
/// Command-line checks for options. CLI11's Range and NonNegativeNumber compare with <
/// and >, which NaN passes; these refuse NaN and the infinities too. And a path given as
/// an empty string is refused, not read as "not given".
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace softsub::app {

/// A finite number in [least, most]; `allowed` says so in words, in the error
/// ("nan is not a number (allowed: 1 to 5)") and in --help after the type.
[[nodiscard]] CLI::Validator finiteNumberIn(double least, double most, const std::string& allowed);

/// A finite number >= 0.
[[nodiscard]] CLI::Validator finiteNonNegative();

/// A whole number in [least, most] (most = INT64_MAX: no upper end), refused in our
/// words: "1.5 is not a whole number (allowed: integer [0, 1000000])", "2000 is out of
/// range (allowed: integer [0, 1024])". CLI11's Range says "Value 2000 not in range 0 to
/// 1024", and a value its conversion refuses "Could not convert: --frames = 1.5".
/// Apply it with ->transform (not ->check): it also rewrites the text as plain decimal
/// ("0048" -> "48"), which CLI11 would otherwise read as octal. `allowedText` replaces
/// the "integer [least, most]" wording.
[[nodiscard]] CLI::Validator wholeNumberIn(std::int64_t least, std::int64_t most, std::string allowedText = {});

/// One of `names`: "rk4 is not one of the choices (allowed: a, b, c)".
[[nodiscard]] CLI::Validator oneOf(std::vector<std::string> names);

/// A particle count cap: >= 1 ("0 is out of range (allowed: a whole number in [1,
/// 9223372036854775807])", not CLI::PositiveNumber's range up to the largest double
/// written out in 309 digits).
[[nodiscard]] CLI::Validator particleCap();

/// A file or folder name that is not empty: `run ""` ran the default scene and
/// `--out ""` wrote to the default folder, as if the option had been left out.
/// `optional`: the option has a default, which the error then points to.
[[nodiscard]] CLI::Validator nonEmptyPath(bool optional = true);

/// A file name ending in `extension` (".mp4", in any case), for an output whose kind the
/// name promises: `render --movie shot.scene` or `fill --out bunny.obj` wrote an MP4 or
/// a PLY over the scene or mesh the user meant to keep. `kind`: what is written, in
/// words ("an MP4 movie").
[[nodiscard]] CLI::Validator outputFileWithExtension(const std::string& extension, const std::string& kind);

}  // namespace softsub::app
