#include "solver/list_guard.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace softsub::solver {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// The first index in [0, n) where `before` is false; `before` holds on a prefix. Not
// std::ranges::partition_point over std::views::iota: clang 14 (the fuzz build) cannot
// compile libstdc++ 12's <ranges>.
template <class Pred>
std::size_t partitionPoint(std::size_t n, Pred before) {
  std::size_t lo = 0;
  while (n > 0) {
    const std::size_t half = n / 2;
    if (before(lo + half)) {
      lo += half + 1;
      n -= half + 1;
    } else {
      n = half;
    }
  }
  return lo;
}

}  // namespace

// Per block: the box of its displacements (low minor, middle, major, then high), its
// radius (negative: no particle); per slab (one block coordinate on the major axis):
// its first cell, then one past the last slab's.
struct ListGuard::Scratch {
  std::vector<float> box, radius;
  std::vector<std::uint32_t> slabCell;
};

ListGuard::ListGuard() : scratch_(std::make_unique<Scratch>()) {}
ListGuard::~ListGuard() = default;
ListGuard::ListGuard(ListGuard&&) noexcept = default;
ListGuard& ListGuard::operator=(ListGuard&&) noexcept = default;

void ListGuard::hold(float reach, float skin) {
  reach_ = reach;
  skin_ = skin;
  laidOut_ = false;
  blocks_ = 0;
}

void ListGuard::layOut(const neighbors::CellGrid& grid) {
  laidOut_ = true;
  blocks_ = 0;
  const std::size_t nc = grid.cellCount();
  if (nc == 0 || grid.wraps() || !(skin_ > 0) || !std::isfinite(reach_)) return;
  const std::array<std::uint32_t, 3> hi = grid.fieldsMax();
  // Blocks of 2, 4, 8 ... cells a side, until there are no more blocks than cells (a
  // scene spread thin): a wider block is as valid, only less often conclusive.
  widthShift_ = 1;
  for (;;) {
    double product = 1;
    for (int a = 0; a < 3; ++a) {
      dims_[a] = (hi[a] >> widthShift_) + 1;
      product *= static_cast<double>(dims_[a]);
    }
    if (product <= static_cast<double>(nc + 64)) break;
    ++widthShift_;
  }
  blocks_ = dims_[0] * dims_[1] * dims_[2];
  Scratch& sc = *scratch_;
  sc.box.resize(6 * blocks_);
  sc.radius.resize(blocks_);
  // Cells come in key order, the major axis most significant: each slab is a run, found
  // by a binary search (no pass over the cells).
  sc.slabCell.resize(dims_[2] + 1);
  for (std::size_t k = 0; k <= dims_[2]; ++k) {
    const auto before = [&](std::size_t c) { return (grid.cellFields(c)[2] >> widthShift_) < k; };
    sc.slabCell[k] = static_cast<std::uint32_t>(partitionPoint(nc, before));
  }
}

bool ListGuard::proves(const neighbors::CellGrid& grid, const ParticleStore& s, const float* ref,
                       std::size_t hint) {
  if (!laidOut_) layOut(grid);
  if (blocks_ == 0) return false;
  const std::size_t n = s.size();
  // The grid must be the list's: its cells reach + skin wide, over this store's slots.
  const std::size_t nc = grid.cellCount();
  if (nc == 0 || grid.cell(nc - 1).end != n || grid.cellSize() < reach_ + skin_) return false;
  const float* __restrict px = s.px.data();
  const float* __restrict py = s.py.data();
  const float* __restrict pz = s.pz.data();
  const float* __restrict rx = ref;
  const float* __restrict ry = ref + n;
  const float* __restrict rz = ref + 2 * n;
  Scratch& sc = *scratch_;
  float* box = sc.box.data();
  float* radius = sc.radius.data();
  const std::size_t d0 = dims_[0], d1 = dims_[1], d2 = dims_[2], perSlab = d0 * d1;
  const int w = widthShift_;
  const auto blockOf = [&](std::size_t c) {
    const std::array<std::uint32_t, 3> k = grid.cellFields(c);
    return (static_cast<std::size_t>(k[2] >> w) * d1 + (k[1] >> w)) * d0 + (k[0] >> w);
  };
  const auto centre = [&](std::size_t b, int a) { return 0.5f * (box[6 * b + a] + box[6 * b + 3 + a]); };
  // Rounding: the sums below err by a few units in the last place of the skin, covered
  // by a margin of skin * 1e-5; each displacement x - ref and what is computed from it
  // errs by a few units in the last place of the displacement itself (large when a lump
  // has fallen far), covered by 2^-20 of each block's largest |d| (its box's largest
  // components, summed over the axes, bound |d|).
  const float margin = skin_ * (1.0f - 1e-5f);
  const auto error = [&](std::size_t b) {
    float m = 0;
    for (int a = 0; a < 3; ++a) m += std::max(std::abs(box[6 * b + a]), std::abs(box[6 * b + 3 + a]));
    return 0x1p-20f * m;
  };
  // Blocks a and b (both holding particles) can have no pair that closed by the skin.
  const auto apart = [&](std::size_t a, std::size_t b) {
    const float ex = centre(a, 0) - centre(b, 0), ey = centre(a, 1) - centre(b, 1),
                ez = centre(a, 2) - centre(b, 2);
    return radius[a] + radius[b] + std::sqrt(ex * ex + ey * ey + ez * ez) < margin - error(a) - error(b);
  };
  // Block (i0, i1, i2) against its touching blocks at major offset o2 (0: the forward
  // ones within the slab, and itself; 1: the nine in the next slab).
  const auto touching = [&](std::size_t i0, std::size_t i1, std::size_t i2, int o2) {
    const std::size_t a = (i2 * d1 + i1) * d0 + i0;
    if (radius[a] < 0) return true;
    if (o2 == 0 && !(2.0f * radius[a] < margin - 2.0f * error(a))) return false;
    for (int o1 = o2 == 0 ? 0 : -1; o1 <= 1; ++o1)
      for (int o0 = o2 == 0 && o1 == 0 ? 1 : -1; o0 <= 1; ++o0) {
        // Below 0 wraps to a huge value: out of range, as past the end.
        const std::size_t j0 = i0 + static_cast<std::size_t>(o0), j1 = i1 + static_cast<std::size_t>(o1),
                          j2 = i2 + static_cast<std::size_t>(o2);
        if (j0 >= d0 || j1 >= d1 || j2 >= d2) continue;
        const std::size_t b = (j2 * d1 + j1) * d0 + j0;
        if (radius[b] >= 0 && !apart(a, b)) return false;
      }
    return true;
  };
  std::atomic<bool> failed{false};

  // 1. Slab by slab: each block's box of displacements, then its radius around the
  // box's middle (the slab's particles still in cache), then its pairs within the slab.
  // A displacement that is not finite makes its block's radius infinite. False when a
  // pair fails.
  const auto slab = [&](std::size_t k) {
    for (std::size_t b = k * perSlab; b < (k + 1) * perSlab; ++b) {
      std::fill_n(box + 6 * b, 3, kInf);
      std::fill_n(box + 6 * b + 3, 3, -kInf);
      radius[b] = 0;
    }
    const std::size_t c0 = sc.slabCell[k], c1 = sc.slabCell[k + 1];
    for (std::size_t c = c0; c < c1; ++c) {
      const neighbors::SlotRange slots = grid.cell(c);
      float lx = kInf, ly = kInf, lz = kInf, hx = -kInf, hy = -kInf, hz = -kInf;
      bool finite = true;
      for (std::uint32_t i = slots.begin; i < slots.end; ++i) {
        const float dx = px[i] - rx[i], dy = py[i] - ry[i], dz = pz[i] - rz[i];
        finite &= dx * dx + dy * dy + dz * dz < kInf;
        lx = std::min(lx, dx), ly = std::min(ly, dy), lz = std::min(lz, dz);
        hx = std::max(hx, dx), hy = std::max(hy, dy), hz = std::max(hz, dz);
      }
      const std::size_t b = blockOf(c);
      float* bb = box + 6 * b;
      bb[0] = std::min(bb[0], lx), bb[1] = std::min(bb[1], ly), bb[2] = std::min(bb[2], lz);
      bb[3] = std::max(bb[3], hx), bb[4] = std::max(bb[4], hy), bb[5] = std::max(bb[5], hz);
      if (!finite) radius[b] = kInf;
    }
    for (std::size_t c = c0; c < c1; ++c) {
      const neighbors::SlotRange slots = grid.cell(c);
      const std::size_t b = blockOf(c);
      const float cx = centre(b, 0), cy = centre(b, 1), cz = centre(b, 2);
      float r2 = 0;
      for (std::uint32_t i = slots.begin; i < slots.end; ++i) {
        const float ex = px[i] - rx[i] - cx, ey = py[i] - ry[i] - cy, ez = pz[i] - rz[i] - cz;
        r2 = std::max(r2, ex * ex + ey * ey + ez * ez);
      }
      radius[b] = std::max(radius[b], r2);
    }
    // Empty blocks get -1; an infinite radius (a displacement not finite, even when
    // the box of that axis stayed empty) stays.
    for (std::size_t b = k * perSlab; b < (k + 1) * perSlab; ++b)
      if (radius[b] != kInf) radius[b] = box[6 * b] <= box[6 * b + 3] ? std::sqrt(radius[b]) : -1.0f;
    for (std::size_t i1 = 0; i1 < d1; ++i1)
      for (std::size_t i0 = 0; i0 < d0; ++i0)
        if (!touching(i0, i1, k, 0)) return false;
    return true;
  };
  // First the slab of the hinted slot (the largest displacement: where a failure is
  // most likely), alone, then the others in parallel.
  std::size_t first = d2;
  if (hint < n) {
    // The last cell starting at or before it.
    const std::size_t holder = partitionPoint(nc, [&](std::size_t c) { return grid.cell(c).begin <= hint; }) - 1;
    first = grid.cellFields(holder)[2] >> w;
    if (!slab(first)) return false;
  }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, d2, 1), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t k = r.begin(); k != r.end(); ++k) {
      if (failed.load(std::memory_order_relaxed)) return;
      if (k != first && !slab(k)) {
        failed.store(true, std::memory_order_relaxed);
        return;
      }
    }
  });
  if (failed.load()) return false;

  // 2. The pairs across neighbouring slabs.
  if (d2 > 1)
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, d2 - 1, 1),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t k = r.begin(); k != r.end(); ++k) {
                          if (failed.load(std::memory_order_relaxed)) return;
                          for (std::size_t i1 = 0; i1 < d1; ++i1)
                            for (std::size_t i0 = 0; i0 < d0; ++i0)
                              if (!touching(i0, i1, k, 1)) {
                                failed.store(true, std::memory_order_relaxed);
                                return;
                              }
                        }
                      });
  if (failed.load()) return false;

  // 3. Blocks that do not touch: any two displacements differ by at most the spread of
  // the block centres plus two block radii.
  float lo[3] = {kInf, kInf, kInf}, hi[3] = {-kInf, -kInf, -kInf}, largest = 0, largestError = 0;
  for (std::size_t b = 0; b < blocks_; ++b) {
    if (radius[b] < 0) continue;
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], centre(b, a));
      hi[a] = std::max(hi[a], centre(b, a));
    }
    largest = std::max(largest, radius[b]);
    largestError = std::max(largestError, error(b));
  }
  float spread2 = 0;
  for (int a = 0; a < 3; ++a) spread2 += (hi[a] - lo[a]) * (hi[a] - lo[a]);
  return std::sqrt(spread2) + 2.0f * largest < reach_ + margin - 2.0f * largestError;
}

std::size_t ListGuard::memoryBytes() const {
  if (!scratch_) return 0;  // moved from
  const Scratch& sc = *scratch_;
  return (sc.box.capacity() + sc.radius.capacity()) * sizeof(float) + sc.slabCell.capacity() * 4;
}

}  // namespace softsub::solver
