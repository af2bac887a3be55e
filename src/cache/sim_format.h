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

/// One rigid body's pose at a frame, as the `.sim` file's `<Object>` element holds it
/// (name, uniform scale, position, rotation, filename; the other fields are not stored).
using SimObject = ObjectSnapshot;

/// A decoded `.sim` file. The file stores neither ids, velocities, colours, sizes nor the
/// frame rate: each fluid's ids are 0..n-1 in file order (the stable-id order), its
/// velocities are zero, and colour, particleSize and framesPerSecond keep their defaults;
/// objects keep only their name, scale, position, rotation and filename.
struct SimFile {
  FrameSnapshot frame;  ///< frame number, time, fluid positions and objects (in file order)
};

/// Encodes a frame (its fluids and objects) as `.sim` XML text.
[[nodiscard]] std::string encodeSim(const FrameSnapshot& frame);

/// Same as encodeSim, into `out` (cleared first), reusing its capacity.
void encodeSimInto(std::string& out, const FrameSnapshot& frame);

/// Parses and validates `.sim` text; InputError with `fileName`, line and element on bad input.
[[nodiscard]] SimFile decodeSim(std::string_view text, const std::string& fileName);

/// Reads and decodes a `.sim` file (IoError if unreadable, InputError if invalid).
[[nodiscard]] SimFile readSimFile(const std::filesystem::path& path);

}  // namespace softsub::cache
