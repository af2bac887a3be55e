#include "cache/naming.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "cache/message.h"
#include "core/error.h"

namespace softsub::cache {

std::string frameTag(std::int64_t frame) {
  if (frame < 0) throw std::invalid_argument(fmt::format("frameTag: negative frame {}", frame));
  return fmt::format("{:04d}", frame);
}

std::int64_t pdcTicks(std::int64_t frame, double fps) {
  if (frame < 0) throw std::invalid_argument(fmt::format("pdcTicks: negative frame {}", frame));
  if (!(fps > 0) || !std::isfinite(fps)) {
    throw std::invalid_argument(fmt::format("pdcTicks: frames per second {} is not > 0", fps));
  }
  return std::llround(static_cast<double>(frame) * 6000.0 / fps);
}

void checkFileNamePart(std::string_view name, std::string_view element) {
  const auto refuse = [&](std::string problem) {
    throw InputError({"", 0, std::string(element)}, std::move(problem),
                     "a non-empty name of at most 100 bytes without '/', '\\' or control characters, "
                     "other than '.' and '..'");
  };
  if (name.empty()) refuse("empty name cannot be used in a file name");
  // A file name holds at most 255 bytes on common file systems, and the longest one a
  // name goes into adds a frame tag, an extension and a temporary suffix with the host's
  // name: 100 leaves room (the scene reader caps fluid and object names at 100 too).
  if (name.size() > 100)
    refuse(fmt::format("name '{}' is {} bytes long: too long for the file names it goes into",
                       detail::excerpt(name), name.size()));
  if (name == "." || name == "..") refuse(fmt::format("name '{}' would make a hidden file", name));
  for (const char c : name) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '/' || c == '\\' || u < 0x20 || u == 0x7f) {
      refuse(fmt::format("name '{}' cannot be used in a file name", detail::excerpt(name)));
    }
  }
}

std::filesystem::path simPath(const std::filesystem::path& dir, std::string_view sceneName,
                              std::int64_t frame) {
  checkFileNamePart(sceneName, "scene name");
  return dir / fmt::format("{}.{}.sim", sceneName, frameTag(frame));
}

std::filesystem::path pdcPath(const std::filesystem::path& dir, std::string_view fluidName,
                              std::int64_t frame, double fps) {
  checkFileNamePart(fluidName, "Fluid/Name");
  return dir / "pdc" / fmt::format("{}Shape.{}.pdc", fluidName, pdcTicks(frame, fps));
}

std::filesystem::path plyPath(const std::filesystem::path& dir, std::string_view sceneName,
                              std::int64_t frame) {
  checkFileNamePart(sceneName, "scene name");
  return dir / "ply" / fmt::format("{}.{}.ply", sceneName, frameTag(frame));
}

std::optional<SimFileName> parseSimFileName(std::string_view name) {
  constexpr std::string_view ext = ".sim";
  if (name.size() <= ext.size() || !name.ends_with(ext)) return std::nullopt;
  const std::string_view base = name.substr(0, name.size() - ext.size());
  const std::size_t dot = base.rfind('.');
  if (dot == std::string_view::npos || dot == 0 || dot + 1 == base.size()) return std::nullopt;
  const std::string_view digits = base.substr(dot + 1);
  if (!std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
    return std::nullopt;
  SimFileName out;
  const auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), out.frame);
  if (ec != std::errc{} || ptr != digits.data() + digits.size()) return std::nullopt;
  out.scene = std::string(base.substr(0, dot));
  return out;
}

}  // namespace softsub::cache
