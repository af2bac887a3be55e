#include "number_checks.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <system_error>

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

CLI::Validator wholeNumberIn(std::int64_t least, std::int64_t most, std::string allowedText) {
  const std::string allowed = !allowedText.empty() ? std::move(allowedText)
                              : most == std::numeric_limits<std::int64_t>::max()
                                  ? fmt::format("integer >= {}", least)
                                  : fmt::format("integer [{}, {}]", least, most);
  return CLI::Validator(
      [least, most, allowed](std::string& text) -> std::string {
        std::int64_t v = 0;
        const char* end = text.data() + text.size();
        const char* first = text.data() + (text.starts_with('+') ? 1 : 0);
        const auto [ptr, ec] = std::from_chars(first, end, v);
        if (ec == std::errc::result_out_of_range)
          return fmt::format("{} is out of range (allowed: {})", text, allowed);
        if (ec != std::errc() || ptr != end || first == end) {
          // A whole number written with an exponent ("2e7") is one too.
          double d = 0;
          const auto [dptr, dec] = std::from_chars(first, end, d);
          if (first == end || dec != std::errc() || dptr != end || !std::isfinite(d) || d != std::floor(d))
            return fmt::format("{} is not a whole number (allowed: {})", text, allowed);
          // 2^63 and beyond do not fit; below that the conversion is exact for whole d.
          if (std::abs(d) >= 9.223372036854775807e18)
            return fmt::format("{} is out of range (allowed: {})", text, allowed);
          v = static_cast<std::int64_t>(d);
        }
        if (v < least || v > most) return fmt::format("{} is out of range (allowed: {})", text, allowed);
        // Plain decimal for CLI11's own conversion, which reads a leading 0 as octal
        // ("0048" would be refused, "0012" taken as 10). Kept because the option
        // applies this validator with ->transform, not ->check.
        text = std::to_string(v);
        return {};
      },
      allowed);
}

CLI::Validator oneOf(std::vector<std::string> names) {
  std::string allowed;
  for (const std::string& n : names) allowed += (allowed.empty() ? "" : ", ") + n;
  return CLI::Validator(
      [names = std::move(names), allowed](std::string& text) -> std::string {
        for (const std::string& n : names)
          if (text == n) return {};
        return fmt::format("{} is not one of the choices (allowed: {})", text, allowed);
      },
      "one of " + allowed);
}

CLI::Validator particleCap() {
  return wholeNumberIn(1, std::numeric_limits<std::int64_t>::max(),
                       fmt::format("a whole number in [1, {}]", std::numeric_limits<std::int64_t>::max()));
}

CLI::Validator nonEmptyPath(bool optional) {
  return CLI::Validator(
      [optional](std::string& value) {
        if (!value.empty()) return std::string();
        return std::string("an empty name is no file or folder") +
               (optional ? " (leave the option out for its default)" : "");
      },
      "PATH");
}

CLI::Validator outputFileWithExtension(const std::string& extension, const std::string& kind) {
  return CLI::Validator(
      [extension, kind](std::string& value) {
        std::string tail =
            value.size() > extension.size() ? value.substr(value.size() - extension.size()) : "";
        for (char& c : tail) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        if (tail == extension && value[value.size() - extension.size() - 1] != '/') return std::string();
        return fmt::format(
            "'{}' does not end in {}: the option writes {} there, and a name without "
            "that ending may be a scene, mesh or frame to keep",
            value, extension, kind);
      },
      "FILE" + extension);
}

}  // namespace softsub::app
