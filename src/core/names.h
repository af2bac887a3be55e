#pragma once
/// The longest fluid or object name: names become parts of file names, and a file name
/// may have at most 255 bytes (NAME_MAX on Linux, macOS and Windows' NTFS).
#include <cstddef>

namespace softsub {

/// At most this many bytes in a fluid or object name. The longest file name made from a
/// name is the temporary of an atomic write of a fluid's PDC file:
/// `.<name>Shape.<ticks>.pdc.tmp.<host>.<pid>.<counter>`, with ticks up to 13 digits
/// (1,000,000 frames at 0.001 fps), a host name up to 64 bytes (HOST_NAME_MAX), a pid up
/// to 10 digits and a counter up to 20: 1 + 6 + 13 + 4 + 5 + 64 + 1 + 10 + 1 + 20 = 125
/// bytes besides the name. An object's `<scene>Geo/<name>.obj` and a fluid's
/// `<name>.<frame>.obj`/`.vdb` add less. 100 leaves room.
inline constexpr std::size_t kMaxNameLength = 100;
static_assert(kMaxNameLength + 1 + 6 + 13 + 4 + 5 + 64 + 1 + 10 + 1 + 20 <= 255);

}  // namespace softsub
