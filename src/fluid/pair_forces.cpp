#include "fluid/pair_forces.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstring>
#include <span>
#include <stdexcept>
#include <thread>
#include <type_traits>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

// A second copy of the hot loops for AVX2 (chosen at run time) where the compiler can
// make one and the build does not already target AVX2 for everything (SOFTSUB_AVX2_COPY).
#if SOFTSUB_AVX2_COPY
#define SOFTSUB_AVX2_ONLY(call) call
#else
#define SOFTSUB_AVX2_ONLY(call) (void)0
#endif

// The closed-form kernel passes 8-lane vectors (pair_kernels.inl) by value, which GCC
// warns about in the baseline copy (its ABI has no AVX). They are internal helpers,
// inlined, in an unnamed namespace: no call crosses that ABI. GCC reports the warning
// at the end of the file, so it is off for the whole file.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace softsub::fluid {

namespace {

// Holds the locks of a packed layer's two layers (its own and the next, whose slots its
// sums reach) while it adds its sums to the store, in the schedule without phases
// (setPairForces): taken in ascending order, so two neighbours never wait on
// each other; held for one pass over the layer's span. Nothing when `locks` is empty.
class LayerLocks {
 public:
  explicit LayerLocks(std::span<std::atomic<bool>> locks) : locks_(locks) {
    for (std::atomic<bool>& l : locks_)
      while (l.exchange(true, std::memory_order_acquire))
        while (l.load(std::memory_order_relaxed)) pause();
  }
  ~LayerLocks() {
    for (std::atomic<bool>& l : locks_) l.store(false, std::memory_order_release);
  }
  LayerLocks(const LayerLocks&) = delete;
  LayerLocks& operator=(const LayerLocks&) = delete;

 private:
  static void pause() {
#if defined(__SSE2__)
    _mm_pause();
#else
    std::this_thread::yield();
#endif
  }
  std::span<std::atomic<bool>> locks_;
};

namespace baseline {
#define SOFTSUB_KERNEL_AVX 0
#include "fluid/pair_kernels.inl"
#undef SOFTSUB_KERNEL_AVX
}  // namespace baseline

#if SOFTSUB_AVX2_COPY
// The same source for AVX2 and FMA: 8-wide passes (GCC 12 emits no gathers here), the same
// IEEE operations in the same order, so the same bits as the baseline copy (tested). FMA
// only where the source asks for one (fused() in pair_kernels.inl); the file is built
// with -ffp-contract=off (src/fluid/CMakeLists.txt), so GCC contracts none of our
// multiplications and additions (its exact integer-to-float conversions aside).
#pragma GCC push_options
#pragma GCC target("avx2,fma")
namespace avx2 {
#define SOFTSUB_KERNEL_AVX 1  // GCC does not define __AVX__ inside the pragma
#include "fluid/pair_kernels.inl"
#undef SOFTSUB_KERNEL_AVX
}  // namespace avx2
#pragma GCC pop_options
#endif

bool cpuHasAvx2() {
#if SOFTSUB_AVX2_COPY
  return __builtin_cpu_supports("avx2") != 0 && __builtin_cpu_supports("fma") != 0;
#else
  return false;
#endif
}

std::atomic<Simd>& simdChoice() {
  static std::atomic<Simd> choice{cpuHasAvx2() ? Simd::Avx2 : Simd::Baseline};
  return choice;
}

// The kernel for one layer, in the copy `simd` selects (sums: the thread's buffer for
// the closed-form kernel).
void layerForces(Simd simd, const PairList::Layer& layer, const forces::InteractionTable& table,
                 ParticleStore& s, std::vector<float>& sums, std::span<std::atomic<bool>> locks = {}) {
  if (simd == Simd::Avx2) SOFTSUB_AVX2_ONLY(avx2::layerForcesOf(layer, table, s, sums, locks));
  else baseline::layerForcesOf(layer, table, s, sums, locks);
}

}  // namespace

Simd simdInUse() { return simdChoice().load(std::memory_order_relaxed); }

bool useSimd(Simd level) {
  if (level == Simd::Avx2 && !cpuHasAvx2()) return false;
  simdChoice().store(level, std::memory_order_relaxed);
  return true;
}

// Per-thread build buffers: one cell's candidates (positions, list entries, owners, each
// with a block of padding that filter() may read), and one layer's forward ranges. They
// grow to the densest neighbourhood seen, then stay.
struct PairList::Scratch {
  struct Buffers {
    std::vector<float> x, y, z;
    std::vector<std::uint32_t> entry, owner;
    std::vector<std::uint32_t> kept;  // one particle's partners when the list is nearly full
    std::vector<neighbors::SlotRange> ranges;  // the forward ranges of one layer's cells
    std::vector<std::uint32_t> rangeStart;     // each cell's first in ranges
    // The closed-form kernel's force sums over a layer's span and, for a layer that
    // reaches the store's end, its positions padded with zeros (layerForcesOf).
    std::vector<float> sums;
  };
  tbb::enumerable_thread_specific<Buffers> perThread;
  // One lock a layer for the schedule without phases (LayerLocks), all released
  // between evaluations; reallocated only when the layers outgrow them.
  std::unique_ptr<std::atomic<bool>[]> locks;
  std::size_t lockCount = 0;
};

PairList::PairList() : scratch_(std::make_unique<Scratch>()) {}
PairList::~PairList() = default;
PairList::PairList(PairList&&) noexcept = default;
PairList& PairList::operator=(PairList&&) noexcept = default;

std::vector<std::uint32_t> PairList::partners(std::size_t i) const {
  const auto end = layers_.begin() + static_cast<std::ptrdiff_t>(layerCount_);
  const auto it = std::upper_bound(layers_.begin(), end, i, [](std::size_t v, const Layer& l) { return v < l.slots.end; });
  if (it == end || i < it->slots.begin) return {};
  std::vector<std::uint32_t> out;
  it->forEachPartner(static_cast<std::uint32_t>(i - it->slots.begin), [&](std::uint32_t j) { out.push_back(j); });
  return out;
}

std::size_t PairList::pairCount() const {
  std::size_t n = 0;
  for (std::size_t l = 0; l < layerCount_; ++l) {
    const Layer& layer = layers_[l];
    if (!layer.grouped) {
      n += layer.size();
      continue;
    }
    // The lanes of every entry (a packed layer's jump and end codes have none).
    if (layer.isPacked()) {
      // A window's lanes from a table (std::popcount is a library call on baseline x86-64).
      static constexpr auto kLanes = [] {
        std::array<std::uint8_t, 128> t{};
        for (std::uint32_t f = 0; f < 128; ++f) t[f] = static_cast<std::uint8_t>(std::popcount(Layer::windowLanes(f)));
        return t;
      }();
      for (const std::uint16_t e : layer.packed) n += Layer::isWindow(e) ? kLanes[e & 127u] : 0u;
      for (const std::uint8_t e : layer.outerLanes) n += kLanes[e & 127u];
      continue;
    }
    for (const std::uint32_t e : layer.groups) n += static_cast<std::size_t>(std::popcount(e & 255u));
  }
  return n;
}

std::size_t PairList::memoryBytes() const {
  std::size_t b = (rowCut2_.capacity() + firstCell_.capacity()) * 4 + layers_.capacity() * sizeof(Layer);
  for (const Layer& l : layers_)
    b += (l.start.capacity() + l.far.capacity() + l.groups.capacity()) * 4 +
         (l.near.capacity() + l.packed.capacity() + l.outer.capacity()) * 2 + l.outerLanes.capacity();
  for (const Scratch::Buffers& s : scratch_->perThread)
    b += (s.x.capacity() + s.y.capacity() + s.z.capacity() + s.entry.capacity() +
          s.owner.capacity() + s.kept.capacity() + s.rangeStart.capacity() + s.sums.capacity()) * 4 + s.ranges.capacity() * sizeof(neighbors::SlotRange);
  return b;
}

// Groups of 8 slots for the closed-form kernel: a group's index has 24 bits, and the
// grouped build does not exclude a rigid owner's own pairs.
bool PairList::groups(const forces::InteractionTable& table, std::size_t particles,
                      const ListOptions& options) {
  return options.closedForm && table.closedFormLj().has_value() && particles < (std::size_t{1} << 27) &&
         options.exclusiveOwnersFrom == UINT32_MAX;
}

void PairList::build(const neighbors::CellGrid& grid, const forces::InteractionTable& table,
                     const ParticleStore& s, float skin, const ListOptions& options) {
  build(grid, table, s, skin, options, nullptr);
}

void PairList::buildAndAccumulate(const neighbors::CellGrid& grid, const forces::InteractionTable& table,
                                  ParticleStore& s, float skin, const ListOptions& options) {
  build(grid, table, s, skin, options, &s);
}

void PairList::build(const neighbors::CellGrid& grid, const forces::InteractionTable& table,
                     const ParticleStore& s, float skin, const ListOptions& options, ParticleStore* forces) {
  packedOnly_ = false;  // until the layers below are built (a build that throws leaves it so)
  rowCut2_.resize(table.materials());
  for (std::size_t a = 0; a < rowCut2_.size(); ++a) {
    const float radius = options.rowRadius.empty() ? std::sqrt(table.rowCutoff2(a)) : options.rowRadius[a];
    const float rc = radius + skin;
    rowCut2_[a] = rc * rc;
  }
  const auto gridLayers = grid.layers();
  layerCount_ = gridLayers.size();
  if (layers_.size() < layerCount_) layers_.resize(layerCount_);
  phases_ = grid.layersByPhase();
  grouped_ = groups(table, s.size(), options);
  // Cells, and so layers, come in slot order: a layer is a run of cells.
  firstCell_.resize(layerCount_ + 1);  // keeps its memory: no allocation once warmed up
  {
    std::size_t c = 0;
    for (std::size_t l = 0; l < layerCount_; ++l) {
      while (grid.cell(c).begin < gridLayers[l].begin) ++c;
      firstCell_[l] = static_cast<std::uint32_t>(c);
    }
    firstCell_[layerCount_] = static_cast<std::uint32_t>(grid.cellCount());
  }
  // Packed windows with no partner within the cutoff are kept as outer windows
  // (Layer::outer; docs/benchmarks.md, thirty-second session: with a margin of a tenth
  // of the skin the liquid at cutoff 2.0 was slower, at 2.5 no faster).
  const float innerCut2 = grouped_ ? table.closedFormLj()->cutoff2 : 0.0f;
  const Simd simd = simdInUse();
  auto buildOne = [&](std::size_t l, Scratch::Buffers& buf, neighbors::CellGrid::ForwardRanges& forwardRanges) {
    if (simd == Simd::Avx2)
      SOFTSUB_AVX2_ONLY(avx2::buildLayer(layers_[l], gridLayers[l], firstCell_[l], firstCell_[l + 1], buf,
                                         forwardRanges, grid, s, options, rowCut2_.data(), grouped_,
                                         innerCut2));
    else
      baseline::buildLayer(layers_[l], gridLayers[l], firstCell_[l], firstCell_[l + 1], buf, forwardRanges,
                           grid, s, options, rowCut2_.data(), grouped_, innerCut2);
  };
  if (forces == nullptr) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, layerCount_, 1), [&](const auto& range) {
      Scratch::Buffers& buf = scratch_->perThread.local();
      neighbors::CellGrid::ForwardRanges forwardRanges(grid);
      for (std::size_t l = range.begin(); l != range.end(); ++l) buildOne(l, buf, forwardRanges);
    });
  } else {
    for (const std::vector<std::uint32_t>& phase : phases_) {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, phase.size(), 1), [&](const auto& range) {
        Scratch::Buffers& buf = scratch_->perThread.local();
        neighbors::CellGrid::ForwardRanges forwardRanges(grid);
        for (std::size_t p = range.begin(); p != range.end(); ++p) {
          const std::size_t l = phase[p];
          buildOne(l, buf, forwardRanges);
          layerForces(simd, layers_[l], table, *forces, buf.sums);
        }
      });
    }
  }
  // Whether the layers may run without phases (setPairForces): every layer
  // packed, its sums reaching no further than the next layer's slots (so two locks
  // cover them; a packed layer is narrow, whose span starts at its own first slot).
  packedOnly_ = true;
  for (std::size_t l = 0; l < layerCount_; ++l) {
    const std::uint32_t reach = l + 1 < layerCount_ ? layers_[l + 1].slots.end : layers_[l].slots.end;
    packedOnly_ = packedOnly_ && layers_[l].isPacked() && layers_[l].span.end <= reach;
  }
  if (packedOnly_ && scratch_->lockCount < layerCount_) {
    scratch_->locks = std::make_unique<std::atomic<bool>[]>(layerCount_);
    scratch_->lockCount = layerCount_;
  }
}

void setPairForces(const PairList& list, const forces::InteractionTable& table, ParticleStore& s) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, s.size(), 16384), [&](const auto& r) {
    std::fill(s.f.begin() + static_cast<std::ptrdiff_t>(r.begin()),
              s.f.begin() + static_cast<std::ptrdiff_t>(r.end()), Force{});
  });
  const auto layers = list.layers();
  if (!list.packedOnly_) return accumulatePairForces(list, table, s);
  // All layers at once: each adds its sums to the store in one pass, holding the locks
  // of its own layer and the next, so a slot gets at most two additions to zero, and
  // a + b == b + a in IEEE arithmetic: the phases' result to the bit, in whatever order
  // the layers finish. Why: two phases of whole layers leave a thread idle at the
  // barrier whenever a phase's layers do not split evenly over the threads (15 layers:
  // 8 and 7), a twelfth of the kernel's time on two threads. Handed out in the phases'
  // order, even layers then odd ones (one thread runs them as the phases did): in
  // layer order the 256,000-atom liquid on two threads was 1-2% slower, in this order
  // it is not. (Storing instead of zeroing and adding, the first of a slot's two
  // writers storing, was no faster: docs/benchmarks.md.)
  const Simd simd = simdInUse();
  std::atomic<bool>* locks = list.scratch_->locks.get();
  const std::size_t evens = (layers.size() + 1) / 2;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, layers.size(), 1), [&](const auto& range) {
    std::vector<float>& sums = list.scratch_->perThread.local().sums;
    for (std::size_t p = range.begin(); p != range.end(); ++p) {
      const std::size_t l = p < evens ? 2 * p : 2 * (p - evens) + 1;
      layerForces(simd, layers[l], table, s, sums, {locks + l, l + 1 < layers.size() ? 2u : 1u});
    }
  });
}

void accumulatePairForces(const PairList& list, const forces::InteractionTable& table, ParticleStore& s) {
  const auto layers = list.layers();
  const Simd simd = simdInUse();
  // Phase by phase: a layer writes to its own slots and the next layer's, which no other
  // layer of its phase touches; each slot's force is summed in slot and phase order.
  for (const std::vector<std::uint32_t>& phase : list.phases()) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, phase.size(), 1), [&](const auto& range) {
      std::vector<float>& sums = list.scratch_->perThread.local().sums;
      for (std::size_t p = range.begin(); p != range.end(); ++p) layerForces(simd, layers[phase[p]], table, s, sums);
    });
  }
}

void accumulatePairForces(const neighbors::CellGrid& grid, const forces::InteractionTable& table,
                          ParticleStore& s) {
  PairList list;
  list.build(grid, table, s, 0.0f);
  accumulatePairForces(list, table, s);
}

void referencePairForces(const forces::InteractionTable& table, const ParticleStore& s,
                         std::vector<double>& fx, std::vector<double>& fy, std::vector<double>& fz) {
  const std::size_t n = s.size();
  fx.assign(n, 0); fy.assign(n, 0); fz.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      const forces::Interaction& in = table.interaction(s.material[i], s.material[j]);
      const double dx = double(s.px[j]) - s.px[i], dy = double(s.py[j]) - s.py[i],
                   dz = double(s.pz[j]) - s.pz[i];
      const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
      if (r >= forces::cutoff(in.function)) continue;
      const double inv = r > 0 ? 1.0 / r : 0.0;
      const double nx = dx * inv, ny = dy * inv, nz = dz * inv;
      const double dvx = double(s.vx[j]) - s.vx[i], dvy = double(s.vy[j]) - s.vy[i],
                   dvz = double(s.vz[j]) - s.vz[i];
      const double vn = dvx * nx + dvy * ny + dvz * nz;
      const double along = -forces::evaluate(in.function, r) + in.relativeVelocity * vn;
      const double gx = along * nx + in.damping * dvx, gy = along * ny + in.damping * dvy,
                   gz = along * nz + in.damping * dvz;
      fx[i] += gx; fy[i] += gy; fz[i] += gz;
      fx[j] -= gx; fy[j] -= gy; fz[j] -= gz;
    }
}

}  // namespace softsub::fluid
