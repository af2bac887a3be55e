// The pair kernel against a double-precision brute-force sum from the formulas.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include <tbb/global_control.h>

#include "fluid/fluid_params.h"
#include "fluid/pair_forces.h"
#include "support/clouds.h"

namespace softsub::fluid {
namespace {

forces::InteractionTable threeMaterials() {
  forces::InteractionTable t(3);
  FluidParams honey;
  honey.viscosity = 2;
  FluidParams water;
  water.amplitude = 5;
  water.interactionDistance = 1.2;
  water.viscosity = 0.1;
  t.set(0, 0, {ownFunction(honey), honey.viscosity, 0});
  t.set(1, 1, {ownFunction(water), water.viscosity, 0});
  t.set(2, 2, {forces::LennardJonesForce{1, 0.8, 2.0}, 0, 0});
  t.set(0, 1, {forces::Linear{5, 1, 0, 5}, 0.3, 1.5});
  t.set(0, 2, {forces::Curve{{0.1, 6, 0.7, 1, 1.3, -0.5}}, 0, 0.7});
  t.set(1, 2, {forces::Linear{8, 1.5, 0, 8}, 0, 0});
  return t;
}

// Every function kind across three materials with velocity terms, the true LJ force
// alone (no velocity terms), and the seed's goo alone (one material with viscosity).
std::vector<forces::InteractionTable> threeTables() {
  forces::InteractionTable lj(1);
  lj.set(0, 0, {forces::LennardJonesForce{1, 0.8, 2.0}, 0, 0});
  forces::InteractionTable goo(1);
  goo.set(0, 0, {ownFunction(FluidParams{}), 1.5, 0});
  std::vector<forces::InteractionTable> out;
  out.push_back(threeMaterials());
  out.push_back(std::move(lj));
  out.push_back(std::move(goo));
  return out;
}

// Puts back the copy of the hot loops in use when the test started.
struct RestoreSimd {
  Simd was = simdInUse();
  RestoreSimd() = default;
  RestoreSimd(const RestoreSimd&) = delete;
  RestoreSimd& operator=(const RestoreSimd&) = delete;
  ~RestoreSimd() { useSimd(was); }
};

void zeroForces(ParticleStore& s) {
  std::fill(s.f.begin(), s.f.end(), Force{});
}

// The forces in `s` against referencePairForces: the largest error per particle within
// `tolerance` (default 2e-3, the tables' sampling) of the largest force (the cloud must
// interact).
void expectMatchesReference(const forces::InteractionTable& table, const ParticleStore& s, double tolerance = 2e-3) {
  std::vector<double> rx, ry, rz;
  referencePairForces(table, s, rx, ry, rz);
  double worst = 0, scale = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    worst = std::max(worst, std::abs(s.f[i].x - rx[i]) + std::abs(s.f[i].y - ry[i]) + std::abs(s.f[i].z - rz[i]));
    scale = std::max(scale, std::abs(rx[i]) + std::abs(ry[i]) + std::abs(rz[i]));
  }
  ASSERT_GT(scale, 1.0) << "the cloud must be dense enough to interact";
  EXPECT_LT(worst, tolerance * scale);
}

// Two lists of the same pairs in two encodings: the same partners for every slot, and
// bitwise the same forces. Returns the store with the first list's forces.
ParticleStore expectSameListsAndForces(const PairList& one, const PairList& other, const forces::InteractionTable& table,
                                       const ParticleStore& s) {
  for (std::size_t i = 0; i < s.size(); ++i) EXPECT_EQ(one.partners(i), other.partners(i)) << i;
  ParticleStore a = s, b = s;
  zeroForces(a);
  zeroForces(b);
  accumulatePairForces(one, table, a);
  accumulatePairForces(other, table, b);
  EXPECT_EQ(a.f, b.f);
  return a;
}

TEST(PairForces, MatchesBruteForceReference) {
  const auto table = threeMaterials();
  ParticleStore s = scenarios::randomCloud(1200, -4, 4, 2.0f, 3, 11);
  neighbors::CellGrid grid;
  grid.rebuild(s, static_cast<float>(table.maxCutoff()));
  zeroForces(s);
  accumulatePairForces(grid, table, s);
  expectMatchesReference(table, s);
}

TEST(PairForces, NewtonsThirdLawSumsToZero) {
  const auto table = threeMaterials();
  ParticleStore s = scenarios::randomCloud(3000, -5, 5, 3.0f, 3, 5);
  neighbors::CellGrid grid;
  grid.rebuild(s, static_cast<float>(table.maxCutoff()));
  accumulatePairForces(grid, table, s);
  double sx = 0, sy = 0, sz = 0, mag = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    sx += s.f[i].x; sy += s.f[i].y; sz += s.f[i].z;
    mag += std::abs(s.f[i].x) + std::abs(s.f[i].y) + std::abs(s.f[i].z);
  }
  EXPECT_LT(std::abs(sx) + std::abs(sy) + std::abs(sz), 1e-5 * mag);
}

TEST(PairForces, TwoParticlesFeelTheFunctionAlongTheirLine) {
  forces::InteractionTable t(1);
  t.set(0, 0, {forces::Linear{4, 2, 0, 4}, 0, 0});
  ParticleStore s;
  s.add(0, 0, 0, 0, 0, 0, 0, 0);
  s.add(0.6f, 0.8f, 0, 0, 0, 0, 0, 0);  // r = 1: F = 2, repulsive
  neighbors::CellGrid g;
  g.rebuild(s, 2.0f);
  accumulatePairForces(g, t, s);
  std::vector<std::uint32_t> slot;
  s.slotsById(slot);
  EXPECT_NEAR(s.f[slot[0]].x, -1.2, 1e-5);
  EXPECT_NEAR(s.f[slot[0]].y, -1.6, 1e-5);
  EXPECT_NEAR(s.f[slot[1]].x, 1.2, 1e-5);
  EXPECT_NEAR(s.f[slot[1]].y, 1.6, 1e-5);
}

TEST(PairForces, ViscosityAndRelativeVelocityTerms) {
  forces::InteractionTable t(1);
  t.set(0, 0, {forces::Linear{0, 2, 0, 0}, 0.5, 2.0});  // no distance force
  ParticleStore s;
  s.add(0, 0, 0, 0, 0, 0, 0, 0);
  s.add(1, 0, 0, -1, 3, 0, 0, 0);  // approaching along x, sliding along y
  neighbors::CellGrid g;
  g.rebuild(s, 2.0f);
  accumulatePairForces(g, t, s);
  std::vector<std::uint32_t> slot;
  s.slotsById(slot);
  // dv = (-1, 3, 0), n = (1, 0, 0): f0 = 0.5 dv + 2 (dv.n) n = (-0.5 - 2, 1.5, 0)
  EXPECT_NEAR(s.f[slot[0]].x, -2.5, 1e-6);
  EXPECT_NEAR(s.f[slot[0]].y, 1.5, 1e-6);
  EXPECT_NEAR(s.f[slot[1]].x, 2.5, 1e-6);
  EXPECT_NEAR(s.f[slot[1]].y, -1.5, 1e-6);
}

TEST(PairForces, CoincidentParticlesStayFinite) {
  forces::InteractionTable t(1);
  FluidParams p;
  t.set(0, 0, {ownFunction(p), p.viscosity, 0});
  ParticleStore s;
  s.add(1, 1, 1, 0, 0, 0, 0, 0);
  s.add(1, 1, 1, 1, 0, 0, 0, 0);
  neighbors::CellGrid g;
  g.rebuild(s, 1.5f);
  accumulatePairForces(g, t, s);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_TRUE(std::isfinite(s.f[i].x) && std::isfinite(s.f[i].y) && std::isfinite(s.f[i].z));
  }
  EXPECT_FLOAT_EQ(s.f[0].x + s.f[1].x, 0.0f);
}

// Rigid bodies: a list that excludes owners from 1 on drops exactly the pairs of two
// particles of one such owner, and a row radius list reaches as far as it says.
TEST(PairList, ExcludesPairsOfOneRigidOwnerAndHonoursRowRadii) {
  const auto table = threeMaterials();
  ParticleStore s = scenarios::randomCloud(1500, -4, 4, 0.0f, 3, 7);
  for (std::size_t i = 0; i < s.size(); ++i) s.owner[i] = static_cast<std::uint32_t>(i % 5);  // owners 0..4
  const std::vector<float> radius{2.2f, 2.2f, 2.2f};  // beyond every cutoff (longest 2.0)
  neighbors::CellGrid grid;
  grid.rebuild(s, 2.2f);
  PairList plain, excluding;
  plain.build(grid, table, s, 0.0f, {.rowRadius = radius});
  excluding.build(grid, table, s, 0.0f, {.rowRadius = radius, .exclusiveOwnersFrom = 1});
  std::size_t dropped = 0, samePlain = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    for (const std::uint32_t j : excluding.partners(i))
      EXPECT_FALSE(s.owner[i] >= 1 && s.owner[i] == s.owner[j]) << i << " " << j;
    for (const std::uint32_t j : plain.partners(i)) {
      const float dx = s.px[j] - s.px[i], dy = s.py[j] - s.py[i], dz = s.pz[j] - s.pz[i];
      EXPECT_LT(dx * dx + dy * dy + dz * dz, 2.2f * 2.2f);
      if (s.owner[i] >= 1 && s.owner[i] == s.owner[j]) ++samePlain;
    }
    dropped += plain.partners(i).size() - excluding.partners(i).size();
  }
  EXPECT_GT(samePlain, 100U);
  EXPECT_EQ(dropped, samePlain);
  // Every pair within 2.2 is listed once: count by brute force.
  std::size_t brute = 0;
  for (std::size_t i = 0; i < s.size(); ++i)
    for (std::size_t j = i + 1; j < s.size(); ++j) {
      const float dx = s.px[j] - s.px[i], dy = s.py[j] - s.py[i], dz = s.pz[j] - s.pz[i];
      brute += dx * dx + dy * dy + dz * dz < 2.2f * 2.2f ? 1 : 0;
    }
  EXPECT_EQ(plain.pairCount(), brute);
}


// The kernel's other instance (no velocity term anywhere: velocities never loaded) and
// listed pairs that are out of range now (a skin): each must add exactly nothing.
TEST(PairForces, ConservativeModelWithASkinMatchesTheReference) {
  forces::InteractionTable table(2);
  table.set(0, 0, {forces::LennardJonesForce{1, 0.8, 2.0}, 0, 0});
  table.set(1, 1, {forces::Curve{{0.1, 6, 0.7, 1, 1.3, -0.5}}, 0, 0});
  table.set(0, 1, {forces::Linear{5, 1, 0, 5}, 0, 0});
  ParticleStore s = scenarios::randomCloud(1500, -4, 4, 2.0f, 2, 5);
  const float skin = 0.6f;
  neighbors::CellGrid grid;
  grid.rebuild(s, static_cast<float>(table.maxCutoff()) + skin);
  PairList list;
  list.build(grid, table, s, skin);
  zeroForces(s);
  accumulatePairForces(list, table, s);
  expectMatchesReference(table, s);
  // The skin listed pairs beyond every cutoff (the ones the kernel must zero).
  std::size_t beyond = 0;
  for (std::size_t i = 0; i < s.size(); ++i)
    for (const std::uint32_t j : list.partners(i)) {
      const float dx = s.px[j] - s.px[i], dy = s.py[j] - s.py[i], dz = s.pz[j] - s.pz[i];
      beyond += !(dx * dx + dy * dy + dz * dz < table.entry(s.material[i], s.material[j]).cutoff2);
    }
  EXPECT_GT(beyond, 100u);
}

// A layer keeps 16-bit partner offsets when its candidates lie within 65,536 slots,
// 32-bit slots otherwise (narrowSpan 0 forces those): the two encodings list the same
// partners in the same order and give bitwise the same forces, for the kernel's
// instances with and without velocity terms, one material and several.
TEST(PairList, SixteenAndThirtyTwoBitEntriesGiveTheSameForces) {
  forces::InteractionTable lj(1);
  lj.set(0, 0, {forces::LennardJonesForce{1, 0.8, 2.0}, 0, 0});
  for (const forces::InteractionTable& table : {threeMaterials(), lj}) {
    ParticleStore s = scenarios::randomCloud(2000, -5, 5, 2.0f, static_cast<std::uint16_t>(table.materials()), 3);
    const float skin = 0.3f;
    neighbors::CellGrid grid;
    grid.rebuild(s, static_cast<float>(table.maxCutoff()) + skin);
    PairList narrow, wide;
    ListOptions narrowOptions;
    narrowOptions.closedForm = false;  // the table kernel's encodings (grouped lists: below)
    narrow.build(grid, table, s, skin, narrowOptions);
    ListOptions wideOptions = narrowOptions;
    wideOptions.narrowSpan = 0;
    wide.build(grid, table, s, skin, wideOptions);
    std::size_t narrowLayers = 0;
    for (const PairList::Layer& l : narrow.layers()) narrowLayers += l.narrow ? 1 : 0;
    for (const PairList::Layer& l : wide.layers()) EXPECT_FALSE(l.narrow);
    // Small layers, and no wrap (the grid counts cells from the lowest one): all 16-bit.
    EXPECT_EQ(narrowLayers, narrow.layers().size());
    ASSERT_GT(narrow.pairCount(), 10000u);
    EXPECT_EQ(narrow.pairCount(), wide.pairCount());
    EXPECT_LT(narrow.memoryBytes(), wide.memoryBytes());
    expectMatchesReference(table, expectSameListsAndForces(narrow, wide, table, s));
  }
}

// The kernel's sums, bit for bit, against a plain scalar loop with the same operations
// per pair in the order the kernel promises: phase by phase, layer by layer, slot by slot,
// partner by partner, each slot's sum added after its last partner. Catches any change of
// summation order (chunking, threads) that the reference tolerance would not.
void plainLoopForces(const PairList& list, const forces::InteractionTable& table, ParticleStore& s) {
  const bool velocity = table.hasVelocityTerms(), relative = table.hasRelativeVelocity();
  const float* samples = table.samples().data();
  for (const std::vector<std::uint32_t>& phase : list.phases())
    for (const std::uint32_t l : phase) {
      const PairList::Layer& layer = list.layers()[l];
      for (std::uint32_t i = layer.slots.begin; i < layer.slots.end; ++i) {
        float ax = 0, ay = 0, az = 0;
        const std::uint32_t k0 = i - layer.slots.begin;
        for (std::uint32_t q = layer.start[k0]; q < layer.start[k0 + 1]; ++q) {
          const std::uint32_t j = layer.partner(q);
          const forces::PairEntry& e = table.entry(s.material[i], s.material[j]);
          const float dx = s.px[j] - s.px[i], dy = s.py[j] - s.py[i], dz = s.pz[j] - s.pz[i];
          const float r2 = dx * dx + dy * dy + dz * dz;
          const float in = r2 < e.cutoff2 ? 1.0f : 0.0f;
          const float r = std::sqrt(r2);
          const bool apart = r > 0;
          const float inv = (apart ? in : 0.0f) / (apart ? r : 1.0f);
          const float pieces = static_cast<float>(e.lastPiece);
          const float tMax = pieces + 1.0f, tr = r * e.invDr;
          const float t = tr < tMax ? tr : tMax;
          const std::int32_t k = std::min(static_cast<std::int32_t>(t), static_cast<std::int32_t>(pieces));
          const float* p = samples + e.offset + 2 * k;
          const float value = p[0] + p[1] * (t - static_cast<float>(k));
          const float nx = dx * inv, ny = dy * inv, nz = dz * inv;
          float gx = -value * nx, gy = -value * ny, gz = -value * nz;
          if (velocity) {
            const float dvx = s.vx[j] - s.vx[i], dvy = s.vy[j] - s.vy[i], dvz = s.vz[j] - s.vz[i];
            const float damp = e.damping * in;
            if (relative) {  // a table without the term skips it
              const float vn = e.relativeVelocity * (dvx * nx + dvy * ny + dvz * nz);
              gx += vn * nx + damp * dvx;
              gy += vn * ny + damp * dvy;
              gz += vn * nz + damp * dvz;
            } else {
              gx += damp * dvx;
              gy += damp * dvy;
              gz += damp * dvz;
            }
          }
          ax += gx; ay += gy; az += gz;
          s.f[j].x -= gx; s.f[j].y -= gy; s.f[j].z -= gz;
        }
        s.f[i].x += ax; s.f[i].y += ay; s.f[i].z += az;
      }
    }
}

TEST(PairForces, KernelSumsEqualAPlainLoopBitForBit) {
  int checked = 0;
  for (const forces::InteractionTable& table : threeTables())
    for (const float hi : {3.0f, 6.0f}) {  // dense (long rows, chunks of 64 full) and sparse
      ParticleStore s = scenarios::randomCloud(2500, -hi, hi, 2.0f, static_cast<std::uint16_t>(table.materials()), 9);
      const float skin = 0.25f;
      neighbors::CellGrid grid;
      grid.rebuild(s, static_cast<float>(table.maxCutoff()) + skin);
      PairList list;
      ListOptions options;
      options.closedForm = false;  // the table kernel (the closed-form one: below)
      list.build(grid, table, s, skin, options);
      ASSERT_FALSE(list.grouped());
      ParticleStore a = s, b = s;
      zeroForces(a);
      zeroForces(b);
      accumulatePairForces(list, table, a);
      plainLoopForces(list, table, b);
#if defined(__FMA__)
      // With FMA the compiler may fuse differently in the two loops: rounding only.
      for (std::size_t i = 0; i < s.size(); ++i) ASSERT_NEAR(a.f[i].x, b.f[i].x, 1e-3f * (1 + std::abs(b.f[i].x)));
#else
      EXPECT_EQ(a.f, b.f);
#endif
      ++checked;
    }
  EXPECT_EQ(checked, 6);
}

// The two compiled copies of the list build and the kernel (Simd) list the same partners
// and give bitwise the same forces: for every table kind, dense and sparse clouds, both
// list encodings, on every thread count the test runs with. The default copy (AVX2 on
// such a CPU) also runs every other test here.
TEST(PairForces, BaselineAndAvx2CopiesAgreeBitForBit) {
  const RestoreSimd restore;
  if (!useSimd(Simd::Avx2)) GTEST_SKIP() << "no AVX2 and FMA copy in this build or on this CPU";
  int checked = 0;
  for (const forces::InteractionTable& table : threeTables())
    for (const float hi : {3.0f, 6.0f})
      for (const std::uint32_t span : {65536u, 0u}) {
        ParticleStore s = scenarios::randomCloud(2500, -hi, hi, 2.0f, static_cast<std::uint16_t>(table.materials()), 5);
        const float skin = 0.25f;
        neighbors::CellGrid grid;
        grid.rebuild(s, static_cast<float>(table.maxCutoff()) + skin);
        ListOptions options;
        options.narrowSpan = span;
        PairList wide, base;
        ASSERT_TRUE(useSimd(Simd::Avx2));
        wide.build(grid, table, s, skin, options);
        ParticleStore a = s;
        zeroForces(a);
        accumulatePairForces(wide, table, a);
        ASSERT_TRUE(useSimd(Simd::Baseline));
        EXPECT_EQ(simdInUse(), Simd::Baseline);
        base.build(grid, table, s, skin, options);
        ParticleStore b = s;
        zeroForces(b);
        accumulatePairForces(base, table, b);
        ASSERT_EQ(wide.pairCount(), base.pairCount());
        ASSERT_GT(base.pairCount(), 1000u);
        for (std::size_t i = 0; i < s.size(); ++i) ASSERT_EQ(wide.partners(i), base.partners(i)) << i;
        EXPECT_EQ(a.f, b.f);
        ++checked;
      }
  EXPECT_EQ(checked, 12);
}

// The list build tests candidates eight at a time and packs the kept ones (filter() in
// pair_kernels.inl): whatever the number of candidates a particle has (clouds where it
// has about 2, 27 or 220, so blocks end at every lane), with rigid owners excluded or
// not, on a fresh list (no spare room: the bit-by-bit path) and on a rebuilt one, each
// copy lists for slot i exactly the slots j > i within reach, in ascending order, as a
// brute-force scan finds them with the same float arithmetic.
TEST(PairList, ListsExactlyThePairsWithinReachOnEveryCopy) {
  const RestoreSimd restore;
  forces::InteractionTable table(1);
  table.set(0, 0, {forces::Linear{5, 1.0, 0, 5}, 0, 0});
  const float radius = 1.0f, skin = 0.1f;
  const float reach = radius + skin, cut2 = reach * reach;
  const std::vector<float> rowRadius{radius};
  int checked = 0;
  for (const Simd simd : {Simd::Baseline, Simd::Avx2}) {
    if (!useSimd(simd)) continue;
    for (const float hi : {12.0f, 5.0f, 2.5f})
      for (const std::uint32_t exclusiveFrom : {UINT32_MAX, 1u}) {
        ParticleStore s = scenarios::randomCloud(1500, -hi, hi, 0.0f, 1, 11);
        for (std::size_t i = 0; i < s.size(); ++i) s.owner[i] = static_cast<std::uint32_t>(i % 3);
        neighbors::CellGrid grid;
        grid.rebuild(s, reach);
        PairList list;
        for (int build = 0; build < 2; ++build) {
          list.build(grid, table, s, skin, {.rowRadius = rowRadius, .exclusiveOwnersFrom = exclusiveFrom});
          std::size_t total = 0;
          for (std::size_t i = 0; i < s.size(); ++i) {
            std::vector<std::uint32_t> expected;
            for (std::size_t j = i + 1; j < s.size(); ++j) {
              const float dx = s.px[j] - s.px[i], dy = s.py[j] - s.py[i], dz = s.pz[j] - s.pz[i];
              const bool sameBody = s.owner[i] >= exclusiveFrom && s.owner[i] == s.owner[j];
              if (dx * dx + dy * dy + dz * dz < cut2 && !sameBody) expected.push_back(static_cast<std::uint32_t>(j));
            }
            ASSERT_EQ(list.partners(i), expected) << "slot " << i << ", extent " << hi << ", build " << build;
            total += expected.size();
          }
          ASSERT_EQ(list.pairCount(), total);
          ASSERT_GT(total, s.size() / 8);
          ++checked;
        }
      }
  }
  EXPECT_GE(checked, 12);  // the baseline copy at least
}

// A rebuild that adds each layer's forces as soon as it is listed (what the solver does
// on the substep of a rebuild) gives the same list and bitwise the same forces as a
// build followed by accumulatePairForces, for every table, on 1 and 3 threads.
TEST(PairList, BuildAndAccumulateEqualsBuildThenAccumulate) {
  int checked = 0;
  for (const forces::InteractionTable& table : threeTables())
    for (const int threads : {1, 3}) {
      const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
      ParticleStore s = scenarios::randomCloud(3000, -6, 6, 2.0f, static_cast<std::uint16_t>(table.materials()), 9);
      const float skin = 0.2f;
      neighbors::CellGrid grid;
      grid.rebuild(s, static_cast<float>(table.maxCutoff()) + skin);
      ASSERT_GT(grid.layers().size(), 4u);
      PairList separate, fused;
      separate.build(grid, table, s, skin);
      ParticleStore a = s, b = s;
      zeroForces(a);
      zeroForces(b);
      accumulatePairForces(separate, table, a);
      fused.buildAndAccumulate(grid, table, b, skin);
      ASSERT_GT(fused.pairCount(), s.size());
      ASSERT_EQ(fused.pairCount(), separate.pairCount());
      for (std::size_t i = 0; i < s.size(); ++i) ASSERT_EQ(fused.partners(i), separate.partners(i)) << i;
      EXPECT_EQ(a.f, b.f);
      // The fused list serves the next substeps like any other.
      ParticleStore c = s;
      zeroForces(c);
      accumulatePairForces(fused, table, c);
      EXPECT_EQ(c.f, a.f);
      ++checked;
    }
  EXPECT_EQ(checked, 6);
}

// At the boundary of the 16-bit form: two layers of 256 x 128 cells, one particle each,
// one cell apart in z with their particles 0.02 apart, span exactly 65,536 slots, so the
// first layer stays 16-bit with a partner at offset 65,535; one particle more in the
// second layer makes the first one 32-bit. Same partners, same forces either way.
TEST(PairList, SixteenBitFormHoldsUpToItsLastOffset) {
  forces::InteractionTable table(1);
  table.set(0, 0, {forces::Linear{5, 0.5, 0, 5}, 0, 0});
  for (const bool extra : {false, true}) {
    ParticleStore s;
    for (const float z : {0.99f, 1.01f})
      for (int y = 0; y < 128; ++y)
        for (int x = 0; x < 256; ++x) s.add(x + 0.5f, y + 0.5f, z, 0, 0, 0, 0, 0);
    if (extra) s.add(256.5f, 0.5f, 1.01f, 0, 0, 0, 0, 0);
    neighbors::CellGrid grid(2);  // layers along z, the thin axis: two layers of 32,768
    grid.rebuild(s, 1.0f);
    ASSERT_EQ(grid.keyAxes()[2], 2);
    ASSERT_EQ(grid.layers().size(), 2u);
    PairList list;
    list.build(grid, table, s, 0.0f);
    const PairList::Layer& first = list.layers()[0];
    EXPECT_EQ(first.narrow, !extra);
    std::uint32_t last = 0;
    for (std::size_t q = 0; q < first.size(); ++q) last = std::max(last, first.partner(static_cast<std::uint32_t>(q)));
    EXPECT_EQ(last, extra ? 65535u + 1u : 65535u);  // the extra particle sorts before the top row's last cell
    EXPECT_EQ(list.pairCount(), 32768u);
    PairList wide;
    ListOptions wideOptions;
    wideOptions.narrowSpan = 0;
    wide.build(grid, table, s, 0.0f, wideOptions);
    const ParticleStore a = expectSameListsAndForces(list, wide, table, s);
    EXPECT_LT(a.f[0].z, 0.0f);  // the lower particle is pushed down, away from its partner
  }
}

// A list holds little more than what it lists: for a dense cloud, its entries and row
// starts plus an eighth; for a scene of sparse layers (one particle each, as a spray or
// a tall thin column gives), no fixed minimum per layer.
TEST(PairList, MemoryStaysCloseToWhatIsListed) {
  forces::InteractionTable table(1);
  table.set(0, 0, {forces::Linear{5, 1.0, 0, 5}, 0, 0});
  constexpr std::size_t kThreadScratch = 256 * 1024;  // per-thread candidate buffers, generous
  {
    ParticleStore s = scenarios::randomCloud(30000, -10, 10, 0, 1, 4);
    neighbors::CellGrid grid;
    grid.rebuild(s, 1.1f);
    PairList list;
    list.build(grid, table, s, 0.1f);
    ASSERT_GT(list.pairCount(), s.size());
    const double listed = 2.0 * static_cast<double>(list.pairCount()) + 4.0 * static_cast<double>(s.size());
    EXPECT_LT(static_cast<double>(list.memoryBytes()),
              1.2 * listed + static_cast<double>(list.layers().size() * sizeof(PairList::Layer) + kThreadScratch));
  }
  {
    ParticleStore s;
    for (int k = 0; k < 20000; ++k) s.add(0.3f * static_cast<float>(k % 7), 0.5f, 3.0f * static_cast<float>(k), 0, 0, 0, 0, 0);
    neighbors::CellGrid grid;
    grid.rebuild(s, 1.0f);
    ASSERT_EQ(grid.layers().size(), s.size());
    PairList list;
    list.build(grid, table, s, 0.1f);
    EXPECT_EQ(list.pairCount(), 0u);
    EXPECT_LT(list.memoryBytes(), s.size() * (sizeof(PairList::Layer) + 16) + kThreadScratch);
  }
}

// A list rebuilt after the particles spread out (a splash after a dense pool) holds what
// it now lists, not what it once did: each layer gives back what it no longer needs.
TEST(PairList, GivesBackMemoryWhenTheParticlesSpreadOut) {
  forces::InteractionTable table(1);
  table.set(0, 0, {forces::Linear{5, 1.0, 0, 5}, 0, 0});
  const ParticleStore spread = scenarios::randomCloud(30000, -10, 10, 0, 1, 4);
  ParticleStore dense = spread;
  for (std::size_t i = 0; i < dense.size(); ++i) {
    dense.px[i] *= 0.5f;
    dense.py[i] *= 0.5f;
    dense.pz[i] *= 0.5f;
  }
  PairList list;
  neighbors::CellGrid grid;
  grid.rebuild(dense, 1.1f);
  list.build(grid, table, dense, 0.1f);
  const std::size_t densePairs = list.pairCount();
  ParticleStore s = spread;
  grid.rebuild(s, 1.1f);
  list.build(grid, table, s, 0.1f);
  ASSERT_GT(densePairs, 4 * list.pairCount());  // the spread cloud lists far fewer pairs
  std::size_t listed = 0;
  for (const PairList::Layer& l : list.layers()) {
    listed += l.size();
    EXPECT_LE(l.near.capacity() + l.far.capacity(), l.size() + l.size() / 4 + 8);
  }
  EXPECT_EQ(listed, list.pairCount());
  for (std::uint32_t i = 0; i < s.size(); i += 97) {  // and it lists the right partners
    std::vector<std::uint32_t> p = list.partners(i);
    for (std::uint32_t j : p) {
      const float dx = s.px[j] - s.px[i], dy = s.py[j] - s.py[i], dz = s.pz[j] - s.pz[i];
      EXPECT_LT(dx * dx + dy * dy + dz * dz, 1.1f * 1.1f);
    }
  }
}

// The true Lennard-Jones force alone, with no velocity terms: the table the closed-form
// kernel serves (InteractionTable::closedFormLj).
forces::InteractionTable ljTable(double sigma = 0.8, double cutoff = 2.0) {
  forces::InteractionTable t(1);
  t.set(0, 0, {forces::LennardJonesForce{1, sigma, cutoff}, 0, 0});
  return t;
}

// The sorted partners of every slot (a grouped list orders them by group).
std::vector<std::vector<std::uint32_t>> sortedPartners(const PairList& list, std::size_t n) {
  std::vector<std::vector<std::uint32_t>> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    out[i] = list.partners(i);
    std::sort(out[i].begin(), out[i].end());
  }
  return out;
}

// The same pairs listed twice: grouped for the closed-form kernel (when the table has
// one) and plain, for the table kernel.
std::pair<PairList, PairList> groupedAndPlain(const neighbors::CellGrid& grid, const forces::InteractionTable& table,
                                              const ParticleStore& s, float skin) {
  std::pair<PairList, PairList> lists;
  lists.first.build(grid, table, s, skin);
  ListOptions options;
  options.closedForm = false;
  lists.second.build(grid, table, s, skin, options);
  return lists;
}

// Which tables get the closed form: only one material whose function is the true LJ
// force with no velocity term, and its constants are the formula's.
TEST(ClosedForm, OnlyTheLennardJonesForceAloneHasOne) {
  const forces::InteractionTable lj = ljTable(0.8, 2.0);
  ASSERT_TRUE(lj.closedFormLj().has_value());
  const forces::ClosedFormLj& c = *lj.closedFormLj();
  EXPECT_FLOAT_EQ(c.a, 48.0f / 0.64f);
  EXPECT_FLOAT_EQ(c.b, 24.0f / 0.64f);
  EXPECT_FLOAT_EQ(c.sigma2, 0.64f);
  EXPECT_FLOAT_EQ(c.cutoff2, 4.0f);
  // minR2 is where the formula's clamp begins: the force just above it is below the
  // clamp, and at it the closed form gives about the clamp.
  const double rMin = std::sqrt(static_cast<double>(c.minR2));
  const double limit = forces::evaluate(lj.interaction(0, 0).function, 0.0);
  EXPECT_LT(forces::evaluate(lj.interaction(0, 0).function, rMin * 1.001), limit);
  EXPECT_NEAR(forces::evaluate(lj.interaction(0, 0).function, rMin * 0.999), limit, 0);
  forces::InteractionTable damped(1);
  damped.set(0, 0, {forces::LennardJonesForce{1, 0.8, 2.0}, 0.5, 0});
  EXPECT_FALSE(damped.closedFormLj().has_value());
  forces::InteractionTable seed(1);
  seed.set(0, 0, {ownFunction(FluidParams{}), 0, 0});
  EXPECT_FALSE(seed.closedFormLj().has_value());
  EXPECT_FALSE(threeMaterials().closedFormLj().has_value());
  // A table reset to another function loses it.
  forces::InteractionTable reset = ljTable();
  reset.set(0, 0, {forces::Linear{5, 1, 0, 5}, 0, 0});
  EXPECT_FALSE(reset.closedFormLj().has_value());
}

// A grouped list lists exactly the pairs a plain one does (the same distance test), in
// both copies, on dense and sparse clouds whose size is not a multiple of 8 (the store's
// last group is partial), and never lists a slot twice.
TEST(ClosedForm, GroupedListHoldsExactlyThePlainListsPairs) {
  const RestoreSimd restore;
  const forces::InteractionTable table = ljTable();
  int checked = 0;
  for (const Simd simd : {Simd::Baseline, Simd::Avx2}) {
    if (!useSimd(simd)) continue;
    for (const float hi : {3.0f, 6.0f}) {
      ParticleStore s = scenarios::randomCloud(2503, -hi, hi, 0, 1, 17);
      const float skin = 0.3f;
      neighbors::CellGrid grid;
      grid.rebuild(s, static_cast<float>(table.maxCutoff()) + skin);
      const auto [grouped, plain] = groupedAndPlain(grid, table, s, skin);
      ASSERT_TRUE(grouped.grouped());
      ASSERT_FALSE(plain.grouped());
      ASSERT_GT(plain.pairCount(), 5000u);
      EXPECT_EQ(grouped.pairCount(), plain.pairCount());
      const auto a = sortedPartners(grouped, s.size()), b = sortedPartners(plain, s.size());
      for (std::size_t i = 0; i < s.size(); ++i) {
        ASSERT_EQ(a[i], b[i]) << i;
        EXPECT_EQ(std::adjacent_find(a[i].begin(), a[i].end()), a[i].end()) << i;
      }
      // Fewer bytes than a pair per entry: a dense liquid has several partners a group.
      if (hi == 3.0f) {
        EXPECT_LT(grouped.memoryBytes(), plain.memoryBytes());
      }
      ++checked;
    }
  }
  EXPECT_GE(checked, 2);
}

// The closed-form kernel against the double-precision reference from the formula, to
// float rounding (the table kernel is held to 2e-3, its sampling error): in both copies,
// with its sums in a buffer (narrow layers) and straight to the store (narrowSpan 0:
// what layers across the grid's wrap do), for two sigmas.
TEST(ClosedForm, KernelMatchesTheReferenceToFloatRounding) {
  const RestoreSimd restore;
  int checked = 0;
  for (const Simd simd : {Simd::Baseline, Simd::Avx2}) {
    if (!useSimd(simd)) continue;
    for (const double sigma : {0.8, 0.05})
      for (const std::uint32_t span : {65536u, 0u}) {
        const forces::InteractionTable table = ljTable(sigma, 2.5 * sigma);
        const auto side = static_cast<float>(4 * sigma);
        // Density 0.6 per sigma^3, no pair closer than 0.8 sigma (a liquid, not a blow-up).
        ParticleStore s = scenarios::randomCloud(1501, -side, side, 0, 1, 23);
        for (std::size_t i = 0; i < s.size(); ++i) {
          const float q = static_cast<float>(i);
          s.px[i] = static_cast<float>(sigma) * (std::fmod(q, 12.0f) + 0.1f * std::sin(q));
          s.py[i] = static_cast<float>(sigma) * (std::fmod(std::floor(q / 12.0f), 12.0f) + 0.1f * std::cos(q));
          s.pz[i] = static_cast<float>(sigma) * (std::floor(q / 144.0f) + 0.1f * std::sin(2 * q));
        }
        const auto skin = static_cast<float>(0.3 * sigma);
        neighbors::CellGrid grid;
        grid.rebuild(s, static_cast<float>(table.maxCutoff()) + skin);
        ListOptions options;
        options.narrowSpan = span;
        PairList list;
        list.build(grid, table, s, skin, options);
        ASSERT_TRUE(list.grouped());
        zeroForces(s);
        accumulatePairForces(list, table, s);
        SCOPED_TRACE(testing::Message() << "sigma " << sigma << " span " << span);
        expectMatchesReference(table, s, 2e-5);
        ++checked;
      }
  }
  EXPECT_GE(checked, 4);
}

// The closed-form kernel's sums are bitwise the same on 1, 2 and 3 threads, in both
// copies (which agree with each other bit for bit too), and with the list built and
// evaluated in one pass (what the solver does on a rebuild).
TEST(ClosedForm, SumsAreBitwiseTheSameOnEveryThreadCountAndCopy) {
  const RestoreSimd restore;
  const forces::InteractionTable table = ljTable();
  ParticleStore s = scenarios::randomCloud(4001, -5, 5, 0, 1, 29);
  const float skin = 0.25f;
  neighbors::CellGrid grid;
  grid.rebuild(s, static_cast<float>(table.maxCutoff()) + skin);
  ASSERT_GT(grid.layers().size(), 4u);
  std::vector<Force> first;
  int checked = 0;
  for (const Simd simd : {Simd::Baseline, Simd::Avx2}) {
    if (!useSimd(simd)) continue;
    for (const std::size_t threads : {1u, 2u, 3u}) {
      const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
      PairList list;
      list.build(grid, table, s, skin);
      ParticleStore a = s;
      zeroForces(a);
      accumulatePairForces(list, table, a);
      if (first.empty()) first = a.f;
      EXPECT_EQ(a.f, first) << threads << " threads";
      ParticleStore b = s;
      zeroForces(b);
      PairList fused;
      fused.buildAndAccumulate(grid, table, b, skin);
      EXPECT_EQ(b.f, first) << threads << " threads, fused";
      ++checked;
    }
  }
  EXPECT_GE(checked, 3);
}

// setPairForces runs the layers of a packed list all at once: each adds its sums to the
// store under its two layers' locks, and two additions to zero commute, so the result
// is zeroing and the phases' accumulatePairForces to the bit, on any thread count,
// however the threads interleave (repeated to give a race its chances; without the
// locks it failed once in a few runs: neighbours seldom finish together), whatever the
// store held before.
TEST(ClosedForm, LayersWithoutPhasesGiveThePhasesBits) {
  const RestoreSimd restore;
  const forces::InteractionTable table = ljTable(1.0, 2.0);
  // An fcc-like jittered lattice of 16,384 atoms at the LJ liquid's density: 8 to 9
  // layers of about 2,000 atoms.
  ParticleStore s = scenarios::randomCloud(16384, 0, 1, 0, 1, 31);
  for (std::size_t i = 0; i < s.size(); ++i) {
    const float q = static_cast<float>(i);
    s.px[i] = 1.06f * (std::fmod(q, 32.0f) + 0.05f * std::sin(q));
    s.py[i] = 1.06f * (std::fmod(std::floor(q / 32.0f), 32.0f) + 0.05f * std::cos(q));
    s.pz[i] = 1.06f * (std::floor(q / 1024.0f) + 0.05f * std::sin(2 * q));
  }
  const float skin = 0.3f;
  neighbors::CellGrid grid;
  grid.rebuild(s, static_cast<float>(table.maxCutoff()) + skin);
  ASSERT_GT(grid.layers().size(), 4u);
  for (const Simd simd : {Simd::Baseline, Simd::Avx2}) {
    if (!useSimd(simd)) continue;
    PairList list;
    list.build(grid, table, s, skin);
    ASSERT_TRUE(list.packedOnly());
    ParticleStore phases = s;
    zeroForces(phases);
    accumulatePairForces(list, table, phases);
    ParticleStore a = s;
    for (const std::size_t threads : {1u, 2u, 3u}) {
      const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
      // The baseline copy's fused multiply-adds are library calls: few rounds there.
      const int rounds = threads == 1 ? 1 : simd == Simd::Avx2 ? 100 : 3;
      for (int round = 0; round < rounds; ++round) {
        std::fill(a.f.begin(), a.f.end(), Force{1e30f, -2.0f, 3.0f, 4.0f});  // overwritten, not added to
        setPairForces(list, table, a);
        // Byte for byte (== on floats would let -0 pass for +0).
        ASSERT_EQ(std::memcmp(a.f.data(), phases.f.data(), a.f.size() * sizeof(Force)), 0)
            << threads << " threads, round " << round;
      }
    }
  }
  // A list that is not packed only (the table kernel) keeps the phases, after zeroing.
  PairList plain;
  ListOptions options;
  options.closedForm = false;
  plain.build(grid, table, s, skin, options);
  EXPECT_FALSE(plain.packedOnly());
  ParticleStore phases = s;
  zeroForces(phases);
  accumulatePairForces(plain, table, phases);
  ParticleStore a = s;
  std::fill(a.f.begin(), a.f.end(), Force{1e30f, -2.0f, 3.0f, 4.0f});
  setPairForces(plain, table, a);
  EXPECT_EQ(a.f, phases.f);
}

// Every listed pair (i, j), i < j, sorted: a list's pairs as a set.
std::vector<std::pair<std::uint32_t, std::uint32_t>> pairSet(const PairList& list) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  list.forEachPair([&](std::uint32_t i, std::uint32_t j) { out.emplace_back(std::min(i, j), std::max(i, j)); });
  std::sort(out.begin(), out.end());
  return out;
}

// The codes of a packed layer (PairList::Layer::packed) that are jumps.
std::size_t jumpCodes(const PairList& list) {
  std::size_t n = 0;
  for (const PairList::Layer& l : list.layers())
    if (l.isPacked())
      for (const std::uint16_t code : l.packed) n += PairList::Layer::isJump(code) ? 1 : 0;
  return n;
}

// Builds the grouped (packed) and the plain list of `s` on a grid with layers along z
// and checks that every layer is packed and that the packed list lists exactly the plain
// one's pairs, none twice; then its forces against the reference. Returns the packed
// list.
PairList expectPackedListsThePlainPairs(const forces::InteractionTable& table, ParticleStore& s, float cell,
                                        float skin) {
  neighbors::CellGrid grid(2);
  grid.rebuild(s, cell);
  auto [packed, plain] = groupedAndPlain(grid, table, s, skin);
  EXPECT_TRUE(packed.grouped());
  for (const PairList::Layer& l : packed.layers()) EXPECT_TRUE(l.isPacked());
  const auto pairs = pairSet(packed);
  EXPECT_EQ(pairs, pairSet(plain));
  EXPECT_EQ(std::adjacent_find(pairs.begin(), pairs.end()), pairs.end());
  EXPECT_EQ(packed.pairCount(), plain.pairCount());
  zeroForces(s);
  accumulatePairForces(packed, table, s);
  expectMatchesReference(table, s, 2e-5);
  return packed;
}

// Packed lists where their codes must jump: layers of thousands of slots, whose next
// layer's rows lie more than 511 slots on, and cells so dense that one candidate range
// spans hundreds of groups. Each lists exactly the plain list's pairs (no pair twice),
// and the kernel matches the reference, in both copies.
TEST(ClosedForm, PackedListsJumpToFarRowsAndWalkDenseCells) {
  const RestoreSimd restore;
  const float skin = 0.3f, cell = 2.3f;
  // A jittered lattice of nx x ny x nz points `spacing` apart (no pair closer than
  // 0.8 sigma: the closed form and the reference agree only down to where the formula
  // clamps).
  const auto lattice = [](int nx, int ny, int nz, float spacing, std::uint32_t seed) {
    const ParticleStore jitter = scenarios::randomCloud(static_cast<std::size_t>(nx * ny * nz), -0.1f, 0.1f, 0, 1, seed);
    ParticleStore s;
    std::size_t q = 0;
    for (int z = 0; z < nz; ++z)
      for (int y = 0; y < ny; ++y)
        for (int x = 0; x < nx; ++x, ++q)
          s.add(spacing * (static_cast<float>(x) + jitter.px[q]), spacing * (static_cast<float>(y) + jitter.py[q]),
                spacing * (static_cast<float>(z) + jitter.pz[q]), 0, 0, 0, 0, 0);
    return s;
  };
  // 18 x 18 cells a layer, 3 layers along z, 8 particles a cell: 324 groups a layer.
  ParticleStore wide = lattice(36, 36, 6, 1.15f, 41);
  const forces::InteractionTable wideTable = ljTable(0.8, 2.0);
  // 2,548 particles in one cell (sigma 0.05, cutoff 2: a very long one).
  ParticleStore dense = lattice(14, 14, 13, 0.11f, 43);
  const forces::InteractionTable denseTable = ljTable(0.05, 2.0);
  // One cell: a particle in a corner, 2,744 beyond its reach in the opposite one, then
  // 100 around it. Its first partner lies 343 groups (2,744 slots) on in a range of
  // 356: jumps before its first window.
  ParticleStore gap;
  gap.add(2.29f, 2.29f, 2.29f, 0, 0, 0, 0, 0);
  for (const auto& [block, at] : {std::pair{lattice(14, 14, 14, 0.06f, 45), 0.05f}, std::pair{lattice(5, 5, 4, 0.1f, 46), 1.8f}})
    for (std::size_t i = 0; i < block.size(); ++i) gap.add(at + block.px[i], at + block.py[i], at + block.pz[i], 0, 0, 0, 0, 0);
  int checked = 0;
  for (const Simd simd : {Simd::Baseline, Simd::Avx2}) {
    if (!useSimd(simd)) continue;
    for (ParticleStore* cloud : {&wide, &dense, &gap}) {
      ParticleStore& s = *cloud;
      const PairList packed = expectPackedListsThePlainPairs(cloud == &wide ? wideTable : denseTable, s, cell, skin);
      if (cloud == &wide) {
        EXPECT_GT(jumpCodes(packed), s.size() / 2);  // about one a particle
      }
      if (cloud == &gap) {
        EXPECT_EQ(packed.layers().size(), 1u);  // one cell
        EXPECT_GT(jumpCodes(packed), 0u);
      }
      ++checked;
    }
  }
  EXPECT_GE(checked, 3);
}

// A packed list across the grid's wrap: a block of liquid and one particle flung about
// 2^21 cells along x, so that the cells' coordinates wrap and the flung particle's
// forward cells (x + 1) are the block's first ones, behind it in the same layer. Its
// candidate ranges there hold no partner, so it lists nothing and writes no window
// (windows are written only for partners; the walk's slot counts start below 0 for the
// first slots). The same pairs as the plain list, the reference's forces, in both
// copies, and a jump and an end code a slot at most besides the windows. (A jump
// counted in 64 bits from a wrapped position once ran on for a million codes past the
// list's end.)
TEST(ClosedForm, PackedListsStepBackAcrossTheGridsWrap) {
  const RestoreSimd restore;
  const forces::InteractionTable table = ljTable(0.8, 2.0);
  const float skin = 0.3f, cell = 2.3f;
  const ParticleStore jitter = scenarios::randomCloud(200 * 6 * 4, -0.1f, 0.1f, 0, 1, 61);
  ParticleStore s;
  s.add(static_cast<float>((double{1 << 21} - 0.5) * cell), 0.6f, 0.6f, 0, 0, 0, 0, 0);
  std::size_t q = 0;
  for (int z = 0; z < 4; ++z)  // 100 x 3 cells a layer, 2 layers, 8 particles a cell
    for (int y = 0; y < 6; ++y)
      for (int x = 0; x < 200; ++x, ++q)
        s.add(0.5f + 1.15f * (static_cast<float>(x) + jitter.px[q]), 0.5f + 1.15f * (static_cast<float>(y) + jitter.py[q]),
              0.5f + 1.15f * (static_cast<float>(z) + jitter.pz[q]), 0, 0, 0, 0, 0);
  int checked = 0;
  for (const Simd simd : {Simd::Baseline, Simd::Avx2}) {
    if (!useSimd(simd)) continue;
    const PairList packed = expectPackedListsThePlainPairs(table, s, cell, skin);
    std::size_t codes = 0, windows = 0;
    for (const PairList::Layer& l : packed.layers()) {
      codes += l.packed.size();
      for (const std::uint16_t code : l.packed) windows += PairList::Layer::isWindow(code) ? 1 : 0;
    }
    EXPECT_LE(static_cast<double>(codes), static_cast<double>(windows) + 2.1 * static_cast<double>(s.size()));
    std::size_t flung = 0;
    while (flung < s.size() && s.px[flung] < 1e5f) ++flung;
    ASSERT_LT(flung, s.size());
    EXPECT_TRUE(packed.partners(flung).empty());
    ++checked;
  }
  EXPECT_GE(checked, 1);
}

// A pair in the skin's shell (beyond the cutoff, within the list) across the grid's wrap:
// its window starts behind its slot, so it stays in the slot's codes (as an outer
// window it had a wrapped 16-bit offset: a partner 65,544 in a store of 290, a pair
// missing and a crash, found by a code review). The plain list's pairs and the
// reference's forces, in both copies.
TEST(ClosedForm, AWindowBehindItsSlotAcrossTheWrapIsNeverOuter) {
  const RestoreSimd restore;
  const forces::InteractionTable table = ljTable(0.8, 2.0);
  const float skin = 0.3f, cell = 2.3f;
  ParticleStore s;
  for (int z = 0; z < 4; ++z)
    for (int y = 0; y < 6; ++y)
      for (int x = 0; x < 12; ++x)
        s.add(0.5f + 1.15f * static_cast<float>(x) + 0.01f * static_cast<float>((x * 7 + y * 3 + z) % 5),
              0.5f + 1.15f * static_cast<float>(y), 0.5f + 1.15f * static_cast<float>(z), 0, 0, 0, 0, 0);
  // P in the grid's last cell along x, Q in its first (2^21 cells on): 2.09 apart.
  s.add(4823449.0f, 0.1f, 0.1f, 0, 0, 0, 0, 0);
  s.add(4823450.0f, 1.4f, 1.4f, 0, 0, 0, 0, 0);
  int checked = 0;
  for (const Simd simd : {Simd::Baseline, Simd::Avx2}) {
    if (!useSimd(simd)) continue;
    ParticleStore t = s;
    const PairList packed = expectPackedListsThePlainPairs(table, t, cell, skin);
    std::size_t p = 0;
    while (p < t.size() && t.px[p] != 4823449.0f) ++p;
    ASSERT_LT(p, t.size());
    std::size_t far = 0;
    packed.forEachPair([&](std::uint32_t i, std::uint32_t j) {
      ASSERT_LT(j, t.size());
      far += (i == p || j == p) ? 1 : 0;
    });
    EXPECT_EQ(far, 1u) << "P's one pair, with Q";
    ++checked;
  }
  EXPECT_GE(checked, 1);
}

// The LJ liquid's lattice: `cells`^3 fcc cells at reduced density 0.8442 (LAMMPS's
// bench/in.lj), each atom moved by up to +-0.02 sigma (the random cloud of `seed`).
ParticleStore fccLiquid(int cells, std::uint64_t seed) {
  const float a = std::cbrt(4.0f / 0.8442f);  // the fcc cell
  ParticleStore s;
  const ParticleStore jitter =
      scenarios::randomCloud(static_cast<std::size_t>(cells * cells * cells * 4), -0.02f, 0.02f, 0, 1, seed);
  const float basis[4][3] = {{0, 0, 0}, {0.5f, 0.5f, 0}, {0.5f, 0, 0.5f}, {0, 0.5f, 0.5f}};
  std::size_t q = 0;
  for (int z = 0; z < cells; ++z)
    for (int y = 0; y < cells; ++y)
      for (int x = 0; x < cells; ++x)
        for (const auto& b : basis) {
          s.add(a * (static_cast<float>(x) + b[0]) + jitter.px[q], a * (static_cast<float>(y) + b[1]) + jitter.py[q],
                a * (static_cast<float>(z) + b[2]) + jitter.pz[q], 0, 0, 0, 0, 0);
          ++q;
        }
  return s;
}

// The LJ liquid's packed list (fcc at reduced density 0.8442, cutoff 2.5, 13,500
// atoms, layers of over 300 groups): 2 bytes a window, fewer windows than aligned
// groups, a jump and an end code a slot and an eighth of spare capacity at most: under
// 30 bytes an atom, where 32-bit aligned groups and row starts took 53 (the issue's
// budget for a whole simulation is 100).
TEST(ClosedForm, PackedListOfTheLjLiquidTakesTwoBytesAWindow) {
  const forces::InteractionTable table = ljTable(1.0, 2.5);
  ParticleStore s = fccLiquid(15, 51);
  const float skin = 0.25f;
  neighbors::CellGrid grid;
  grid.rebuild(s, 2.5f + skin);
  PairList list;
  list.build(grid, table, s, skin);
  ASSERT_TRUE(list.grouped());
  std::size_t codes = 0, windows = 0, capacity = 0;
  for (const PairList::Layer& l : list.layers()) {
    ASSERT_TRUE(l.isPacked());
    EXPECT_TRUE(l.start.empty());
    codes += l.packed.size() + l.outer.size();
    capacity += l.packed.capacity() + l.outer.capacity();
    windows += l.outer.size();
    for (const std::uint16_t code : l.packed) windows += PairList::Layer::isWindow(code) ? 1 : 0;
  }
  // Per slot, from its partners sorted: the aligned groups of 8 they fall in, and the
  // greedy windows (each from the lowest partner not yet in one) the list should hold.
  std::vector<std::vector<std::uint32_t>> partners(s.size());
  list.forEachPair([&](std::uint32_t i, std::uint32_t j) { partners[i].push_back(j); });
  std::size_t aligned = 0, greedy = 0;
  for (std::vector<std::uint32_t>& p : partners) {
    std::sort(p.begin(), p.end());
    std::int64_t groupSeen = -1, windowEnd = -1;
    for (const std::uint32_t j : p) {
      if (static_cast<std::int64_t>(j / 8) != groupSeen) {
        ++aligned;
        groupSeen = j / 8;
      }
      if (static_cast<std::int64_t>(j) >= windowEnd) {
        ++greedy;
        windowEnd = static_cast<std::int64_t>(j) + 8;
      }
    }
  }
  EXPECT_EQ(windows, greedy);
  const auto n = static_cast<double>(s.size());
  EXPECT_GT(static_cast<double>(list.pairCount()) / n, 30.0);  // a dense liquid: about 35 partners
  // Windows that start at a partner need fewer than aligned groups (9.5 against 11 a
  // particle when this test was written).
  EXPECT_LT(static_cast<double>(windows), 0.92 * static_cast<double>(aligned));
  EXPECT_LE(static_cast<double>(codes), static_cast<double>(windows) + 2.1 * n);  // a jump and an end a slot
  EXPECT_LE(static_cast<double>(capacity), 1.15 * static_cast<double>(codes));
  EXPECT_LT(2.0 * static_cast<double>(capacity) / n, 30.0);
}

// The outer windows of a packed list (PairList::Layer::outer): on the LJ liquid at
// cutoff 2.0 (fcc, its third shell at 2.06 sigma lies in the skin) a fifth or more of
// the windows, none with a partner within the cutoff when the list was built. Then
// every particle moves by up to a third of the skin,
// so that some outer windows hold pairs within the cutoff: the kernel evaluates them
// (the forces match the reference to float rounding), in both copies, bitwise the same
// on 1, 2 and 3 threads and in the phases and all at once.
TEST(ClosedForm, OuterWindowsAreEvaluatedOnceTheirPartnersComeWithinTheCutoff) {
  const RestoreSimd restore;
  const forces::InteractionTable table = ljTable(1.0, 2.0);
  ParticleStore s = fccLiquid(12, 53);
  const float skin = 0.3f, cut2 = 4.0f;
  neighbors::CellGrid grid;
  grid.rebuild(s, 2.0f + skin);
  const auto r2 = [](const ParticleStore& p, std::uint32_t i, std::uint32_t j) {
    const float dx = p.px[j] - p.px[i], dy = p.py[j] - p.py[i], dz = p.pz[j] - p.pz[i];
    return dx * dx + dy * dy + dz * dz;
  };
  // Each outer window's partners: fn(slot, partners of the window).
  const auto forEachOuter = [](const PairList& list, auto&& fn) {
    for (const PairList::Layer& l : list.layers()) {
      ASSERT_TRUE(l.isPacked());
      ASSERT_EQ(l.outer.size(), l.outerLanes.size());
      std::size_t o = 0;
      std::uint32_t k = 0;
      for (const std::uint16_t code : l.packed) {
        if (!PairList::Layer::isEnd(code)) continue;
        for (std::uint32_t n = 0; n < code; ++n, ++o) {
          const std::uint32_t i = l.slots.begin + k, w = i + 1 + l.outer[o];
          std::vector<std::uint32_t> partners;
          for (std::uint32_t bits = PairList::Layer::windowLanes(l.outerLanes[o]); bits != 0;
               bits &= bits - 1)
            partners.push_back(w + static_cast<std::uint32_t>(std::countr_zero(bits)));
          fn(i, partners);
        }
        ++k;
      }
      EXPECT_EQ(o, l.outer.size());
      EXPECT_EQ(k, l.slots.end - l.slots.begin);
    }
  };
  std::vector<Force> first;
  int checked = 0;
  for (const Simd simd : {Simd::Baseline, Simd::Avx2}) {
    if (!useSimd(simd)) continue;
    PairList list;
    list.build(grid, table, s, skin);
    std::size_t outer = 0, windows = 0;
    for (const PairList::Layer& l : list.layers()) {
      outer += l.outer.size();
      windows += l.outer.size();
      for (const std::uint16_t code : l.packed) windows += PairList::Layer::isWindow(code) ? 1 : 0;
    }
    EXPECT_GT(static_cast<double>(outer), 0.2 * static_cast<double>(windows));
    forEachOuter(list, [&](std::uint32_t i, const std::vector<std::uint32_t>& partners) {
      for (const std::uint32_t j : partners) EXPECT_GE(r2(s, i, j), cut2) << i << " " << j;
    });
    // The move: each particle by up to skin / 3 on each axis (under skin / 2 in all).
    ParticleStore moved = s;
    const ParticleStore shift = scenarios::randomCloud(s.size(), -0.1f, 0.1f, 0, 1, 59);
    for (std::size_t i = 0; i < s.size(); ++i) {
      moved.px[i] += 0.8f * shift.px[i];
      moved.py[i] += 0.8f * shift.py[i];
      moved.pz[i] += 0.8f * shift.pz[i];
    }
    std::size_t woken = 0;
    forEachOuter(list, [&](std::uint32_t i, const std::vector<std::uint32_t>& partners) {
      bool any = false;
      for (const std::uint32_t j : partners) any = any || r2(moved, i, j) < cut2;
      woken += any ? 1 : 0;
    });
    EXPECT_GT(woken, 100u);
    EXPECT_LT(woken, outer);
    zeroForces(moved);
    accumulatePairForces(list, table, moved);
    expectMatchesReference(table, moved, 2e-5);
    if (first.empty()) first = moved.f;
    EXPECT_EQ(moved.f, first);  // the two copies
    for (const std::size_t threads : {1u, 2u, 3u}) {
      const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
      ParticleStore again = moved;
      zeroForces(again);
      accumulatePairForces(list, table, again);
      EXPECT_EQ(again.f, first) << threads << " threads";
      std::fill(again.f.begin(), again.f.end(), Force{1e30f, -2.0f, 3.0f, 4.0f});
      setPairForces(list, table, again);
      EXPECT_EQ(std::memcmp(again.f.data(), first.data(), first.size() * sizeof(Force)), 0)
          << threads << " threads";
    }
    ++checked;
  }
  EXPECT_GE(checked, 1);
}

// A slot with more windows beyond the cutoff than its end code can count
// (PairList::Layer::kOuterMost): a lattice with a skin twice the cutoff, where each slot
// lists hundreds of partners that lie beyond it. The first kOuterMost go apart, the rest
// stay in the slot's codes: still exactly the plain list's pairs, and the reference's
// forces, in both copies.
TEST(ClosedForm, SlotsWithMoreOuterWindowsThanTheirEndCodeCountsKeepTheRest) {
  const RestoreSimd restore;
  const forces::InteractionTable table = ljTable(0.3, 0.9);
  const float skin = 2.0f, cell = 0.9f + skin;
  const ParticleStore jitter = scenarios::randomCloud(16 * 16 * 16, -0.05f, 0.05f, 0, 1, 67);
  ParticleStore s;
  std::size_t q = 0;
  for (int z = 0; z < 16; ++z)
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x, ++q)
        s.add(0.45f * static_cast<float>(x) + jitter.px[q], 0.45f * static_cast<float>(y) + jitter.py[q],
              0.45f * static_cast<float>(z) + jitter.pz[q], 0, 0, 0, 0, 0);
  int checked = 0;
  for (const Simd simd : {Simd::Baseline, Simd::Avx2}) {
    if (!useSimd(simd)) continue;
    const PairList packed = expectPackedListsThePlainPairs(table, s, cell, skin);
    std::size_t full = 0, outer = 0;
    for (const PairList::Layer& l : packed.layers()) {
      outer += l.outer.size();
      for (const std::uint16_t code : l.packed) full += code == PairList::Layer::kOuterMost ? 1 : 0;
    }
    EXPECT_GT(full, 10u);  // slots whose end code is full (54 when this was written)
    EXPECT_GT(outer, full * PairList::Layer::kOuterMost);
    ++checked;
  }
  EXPECT_GE(checked, 1);
}

// A packed layer's codes, written by hand: windows, a jump ahead, a jump back, the end
// of each slot with its count of outer windows, and those; decoded into partners.
TEST(PairList, PackedCodesDecodeIntoPartners) {
  using Layer = PairList::Layer;
  Layer layer;
  layer.grouped = true;
  layer.narrow = true;
  layer.slots = {16, 18};  // slot 16's walk starts at 9
  layer.span = {16, 20000};
  // A window `step` slots on; field bit c - 1: its lane c (lane 0 always) is a partner.
  const auto window = [](std::uint32_t step, std::uint32_t field) { return static_cast<std::uint16_t>(step << 7 | field); };
  const auto jump = [](std::int32_t units) { return static_cast<std::uint16_t>(1u << 7 | (static_cast<std::uint32_t>(units) & 127u)); };
  layer.packed = {window(8, 0b1),         // slot 17 and lane 1: 18
                  window(23, 0),          // 40
                  jump(10),               // 40 + 2,560
                  window(30, 0b1000000),  // 2,630 and lane 7: 2,637
                  jump(-5),               // 2,630 - 1,280
                  window(511, 0),         // 1,861
                  2,                      // the end, and 2 outer windows
                  0};                     // slot 17: no partners, no outer windows
  layer.outer = {3, 700};                 // 16 + 1 + 3 = 20, 717
  layer.outerLanes = {0b0000101, 0};      // 20, lanes 1 and 3: 21, 23; 717
  EXPECT_TRUE(Layer::isJump(jump(-64)));
  EXPECT_TRUE(Layer::isJump(jump(63)));
  EXPECT_FALSE(Layer::isJump(window(8, 0)));
  EXPECT_FALSE(Layer::isJump(0));
  EXPECT_FALSE(Layer::isJump(2));
  EXPECT_TRUE(Layer::isEnd(2));
  EXPECT_TRUE(Layer::isEnd(Layer::kOuterMost));
  EXPECT_FALSE(Layer::isEnd(jump(0)));
  EXPECT_EQ(static_cast<std::int32_t>(Layer::jumpOf(jump(-64))), -64 * Layer::kJumpSlots);
  EXPECT_EQ(static_cast<std::int32_t>(Layer::jumpOf(jump(63))), 63 * Layer::kJumpSlots);
  EXPECT_EQ(Layer::windowLanes(window(9, 0b1000001)), 0b10000011u);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> got;
  layer.forEachPair([&](std::uint32_t k, std::uint32_t j) { got.emplace_back(k, j); });
  const std::vector<std::pair<std::uint32_t, std::uint32_t>> want = {
      {0, 17}, {0, 18}, {0, 40}, {0, 2630}, {0, 2637}, {0, 1861}, {0, 20}, {0, 21}, {0, 23}, {0, 717}};
  EXPECT_EQ(got, want);
  std::vector<std::uint32_t> of0;
  layer.forEachPartner(0, [&](std::uint32_t j) { of0.push_back(j); });
  EXPECT_EQ(of0, (std::vector<std::uint32_t>{17, 18, 40, 2630, 2637, 1861, 20, 21, 23, 717}));
  std::size_t of1 = 0;
  layer.forEachPartner(1, [&](std::uint32_t) { ++of1; });
  EXPECT_EQ(of1, 0u);
}

// Two atoms closer than where the formula clamps its force, and two on top of each
// other: finite, opposite forces (no direction for the coincident pair: none at all).
TEST(ClosedForm, CloseAndCoincidentAtomsStayFinite) {
  const forces::InteractionTable table = ljTable(1.0, 2.5);
  ParticleStore s;
  s.add(0, 0, 0, 0, 0, 0, 0, 0);
  s.add(0.01f, 0, 0, 0, 0, 0, 0, 0);
  s.add(5, 5, 5, 0, 0, 0, 0, 0);
  s.add(5, 5, 5, 0, 0, 0, 0, 0);
  neighbors::CellGrid g;
  g.rebuild(s, 2.8f);
  PairList list;
  list.build(g, table, s, 0.3f);
  ASSERT_TRUE(list.grouped());
  zeroForces(s);
  accumulatePairForces(list, table, s);
  for (const Force& f : s.f) EXPECT_TRUE(std::isfinite(f.x) && std::isfinite(f.y) && std::isfinite(f.z));
  std::vector<std::uint32_t> slot;
  s.slotsById(slot);
  EXPECT_LT(s.f[slot[0]].x, -1e9f);  // pushed apart hard
  EXPECT_FLOAT_EQ(s.f[slot[0]].x, -s.f[slot[1]].x);
  EXPECT_EQ(s.f[slot[2]].x, 0.0f);
  EXPECT_EQ(s.f[slot[3]].x, 0.0f);
}

}  // namespace
}  // namespace softsub::fluid
