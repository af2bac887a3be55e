#pragma once
/// `softsub render`: draw a scene's frames (simulated on the way) or a recorded folder's
/// frames into PNG pictures off-screen, and an MP4 through ffmpeg when asked.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "surface/surface.h"

namespace CLI {
class App;
}

namespace softsub::app {

/// The options of `render`.
struct RenderOptions {
  std::string input;                      ///< .scene file or recorded folder; empty: the default scene
  std::string out;                        ///< folder for the pictures (required)
  std::string scene;  ///< with a recording: its scene file; empty: <scene>.scene beside it
  int width = 1280;                       ///< picture width, pixels
  int height = 720;                       ///< picture height, pixels
  std::string frames;                     ///< "a:b" inclusive, "a:", ":b" or "a"; empty: all
  std::string movie;                      ///< MP4 file to encode with ffmpeg; empty: none
  std::optional<std::int64_t> substeps;   ///< overrides the scene's Substeps
  std::uint64_t maxParticles = 0;         ///< as `run --max-particles`
  bool quiet = false;                     ///< nothing on stderr but errors
  bool surface = false;                   ///< draw each fluid's surface instead of its particles
  surface::SurfaceSettings surfaceSettings;  ///< --voxel-size, --blob-radius (with --surface)
};

/// An inclusive frame range; `last` unset means "to the end".
struct FrameRange {
  std::int64_t first = 0;
  std::optional<std::int64_t> last;
  [[nodiscard]] bool contains(std::int64_t f) const { return f >= first && (!last || f <= *last); }
};

/// Parses `--frames`: "a:b", "a:", ":b", "a" (one frame) or empty (all). InputError
/// naming `option` otherwise (negative numbers, b < a, junk).
[[nodiscard]] FrameRange parseFrameRange(const std::string& text, const std::string& option);

/// `<dir>/<scene>.NNNN.png`: the picture of one frame.
[[nodiscard]] std::filesystem::path picturePath(const std::filesystem::path& dir, std::string_view scene,
                                                std::int64_t frame);

/// Adds the `render` subcommand bound to `options` and returns it.
CLI::App* addRenderCommand(CLI::App& root, RenderOptions& options);

/// Runs it; returns the exit code, throws InputError, IoError or BlowUpError.
int renderCommand(const RenderOptions& options);

/// Encodes `pictures`, in their order, at `fps` into `movie` with ffmpeg (H.264,
/// yuv420p): exactly those pictures, whatever else their folder holds. IoError when
/// ffmpeg is missing or fails, or there is no picture.
void encodeMovie(const std::vector<std::filesystem::path>& pictures, double fps, const std::string& movie);

/// The path of the executable `name` on PATH (or `name` itself when it holds a '/' and
/// is executable), or empty.
[[nodiscard]] std::string findOnPath(const std::string& name);

/// The path of ffmpeg on PATH, or empty.
[[nodiscard]] std::string findFfmpeg();

}  // namespace softsub::app
