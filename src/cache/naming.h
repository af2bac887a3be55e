#pragma once
/// Names of the cache files of one frame: `<scene>.<tag>.sim`, `pdc/<fluid>Shape.<ticks>.pdc`
/// and `ply/<scene>.<tag>.ply` inside the output folder (see docs/cache-formats.md).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace softsub::cache {

/// Frame number as written in file names: at least 4 digits, zero padded (0007, 12345).
/// Throws std::invalid_argument for a negative frame.
[[nodiscard]] std::string frameTag(std::int64_t frame);

/// Maya time of a frame in ticks (6000 a second): round(frame * 6000 / fps); 250 a frame
/// at 24 fps. Throws std::invalid_argument for a negative frame or a non-positive fps.
[[nodiscard]] std::int64_t pdcTicks(std::int64_t frame, double fps);

/// Checks that `name` can be part of a file name: not empty, no '/', '\\' or control
/// characters. Throws InputError naming `element` (e.g. "Fluid/Name") otherwise.
void checkFileNamePart(std::string_view name, std::string_view element);

/// A frame file's name `<scene>.<digits>.sim`, split.
struct SimFileName {
  std::string scene;
  std::int64_t frame = 0;
};
/// Splits a `.sim` frame file's name; nullopt for any other name.
[[nodiscard]] std::optional<SimFileName> parseSimFileName(std::string_view name);

/// `dir/<scene>.<tag>.sim`.
[[nodiscard]] std::filesystem::path simPath(const std::filesystem::path& dir,
                                            std::string_view sceneName, std::int64_t frame);

/// `dir/pdc/<fluid>Shape.<ticks>.pdc`, the name Maya's particle cache looks for.
[[nodiscard]] std::filesystem::path pdcPath(const std::filesystem::path& dir,
                                            std::string_view fluidName, std::int64_t frame,
                                            double fps);

/// `dir/ply/<scene>.<tag>.ply`.
[[nodiscard]] std::filesystem::path plyPath(const std::filesystem::path& dir,
                                            std::string_view sceneName, std::int64_t frame);

}  // namespace softsub::cache
