// The particle store: every array moves together, ids stay a permutation.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

#include "core/particle_store.h"

namespace softsub {
namespace {

ParticleStore numbered(std::size_t n) {
  ParticleStore s;
  for (std::size_t i = 0; i < n; ++i) {
    const float f = static_cast<float>(i);
    s.add(f, 10 + f, 20 + f, 30 + f, 40 + f, 50 + f, static_cast<std::uint16_t>(i % 7),
          static_cast<std::uint32_t>(i % 3));
    s.f.back() = {60 + f, 70 + f, 80 + f, 0};
  }
  return s;
}

TEST(ParticleStore, AddAssignsIdsInOrder) {
  const ParticleStore s = numbered(5);
  ASSERT_EQ(s.size(), 5u);
  for (std::uint32_t i = 0; i < 5; ++i) EXPECT_EQ(s.id[i], i);
  EXPECT_EQ(s.material[4], 4);
  EXPECT_EQ(s.owner[4], 1u);
}

TEST(ParticleStore, PermuteMovesEveryArrayTogetherAndZeroesForces) {
  ParticleStore s = numbered(1000);
  std::vector<std::uint32_t> order(s.size()), scratch(s.size());
  std::iota(order.begin(), order.end(), 0u);
  std::shuffle(order.begin(), order.end(), std::mt19937(5));
  s.permute(order, scratch);
  for (std::size_t k = 0; k < s.size(); ++k) {
    const std::uint32_t was = order[k];
    const float f = static_cast<float>(was);
    ASSERT_EQ(s.id[k], was);
    ASSERT_EQ(s.px[k], f); ASSERT_EQ(s.py[k], 10 + f); ASSERT_EQ(s.pz[k], 20 + f);
    ASSERT_EQ(s.vx[k], 30 + f); ASSERT_EQ(s.vy[k], 40 + f); ASSERT_EQ(s.vz[k], 50 + f);
    // The force records were the scratch: not carried, zero.
    ASSERT_EQ(s.f[k], Force{});
    ASSERT_EQ(s.material[k], was % 7);
    ASSERT_EQ(s.owner[k], was % 3);
  }
  // Every array keeps its size.
  for (const auto* a : {&s.px, &s.py, &s.pz, &s.vx, &s.vy, &s.vz}) EXPECT_EQ(a->size(), s.size());
  EXPECT_EQ(s.f.size(), s.size());
  // A second permutation composes with the first, and a longer scratch is fine.
  std::vector<std::uint32_t> back(s.size()), longer(s.size() + 7);
  for (std::size_t k = 0; k < s.size(); ++k) back[order[k]] = static_cast<std::uint32_t>(k);
  s.permute(back, longer);
  for (std::uint32_t k = 0; k < s.size(); ++k) {
    ASSERT_EQ(s.id[k], k);
    ASSERT_EQ(s.vz[k], 50 + static_cast<float>(k));
    ASSERT_EQ(s.material[k], k % 7);
  }
}

// A re-sort in which few particles changed cell: runs of consecutive slots shifted, a
// few strays between them, across the parallel blocks, with a length that is no whole
// number of runs of eight (the gather copies whole runs at once).
TEST(ParticleStore, PermuteOfShiftedRunsAndStraysMovesEveryArrayTogether) {
  ParticleStore s = numbered(40003);
  std::vector<std::uint32_t> order(s.size()), scratch(s.size());
  std::iota(order.begin(), order.end(), 0u);
  std::mt19937 rng(11);
  // Each move takes one slot out and puts it back elsewhere: what lies between shifts by one.
  for (int m = 0; m < 300; ++m) {
    const std::size_t from = rng() % order.size(), to = rng() % order.size();
    const std::uint32_t v = order[from];
    order.erase(order.begin() + static_cast<std::ptrdiff_t>(from));
    order.insert(order.begin() + static_cast<std::ptrdiff_t>(to), v);
  }
  s.permute(order, scratch);
  for (std::size_t k = 0; k < s.size(); ++k) {
    const std::uint32_t was = order[k];
    const float f = static_cast<float>(was);
    ASSERT_EQ(s.id[k], was) << k;
    ASSERT_EQ(s.px[k], f);
    ASSERT_EQ(s.py[k], 10 + f);
    ASSERT_EQ(s.pz[k], 20 + f);
    ASSERT_EQ(s.vx[k], 30 + f);
    ASSERT_EQ(s.vy[k], 40 + f);
    ASSERT_EQ(s.vz[k], 50 + f);
    ASSERT_EQ(s.material[k], was % 7);
    ASSERT_EQ(s.owner[k], was % 3);
  }
}

TEST(ParticleStore, SlotsByIdInvertsThePermutation) {
  ParticleStore s = numbered(300);
  std::vector<std::uint32_t> order(s.size());
  std::iota(order.rbegin(), order.rend(), 0u);  // reversed
  std::vector<std::uint32_t> scratch(s.size());
  s.permute(order, scratch);
  std::vector<std::uint32_t> slot;
  s.slotsById(slot);
  ASSERT_EQ(slot.size(), s.size());
  for (std::uint32_t id = 0; id < s.size(); ++id) {
    EXPECT_EQ(s.id[slot[id]], id);
    EXPECT_EQ(s.px[slot[id]], static_cast<float>(id));
  }
}

}  // namespace
}  // namespace softsub
