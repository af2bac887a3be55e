#pragma once
/// PLY point clouds: a whole frame (all fluids) as one binary little-endian `.ply`, and a
/// reader for the PLY point clouds other tools write. See docs/cache-formats.md.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/snapshot.h"

namespace softsub::cache {

/// PLY scalar types (each has two spellings in headers: `uchar` / `uint8`, ...).
enum class PlyScalar { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

/// One scalar property of the `vertex` element, every vertex's value widened to double.
struct PlyProperty {
  std::string name;                     ///< e.g. "x"
  PlyScalar type = PlyScalar::Float32;  ///< type declared in the header
  std::vector<double> values;           ///< one per vertex
};

/// A decoded PLY point cloud: the `vertex` element's scalar properties, plus what the
/// softsub header comments say (frame, time, fluid names). Other elements are skipped.
struct PlyCloud {
  std::string format;                   ///< ascii, binary_little_endian or binary_big_endian
  std::vector<std::string> comments;    ///< every `comment` line's text, in order
  bool hasFrame = false;                ///< a `comment softsub frame F time T` line was found
  std::int64_t frame = 0;               ///< frame number from that comment
  double time = 0;                      ///< time from that comment, seconds
  std::vector<std::string> fluidNames;  ///< from `comment fluid <index> <name>` lines
  std::size_t vertexCount = 0;          ///< number of vertices
  std::vector<PlyProperty> properties;  ///< scalar vertex properties, header order

  /// The vertex property called `name`, or nullptr.
  [[nodiscard]] const PlyProperty* find(std::string_view name) const;
};

/// Encodes all fluids of a frame as a binary little-endian PLY point cloud with float
/// x y z vx vy vz, uint id, int fluid, uchar red green blue per vertex.
[[nodiscard]] std::string encodePly(const FrameSnapshot& frame);

/// Same as encodePly, into `out` (cleared first), reusing its capacity.
void encodePlyInto(std::string& out, const FrameSnapshot& frame);

/// Parses a PLY file (ascii or binary, any scalar types and property order, other
/// elements and list properties skipped); InputError on anything it cannot read.
/// Never allocates more than the input can hold, whatever the declared counts.
[[nodiscard]] PlyCloud decodePly(std::string_view bytes, const std::string& fileName);

/// Reads and decodes a PLY file (IoError if unreadable, InputError if invalid).
[[nodiscard]] PlyCloud readPlyFile(const std::filesystem::path& path);

}  // namespace softsub::cache
