#pragma once
/// The `.sim` file: one recorded frame as XML (the seed's "Simulation format"), with
/// fluid positions in stable-id order. See docs/cache-formats.md for the exact syntax.
#include <array>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/snapshot.h"

namespace softsub::cache {

/// One rigid body's pose at a frame, as the `.sim` file's `<Object>` element holds it.
struct SimObject {
  std::string name;                            ///< the body's unique name from the scene
  double uniformScale = 1;                     ///< the scene's UniformScale
  std::array<double, 3> position{0, 0, 0};     ///< world position, scene units
  std::array<double, 4> rotation{1, 0, 0, 0};  ///< unit quaternion w x y z
  std::string filename;                        ///< the body's geometry file, as in the scene
};

/// A decoded `.sim` file. The file stores neither ids, velocities, colours, sizes nor the
/// frame rate: each fluid's ids are 0..n-1 in file order (the stable-id order), its
/// velocities are zero, and colour, particleSize and framesPerSecond keep their defaults.
struct SimFile {
  FrameSnapshot frame;             ///< frame number, time and fluid positions
  std::vector<SimObject> objects;  ///< rigid bodies, in file order (may be empty)
};

/// Encodes a frame (and optional rigid bodies) as `.sim` XML text.
[[nodiscard]] std::string encodeSim(const FrameSnapshot& frame,
                                    std::span<const SimObject> objects = {});

/// Same as encodeSim, into `out` (cleared first), reusing its capacity.
void encodeSimInto(std::string& out, const FrameSnapshot& frame,
                   std::span<const SimObject> objects = {});

/// Parses and validates `.sim` text; InputError with `fileName`, line and element on bad input.
[[nodiscard]] SimFile decodeSim(std::string_view text, const std::string& fileName);

/// Reads and decodes a `.sim` file (IoError if unreadable, InputError if invalid).
[[nodiscard]] SimFile readSimFile(const std::filesystem::path& path);

}  // namespace softsub::cache
