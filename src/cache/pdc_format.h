#pragma once
/// Maya's particle disk cache (`.pdc`): one fluid at one frame, big-endian binary.
/// See docs/cache-formats.md for the byte layout.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/snapshot.h"

namespace softsub::cache {

/// Maya's PDC attribute types.
enum class PdcType : std::int32_t {
  Int = 0,          ///< one int32
  IntArray = 1,     ///< count int32
  Double = 2,       ///< one double
  DoubleArray = 3,  ///< count doubles
  Vector = 4,       ///< three doubles
  VectorArray = 5,  ///< count x 3 doubles
};

/// One attribute of a PDC file, values widened to double (int32 fit exactly).
struct PdcAttribute {
  std::string name;             ///< e.g. "position"
  PdcType type = PdcType::Int;  ///< Maya's type code
  std::vector<double> values;   ///< 1, 3, count or 3 x count values depending on type
};

/// A decoded PDC file.
struct PdcFile {
  std::int32_t version = 1;              ///< format version (always 1)
  std::int32_t byteOrder = 1;            ///< Maya's byte-order field (1)
  std::int32_t extra1 = 0;               ///< reserved header field
  std::int32_t extra2 = 0;               ///< reserved header field
  std::int32_t count = 0;                ///< number of particles
  std::vector<PdcAttribute> attributes;  ///< in file order

  /// The attribute called `name`, or nullptr.
  [[nodiscard]] const PdcAttribute* find(std::string_view name) const;
};

/// Encodes one fluid as a PDC file with attributes position, velocity (vector arrays),
/// particleId, radiusPP (double arrays) and rgbPP (vector array), in that order.
[[nodiscard]] std::string encodePdc(const FluidSnapshot& fluid);

/// Same as encodePdc, into `out` (cleared first), reusing its capacity.
void encodePdcInto(std::string& out, const FluidSnapshot& fluid);

/// Parses and validates PDC bytes (all six Maya types); InputError on truncated or bad
/// input. Never allocates more than the input can hold, whatever the declared counts.
[[nodiscard]] PdcFile decodePdc(std::string_view bytes, const std::string& fileName);

/// Reads and decodes a PDC file (IoError if unreadable, InputError if invalid).
[[nodiscard]] PdcFile readPdcFile(const std::filesystem::path& path);

}  // namespace softsub::cache
