// The grid must list exactly the brute-force pairs, each once, whatever the layout.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <set>
#include <span>
#include <stdexcept>

#include <tbb/global_control.h>

#include "neighbors/cell_grid.h"

namespace softsub::neighbors {
namespace {

using Pair = std::pair<std::uint32_t, std::uint32_t>;

ParticleStore cloud(std::size_t n, float lo, float hi, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(lo, hi);
  ParticleStore s;
  for (std::size_t i = 0; i < n; ++i) s.add(u(rng), u(rng), u(rng), 0, 0, 0, 0, 0);
  return s;
}

// Pairs within the cutoff found by the grid, as sorted (id, id) pairs.
std::vector<Pair> gridPairs(const CellGrid& g, const ParticleStore& s, float cutoff, std::size_t* visits) {
  std::vector<Pair> out;
  const float c2 = cutoff * cutoff;
  std::size_t count = 0;
  g.forEachCandidatePair([&](std::uint32_t i, std::uint32_t j) {
    ++count;
    const float dx = s.px[j] - s.px[i], dy = s.py[j] - s.py[i], dz = s.pz[j] - s.pz[i];
    if (dx * dx + dy * dy + dz * dz < c2) out.emplace_back(std::min(s.id[i], s.id[j]), std::max(s.id[i], s.id[j]));
  });
  if (visits) *visits = count;
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<Pair> brutePairs(const ParticleStore& s, float cutoff) {
  std::vector<Pair> out;
  for (auto [i, j] : bruteForcePairs(s, cutoff)) out.emplace_back(std::min(s.id[i], s.id[j]), std::max(s.id[i], s.id[j]));
  std::sort(out.begin(), out.end());
  return out;
}

TEST(CellGrid, MatchesBruteForceOnRandomClouds) {
  for (std::uint32_t seed = 1; seed <= 8; ++seed) {
    ParticleStore s = cloud(1500, -5, 5, seed);
    const float cutoff = 0.5f + 0.25f * static_cast<float>(seed % 4);
    CellGrid g;
    g.rebuild(s, cutoff);
    const auto expected = brutePairs(s, cutoff);
    const auto got = gridPairs(g, s, cutoff, nullptr);
    ASSERT_FALSE(expected.empty());
    EXPECT_EQ(got, expected) << "seed " << seed;  // also proves no pair is listed twice
  }
}

TEST(CellGrid, CellFieldsAreEachParticlesCellCountedFromTheLowest) {
  // Clouds stretched along each axis in turn, so that each becomes the layers' axis.
  for (int stretched = 0; stretched < 3; ++stretched) {
    ParticleStore s = cloud(800, -3, 3, 40 + static_cast<std::uint32_t>(stretched));
    std::vector<float>* axis[3] = {&s.px, &s.py, &s.pz};
    for (float& v : *axis[stretched]) v = 5.0f * v - 11.0f;
    const float h = 0.7f;
    const double inverse = static_cast<double>(1.0f / h);  // as the grid rounds it
    CellGrid g;
    g.rebuild(s, h);
    ASSERT_FALSE(g.wraps());
    const std::array<int, 3> axes = g.keyAxes();
    EXPECT_EQ(axes[2], stretched);
    std::array<double, 3> lowest{};
    for (int f = 0; f < 3; ++f) {
      const std::vector<float>& v = *axis[axes[f]];
      lowest[f] = std::floor(static_cast<double>(*std::min_element(v.begin(), v.end())) * inverse);
    }
    std::uint32_t previousMajor = 0;
    for (std::size_t c = 0; c < g.cellCount(); ++c) {
      const std::array<std::uint32_t, 3> k = g.cellFields(c);
      EXPECT_GE(k[2], previousMajor) << "cell " << c;
      previousMajor = k[2];
      for (std::uint32_t i = g.cell(c).begin; i < g.cell(c).end; ++i)
        for (int f = 0; f < 3; ++f)
          ASSERT_EQ(static_cast<double>(k[f]),
                    std::floor(static_cast<double>((*axis[axes[f]])[i]) * inverse) - lowest[f])
              << "cell " << c << " slot " << i << " field " << f;
    }
  }
}

TEST(CellGrid, FarOutliersNeitherLosePairsNorGrowMemory) {
  ParticleStore s = cloud(2000, 0, 6, 42);
  const std::size_t before = [&] {
    CellGrid g;
    g.rebuild(s, 0.7f);
    return g.memoryBytes();
  }();
  // Outliers far away in every direction, including a close pair far out, values that
  // alias under the 21-bit wrap (2^21 cells away) and huge coordinates.
  const float h = 0.7f;
  const float wrap = h * 2097152.0f;
  s.add(1e9f, 1e9f, 1e9f, 0, 0, 0, 0, 0);
  s.add(1e9f + 0.1f * 64, 1e9f, 1e9f, 0, 0, 0, 0, 0);
  s.add(-3e8f, 5, 5, 0, 0, 0, 0, 0);
  s.add(1.0f + wrap, 1.0f, 1.0f, 0, 0, 0, 0, 0);  // aliases a cell inside the cloud
  s.add(1.3f + wrap, 1.0f, 1.0f, 0, 0, 0, 0, 0);  // and is within the cutoff of the previous
  s.add(3.0e38f, -3.0e38f, 0, 0, 0, 0, 0, 0);
  CellGrid g;
  g.rebuild(s, h);
  EXPECT_EQ(gridPairs(g, s, h, nullptr), brutePairs(s, h));
  // Memory depends on the particle count, not on the extent.
  EXPECT_LT(g.memoryBytes(), 2 * before + 4096);
}

TEST(CellGrid, RebuildAfterMotionAndIdentityOrder) {
  ParticleStore s = cloud(800, -3, 3, 7);
  CellGrid g;
  g.rebuild(s, 0.6f);
  EXPECT_TRUE(g.reordered());
  g.rebuild(s, 0.6f);
  EXPECT_FALSE(g.reordered()) << "already sorted input must not be permuted again";
  std::mt19937 rng(3);
  std::normal_distribution<float> d(0, 0.05f);
  for (std::size_t i = 0; i < s.size(); ++i) { s.px[i] += d(rng); s.py[i] += d(rng); s.pz[i] += d(rng); }
  g.rebuild(s, 0.6f);  // nearly sorted: the insertion-sort path
  EXPECT_EQ(gridPairs(g, s, 0.6f, nullptr), brutePairs(s, 0.6f));
  // Ids survive the permutations as a permutation of 0..n-1.
  std::vector<std::uint32_t> ids = s.id;
  std::sort(ids.begin(), ids.end());
  for (std::uint32_t k = 0; k < ids.size(); ++k) ASSERT_EQ(ids[k], k);
}

TEST(CellGrid, CandidatePairsAreBoundedByCellVolume) {
  // A dense lattice: candidates must stay a small multiple of true pairs (27 cells of
  // side h versus a sphere of radius h: about 6.5x in the bulk, more at boundaries; half of them by Newton's law).
  ParticleStore s;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j)
      for (int k = 0; k < 20; ++k) s.add(0.5f * i, 0.5f * j, 0.5f * k, 0, 0, 0, 0, 0);
  CellGrid g;
  g.rebuild(s, 1.0f);
  std::size_t visits = 0;
  const auto pairs = gridPairs(g, s, 1.0f, &visits);
  EXPECT_EQ(pairs, brutePairs(s, 1.0f));
  EXPECT_LT(static_cast<double>(visits), 8.0 * static_cast<double>(pairs.size()));
}

TEST(CellGrid, NearlySortedButFarMovedInputFallsBackCorrectly) {
  // One descent only, but the last block belongs at the front: the insertion sort's
  // move budget runs out and the radix sort finishes the job.
  ParticleStore s;
  for (int i = 0; i < 4000; ++i) s.add(0.5f * static_cast<float>(i % 40), 0.5f * static_cast<float>(i / 40), 0, 0, 0, 0, 0, 0);
  CellGrid g;
  g.rebuild(s, 1.0f);  // sorted now
  for (std::size_t i = s.size() - 100; i < s.size(); ++i) s.py[i] = -50.0f - 0.01f * static_cast<float>(i);
  g.rebuild(s, 1.0f);
  EXPECT_EQ(gridPairs(g, s, 1.0f, nullptr), brutePairs(s, 1.0f));
}

TEST(CellGrid, EmptyAndSingle) {
  ParticleStore s;
  CellGrid g;
  g.rebuild(s, 1.0f);
  EXPECT_EQ(g.cellCount(), 0u);
  s.add(0, 0, 0, 0, 0, 0, 0, 0);
  g.rebuild(s, 1.0f);
  EXPECT_EQ(g.cellCount(), 1u);
  EXPECT_TRUE(gridPairs(g, s, 1.0f, nullptr).empty());
}

// The forward ranges do not depend on the order the cells are visited in: a walker that
// jumps around (random order, repeats, backwards) finds what an ascending walk finds,
// the cloud straddling the 21-bit wrap included.
TEST(CellGrid, ForwardRangesAreTheSameInAnyVisitOrder) {
  ParticleStore s = cloud(3000, -6, 6, 21);
  CellGrid g;
  g.rebuild(s, 1.1f);
  std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> ascending(g.cellCount());
  CellGrid::ForwardRanges walk(g);
  for (std::size_t c = 0; c < g.cellCount(); ++c)
    for (const SlotRange& r : walk.of(c)) ascending[c].emplace_back(r.begin, r.end);
  std::mt19937 rng(4);
  std::uniform_int_distribution<std::size_t> pick(0, g.cellCount() - 1);
  CellGrid::ForwardRanges jumping(g);
  std::size_t nonEmpty = 0;
  for (int k = 0; k < 5000; ++k) {
    const std::size_t c = k % 7 == 0 ? g.cellCount() - 1 - static_cast<std::size_t>(k) % g.cellCount() : pick(rng);
    std::vector<std::pair<std::uint32_t, std::uint32_t>> got;
    for (const SlotRange& r : jumping.of(c)) got.emplace_back(r.begin, r.end);
    ASSERT_EQ(got, ascending[c]) << "cell " << c;
    nonEmpty += got.empty() ? 0 : 1;
  }
  EXPECT_GT(nonEmpty, 4000u);
}

// After a jump each cursor seeks before it walks: a fresh walker that starts in the middle
// of the cells (as each task of the parallel list build does) steps over a few cells per
// cell visited, not over every cell before it.
TEST(CellGrid, ForwardRangesSeekAfterAJump) {
  ParticleStore s = cloud(20000, 0, 40, 5);
  CellGrid g;
  g.rebuild(s, 1.0f);
  ASSERT_GT(g.cellCount(), 10000u);
  for (const std::size_t start : {g.cellCount() / 2, g.cellCount() - 200}) {
    CellGrid::ForwardRanges walk(g);
    for (std::size_t c = start; c < start + 100; ++c) walk.of(c);
    EXPECT_LT(walk.steps(), 13u * 100u * 4u) << "from cell " << start;
  }
  // The same walker, jumping back and then forward again.
  CellGrid::ForwardRanges walk(g);
  for (const std::size_t start : {std::size_t{0}, g.cellCount() / 2, std::size_t{100}, g.cellCount() - 200}) {
    const std::size_t before = walk.steps();
    for (std::size_t c = start; c < start + 100; ++c) walk.of(c);
    EXPECT_LT(walk.steps() - before, 13u * 100u * 4u) << "after jumping to cell " << start;
  }
}

// Rebuilding after particles moved puts the store in the order by (cell key, previous
// slot): cells ascending in (z, y, x), and the particles of one cell in the order they
// had. Checked for a few moved particles (the nearly-sorted path), many (the radix sort)
// and every amount in between, on coordinates that do not wrap.
TEST(CellGrid, ReSortIsStableByCellWhateverHowManyParticlesMoved) {
  const float h = 1.0f;
  for (const double movedShare : {0.0005, 0.01, 0.05, 0.12, 0.3, 1.0}) {
    ParticleStore s = cloud(20000, 0.0f, 30.0f, 8);
    CellGrid g;
    g.rebuild(s, h);
    std::mt19937 rng(static_cast<std::uint32_t>(movedShare * 1e6));
    std::uniform_real_distribution<float> u(0.0f, 1.0f), step(-1.5f, 1.5f);
    for (std::size_t i = 0; i < s.size(); ++i) {
      s.id[i] = static_cast<std::uint32_t>(i);  // the slot before the rebuild
      if (u(rng) < movedShare) {
        s.px[i] = std::clamp(s.px[i] + step(rng), 0.0f, 29.99f);
        s.pz[i] = std::clamp(s.pz[i] + 8 * step(rng), 0.0f, 29.99f);  // across layers too
      }
    }
    g.rebuild(s, h);
    auto coords = [&](std::size_t i) {
      return std::array<int, 3>{static_cast<int>(std::floor(s.pz[i] / h)), static_cast<int>(std::floor(s.py[i] / h)),
                                static_cast<int>(std::floor(s.px[i] / h))};
    };
    std::size_t covered = 0;
    for (std::size_t c = 0; c < g.cellCount(); ++c) {
      const SlotRange r = g.cell(c);
      ASSERT_EQ(r.begin, covered);
      covered = r.end;
      for (std::uint32_t i = r.begin; i < r.end; ++i) {
        ASSERT_EQ(coords(i), coords(r.begin)) << "one cell, one coordinate";
        if (i > r.begin) {
          ASSERT_LT(s.id[i - 1], s.id[i]) << "stable within a cell (moved " << movedShare << ")";
        }
      }
      if (c > 0) {
        ASSERT_LT(coords(g.cell(c - 1).begin), coords(r.begin)) << "cells ascending by (z, y, x)";
      }
    }
    EXPECT_EQ(covered, s.size());
  }
}

// Slots of each cell in the order they had before the rebuild (ids set to the old slot).
void expectStableByCell(const CellGrid& g, const ParticleStore& s) {
  std::size_t covered = 0;
  for (std::size_t c = 0; c < g.cellCount(); ++c) {
    const SlotRange r = g.cell(c);
    ASSERT_EQ(r.begin, covered);
    covered = r.end;
    for (std::uint32_t i = r.begin + 1; i < r.end; ++i) ASSERT_LT(s.id[i - 1], s.id[i]) << "cell " << c;
  }
  EXPECT_EQ(covered, s.size());
}

// A rebuild where a few particles changed cell takes them out, sorts them and merges
// them back (CellGrid::sortMovers); its keys are counted from the lowest cell, so the
// case where that corner moved (an outlier leaving or rejoining the cloud) shifts every
// other key: still the stable order, as a grid that never saw the old order gives.
TEST(CellGrid, ReSortOfAFewMoversIsStableWhenTheLowestCornerMoves) {
  const float h = 1.0f;
  for (const float outlier : {0.5f, -3.5f, 40.0f}) {
    ParticleStore s = cloud(20000, 0.0f, 30.0f, 8);
    s.px[0] = -6.5f;  // the lowest x of the first rebuild
    CellGrid g;
    g.rebuild(s, h);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f), step(-1.5f, 1.5f);
    for (std::size_t i = 0; i < s.size(); ++i) {
      s.id[i] = static_cast<std::uint32_t>(i);
      if (u(rng) < 0.01f) {
        s.px[i] = std::clamp(s.px[i] + step(rng), 0.0f, 29.99f);
        s.pz[i] = std::clamp(s.pz[i] + 8 * step(rng), 0.0f, 29.99f);
      }
      if (s.px[i] == -6.5f) s.px[i] = outlier;  // the corner moves by -7, +3 or -46 cells
    }
    ParticleStore fresh = s;
    g.rebuild(s, h);
    expectStableByCell(g, s);
    CellGrid other;
    other.rebuild(fresh, h);
    ASSERT_EQ(other.cellCount(), g.cellCount());
    EXPECT_EQ(fresh.id, s.id) << "outlier at " << outlier;
    EXPECT_EQ(fresh.px, s.px);
  }
}

// The in-place radix sort from a shuffled store: cells crowded far beyond its insertion
// threshold (ties broken by slot), just above that threshold, a cloud whose x
// coordinates span two key bytes, and keys that wrap (a torus: outliers 1e9 away).
TEST(CellGrid, ShuffledInputSortsStablyInCrowdedCellsWideCloudsAndTori) {
  struct Case {
    float lo, hi, h;
    std::size_t n;
    bool wide, torus;
  };
  for (const Case& c : {Case{0, 2, 1, 6000, false, false}, Case{0, 1.9f, 1, 49, false, false},
                        Case{0, 1.9f, 1, 50, false, false}, Case{0, 3000, 1, 20000, true, false},
                        Case{-7, 7, 0.5f, 30000, false, false}, Case{-3, 3, 0.5f, 5000, false, true}}) {
    ParticleStore s = cloud(c.n, c.lo, c.hi, 11);
    if (c.wide)  // wide in x only: thousands of cells, up to 12 bits of x
      for (std::size_t i = 0; i < s.size(); ++i) s.py[i] = s.pz[i] = 0.5f;
    if (c.torus)
      for (std::size_t i = 0; i < s.size(); i += 97) s.px[i] += (i % 2 ? 1e9f : -1e9f);
    for (std::size_t i = 0; i < s.size(); ++i) s.id[i] = static_cast<std::uint32_t>(i);
    CellGrid g;
    g.rebuild(s, c.h);
    ASSERT_TRUE(g.reordered());
    expectStableByCell(g, s);
    if (!c.torus) {  // (wrapped keys are ordered by wrapped coordinates)
      const std::array<int, 3> axes = g.keyAxes();
      const std::vector<float>* p[3] = {&s.px, &s.py, &s.pz};
      for (std::size_t k = 1; k < g.cellCount(); ++k) {
        const std::uint32_t a = g.cell(k - 1).begin, b = g.cell(k).begin;
        const auto key = [&](std::uint32_t i) {
          return std::array<float, 3>{std::floor((*p[axes[2]])[i] / c.h), std::floor((*p[axes[1]])[i] / c.h),
                                      std::floor((*p[axes[0]])[i] / c.h)};
        };
        ASSERT_LT(key(a), key(b)) << "cells ascending by (major, middle, minor) axis";
      }
    }
    EXPECT_EQ(gridPairs(g, s, c.h, nullptr), brutePairs(s, c.h)) << c.n << " particles";
  }
}

// The nearly sorted path sorts fixed blocks in parallel and then joins them; the radix
// sort splits its first level across threads. Either way the order is the stable one and
// the same on 1 and 3 threads: a store of several blocks where every particle moved a
// little, some moved across many blocks (both ways), and then one where so many moved
// that the insertion sort gives up.
TEST(CellGrid, ParallelSortGivesTheStableOrderOnAnyThreadCount) {
  for (const double farShare : {0.0003, 0.2}) {
    ParticleStore base = cloud(70000, 0.0f, 40.0f, 31);
    CellGrid(2).rebuild(base, 1.0f);
    std::mt19937 rng(static_cast<std::uint32_t>(farShare * 1000));
    std::uniform_real_distribution<float> u(0.0f, 1.0f), jitter(-0.01f, 0.01f), far(3.0f, 12.0f);
    for (std::size_t i = 0; i < base.size(); ++i) {
      base.id[i] = static_cast<std::uint32_t>(i);
      base.px[i] = std::clamp(base.px[i] + jitter(rng), 0.0f, 39.99f);
      if (u(rng) < farShare)  // z is the layers' axis: 3-12 layers reach across a block of slots
        base.pz[i] = std::clamp(base.pz[i] + (u(rng) < 0.5f ? -far(rng) : far(rng)), 0.0f, 39.99f);
    }
    std::vector<std::vector<std::uint32_t>> orders;
    for (const int threads : {1, 3}) {
      const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
      ParticleStore s = base;
      CellGrid g(2);
      g.rebuild(s, 1.0f);
      ASSERT_TRUE(g.reordered());
      expectStableByCell(g, s);
      for (std::size_t c = 1; c < g.cellCount(); ++c) {
        const std::uint32_t a = g.cell(c - 1).begin, b = g.cell(c).begin;
        const auto key = [&](std::uint32_t i) {
          return std::array<float, 3>{std::floor(s.pz[i]), std::floor(s.py[i]), std::floor(s.px[i])};
        };
        ASSERT_LT(key(a), key(b)) << "cells ascending by (z, y, x)";
      }
      orders.push_back(s.id);
    }
    EXPECT_EQ(orders[0], orders[1]) << "far share " << farShare;
  }
}

// A caller's work memory gives the same grid and the same store as the grid's own, and
// the grid then keeps no per-particle memory; reordered forces come back zero.
TEST(CellGrid, WorkMemoryFromTheCallerGivesTheSameResult) {
  ParticleStore a = cloud(5000, -4, 4, 21);
  for (std::size_t i = 0; i < a.size(); ++i) a.f[i] = {1.0f, 1.0f, 1.0f, 0.0f};
  ParticleStore b = a;
  CellGrid own, lent;
  own.rebuild(a, 0.8f);
  std::vector<std::uint64_t> work(CellGrid::workBytes(b.size()) / 8 + 1);
  lent.rebuild(b, 0.8f, std::as_writable_bytes(std::span<std::uint64_t>(work)));
  ASSERT_TRUE(lent.reordered());
  EXPECT_EQ(a.px, b.px);
  EXPECT_EQ(a.vz, b.vz);
  EXPECT_EQ(a.id, b.id);
  ASSERT_EQ(own.cellCount(), lent.cellCount());
  for (std::size_t c = 0; c < own.cellCount(); ++c) ASSERT_EQ(own.cell(c).end, lent.cell(c).end);
  for (std::size_t i = 0; i < b.size(); ++i) ASSERT_EQ(b.f[i], Force{});
  EXPECT_GE(own.memoryBytes(), lent.memoryBytes() + CellGrid::workBytes(a.size()));
  // Sorted input is left alone, forces included.
  b.f[3].x = 2.0f;
  lent.rebuild(b, 0.8f, std::as_writable_bytes(std::span<std::uint64_t>(work)));
  EXPECT_FALSE(lent.reordered());
  EXPECT_EQ(b.f[3].x, 2.0f);
  // Too small, or misaligned: refused before anything changes.
  const auto bytes = std::as_writable_bytes(std::span<std::uint64_t>(work));
  EXPECT_THROW(lent.rebuild(b, 0.8f, bytes.first(CellGrid::workBytes(b.size()) - 1)), std::invalid_argument);
  EXPECT_THROW(lent.rebuild(b, 0.8f, bytes.subspan(4)), std::invalid_argument);
}

// The layers (the unit of parallel work) run along z unless the particles spread clearly
// more along y or x: a dam flat in z gets one layer per x cell, not one or two; a pool
// with one particle flung high keeps its layers along z; a fixed axis is kept.
TEST(CellGrid, LayersRunAlongTheAxisOfLargestSpreadWithAMarginForZ) {
  struct Case {
    float x, y, z;  // the box's side on each axis (from 0)
    int major;      // expected layers' axis
    bool outlier = false;
    int fixed = -1;
  };
  for (const Case& c : {Case{110, 55, 2, 0}, Case{6, 40, 6, 1}, Case{14, 10, 10, 2}, Case{20, 30, 10, 1},
                        Case{12, 12, 12, 2}, Case{60, 3, 60, 2, true}, Case{12, 12, 12, 0, false, 0}}) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    ParticleStore s;
    const std::size_t n = 6000;
    for (std::size_t i = 0; i < n; ++i) s.add(c.x * u(rng), c.y * u(rng), c.z * u(rng), 0, 0, 0, 0, 0);
    CellGrid g(c.fixed);
    const float h = 1.0f;
    if (c.outlier) {  // the bounding box is now 100 cells high, the pool 60 wide
      s.add(30.5f, 100.5f, 30.5f, 0, 0, 0, 0, 0);
      g.rebuild(s, h);
      EXPECT_EQ(g.keyAxes()[2], 2);
      EXPECT_EQ(g.layers().size(), 60u);
      EXPECT_EQ(gridPairs(g, s, h, nullptr), brutePairs(s, h));
      continue;
    }
    g.rebuild(s, h);
    const std::array<int, 3> axes = g.keyAxes();
    EXPECT_EQ(axes[2], c.major) << c.x << " x " << c.y << " x " << c.z;
    std::array<int, 3> sorted = axes;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(sorted, (std::array<int, 3>{0, 1, 2}));
    const float side[3] = {c.x, c.y, c.z};
    EXPECT_EQ(g.layers().size(), static_cast<std::size_t>(std::ceil(side[c.major] / h)));
    // Each layer holds one coordinate of the major axis, in ascending order.
    const std::vector<float>* p[3] = {&s.px, &s.py, &s.pz};
    float previous = -1;
    for (const SlotRange& layer : g.layers()) {
      const float first = std::floor((*p[c.major])[layer.begin] / h);
      EXPECT_GT(first, previous);
      previous = first;
      for (std::uint32_t i = layer.begin; i < layer.end; ++i) ASSERT_EQ(std::floor((*p[c.major])[i] / h), first);
    }
    EXPECT_EQ(gridPairs(g, s, h, nullptr), brutePairs(s, h));
  }
}

}  // namespace
}  // namespace softsub::neighbors
