#pragma once
/// Shared helpers of the cache tests: scratch folders, snapshots with awkward values.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/snapshot.h"

namespace softsub::cache::test {

/// A fresh empty folder under the system temporary folder, removed on destruction.
class ScratchDir {
 public:
  ScratchDir() {
    static std::atomic<int> counter{0};
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = "softsub-cache-";
    if (info != nullptr) name += std::string(info->test_suite_name()) + "-" + info->name() + "-";
    name += std::to_string(::getpid()) + "-" + std::to_string(counter++);
    std::replace(name.begin(), name.end(), '/', '_');
    path_ = std::filesystem::temp_directory_path() / name;
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    // Restore write permission first: some tests make folders read-only.
    std::filesystem::permissions(path_, std::filesystem::perms::owner_all,
                                 std::filesystem::perm_options::add, ec);
    std::filesystem::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

/// Every regular file under `dir`, as sorted paths relative to `dir`.
inline std::vector<std::string> listFiles(const std::filesystem::path& dir) {
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
    if (entry.is_regular_file()) files.push_back(entry.path().lexically_relative(dir).string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

/// A finite float from random bits: covers negative, zero, subnormal, tiny and huge values.
inline float randomFloat(std::mt19937& rng) {
  while (true) {
    const float f = std::bit_cast<float>(static_cast<std::uint32_t>(rng()));
    if (std::isfinite(f)) return f;
  }
}

/// A fluid of `n` particles with ids `firstId`, `firstId + 2`, ... and values from `rng`;
/// `wild` picks random float bit patterns, otherwise plain values in [-10, 10].
inline FluidSnapshot makeFluid(const std::string& name, std::size_t n, std::uint32_t firstId,
                               std::mt19937& rng, bool wild = false) {
  FluidSnapshot f;
  f.name = name;
  f.colour = {0.25F, 0.5F, 1.0F};
  f.particleSize = 0.3F;
  std::uniform_real_distribution<float> plain(-10.0F, 10.0F);
  for (std::size_t k = 0; k < n; ++k) {
    f.ids.push_back(firstId + 2 * static_cast<std::uint32_t>(k));
    for (int c = 0; c < 3; ++c) {
      f.positions.push_back(wild ? randomFloat(rng) : plain(rng));
      f.velocities.push_back(plain(rng));
    }
  }
  return f;
}

/// A frame with two fluids (3 and 5 particles) at frame 10, 24 fps.
inline FrameSnapshot makeFrame(std::uint32_t seed = 1) {
  std::mt19937 rng(seed);
  FrameSnapshot frame;
  frame.frame = 10;
  frame.framesPerSecond = 24;
  frame.time = 10.0 / 24.0;
  frame.fluids.push_back(makeFluid("honey", 3, 0, rng));
  frame.fluids.push_back(makeFluid("oil", 5, 100, rng));
  frame.fluids[1].colour = {1.0F, 0.0F, 0.123F};
  frame.fluids[1].particleSize = 0.5F;
  return frame;
}

}  // namespace softsub::cache::test
