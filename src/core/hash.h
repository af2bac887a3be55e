#pragma once
/// A fast 64-bit hash of bytes: checkpoints' checksums, runs' fingerprints, the
/// content-derived ids of written files. Not cryptographic.
#include <cstdint>
#include <string_view>

namespace softsub {

/// FNV-1a over 8-byte words (then the tail bytes), finished with a full avalanche mix;
/// `seed` chains hashes of several pieces.
[[nodiscard]] std::uint64_t hashBytes(std::string_view bytes, std::uint64_t seed = 0);

}  // namespace softsub
