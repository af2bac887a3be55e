// Decoders under random damage: every mutated file is either read or refused with an
// InputError; nothing else escapes (no crash, no bad_alloc, no other exception).
#include <gtest/gtest.h>

#include "cache/cache_test_support.h"
#include "cache/pdc_format.h"
#include "cache/ply_format.h"
#include "cache/sim_format.h"
#include "core/error.h"

namespace softsub::cache {
namespace {

/// One random change: overwrite, insert or delete a few bytes, or cut the tail.
std::string mutate(std::string bytes, std::mt19937& rng) {
  const auto pick = [&](std::size_t n) { return n == 0 ? 0 : static_cast<std::size_t>(rng() % n); };
  const int edits = 1 + static_cast<int>(rng() % 4);
  for (int e = 0; e < edits; ++e) {
    switch (rng() % 4) {
      case 0:
        if (!bytes.empty()) bytes[pick(bytes.size())] = static_cast<char>(rng());
        break;
      case 1: bytes.insert(pick(bytes.size() + 1), 1, static_cast<char>(rng())); break;
      case 2:
        if (!bytes.empty()) bytes.erase(pick(bytes.size()), 1 + pick(8));
        break;
      default: bytes.resize(pick(bytes.size() + 1)); break;
    }
  }
  return bytes;
}

template <class Decode>
void fuzz(const std::string& good, Decode decode, std::uint32_t seed) {
  std::mt19937 rng(seed);
  int accepted = 0;
  for (int i = 0; i < 3000; ++i) {
    const std::string bad = mutate(good, rng);
    try {
      decode(bad);
      ++accepted;
    } catch (const InputError& e) {
      // Expected; the message quotes the input only as a short, printable excerpt.
      const std::string what = e.what();
      ASSERT_LT(what.size(), 400U) << what;
      for (const char c : what) {
        ASSERT_FALSE(static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
            << "mutation " << i << ": " << what;
      }
    } catch (const std::exception& e) {
      FAIL() << "mutation " << i << " threw a non-InputError: " << e.what();
    }
  }
  ::testing::Test::RecordProperty("accepted", accepted);
}

TEST(DecoderFuzz, Sim) {
  fuzz(
      encodeSim(test::makeFrame()), [](const std::string& b) { return decodeSim(b, "f.sim"); }, 11);
}

TEST(DecoderFuzz, Pdc) {
  const FrameSnapshot frame = test::makeFrame();
  fuzz(
      encodePdc(frame.fluids[1]), [](const std::string& b) { return decodePdc(b, "f.pdc"); }, 12);
}

TEST(DecoderFuzz, PlyBinary) {
  fuzz(
      encodePly(test::makeFrame()), [](const std::string& b) { return decodePly(b, "f.ply"); }, 13);
}

TEST(DecoderFuzz, PlyAscii) {
  const std::string ascii =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nproperty list uchar int idx\nelement face 1\n"
      "property list uchar uint vertex_indices\nend_header\n"
      "1 2 3 1 7\n4 5 6 0\n7 8 9 2 1 2\n3 0 1 2\n";
  fuzz(
      ascii, [](const std::string& b) { return decodePly(b, "f.ply"); }, 14);
}

}  // namespace
}  // namespace softsub::cache
