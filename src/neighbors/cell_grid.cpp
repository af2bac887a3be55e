#include "neighbors/cell_grid.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

namespace softsub::neighbors {

namespace {

// Exact sums of cell coordinates and their squares (GCC and Clang; __extension__ keeps
// -Wpedantic quiet).
__extension__ typedef unsigned __int128 U128;

constexpr int kBits = CellGrid::kKeyBits;
constexpr std::uint64_t kMask = (std::uint64_t{1} << kBits) - 1;
constexpr std::uint64_t kEmpty = ~std::uint64_t{0};

// floor(x / h) as an integer, safe for any float (NaN and huge values included):
// values are clamped far beyond any useful range before the conversion. The floor is
// a truncation and a correction: std::floor is a libm call in the baseline build (no
// SSE4.1 rounding instruction), a third of the cost of a rebuild's keys. Clamping to
// whole numbers first gives the same integers as flooring first.
inline std::int64_t cellCoord(float x, float invH) {
  double v = static_cast<double>(x) * static_cast<double>(invH);
  if (!(v > -1e15)) v = -1e15;  // also catches NaN
  if (v > 1e15) v = 1e15;
  const auto t = static_cast<std::int64_t>(v);  // toward zero; exact below 2^53
  return t - static_cast<std::int64_t>(static_cast<double>(t) > v);
}

// A cell coordinate counted from the origin, wrapped to 21 bits.
inline std::uint64_t wrappedCoord(float x, float invH, std::int64_t origin) {
  return static_cast<std::uint64_t>(cellCoord(x, invH) - origin) & kMask;
}

inline std::uint64_t pack(std::uint64_t x, std::uint64_t y, std::uint64_t z) {
  return (z << (2 * kBits)) | (y << kBits) | x;
}

inline std::uint64_t hashKey(std::uint64_t k) {
  k ^= k >> 31;
  k *= 0x9E3779B97F4A7C15ull;
  k ^= k >> 29;
  return k;
}

// The 13 forward offsets of a half shell in key fields (major, middle, minor: (dz, dy, dx)
// when the layers run along z), in increasing key order for
// non-wrapping cells, so contiguous neighbours merge into one slot range.
constexpr std::array<std::array<int, 3>, 13> kForward = {{
    {0, 0, 1},
    {0, 1, -1}, {0, 1, 0}, {0, 1, 1},
    {1, -1, -1}, {1, -1, 0}, {1, -1, 1},
    {1, 0, -1}, {1, 0, 0}, {1, 0, 1},
    {1, 1, -1}, {1, 1, 0}, {1, 1, 1},
}};
// The first offset of each row of kForward (the same major and middle field).
constexpr std::array<std::size_t, 5> kRowOffset = {0, 1, 4, 7, 10};

}  // namespace

void CellGrid::rebuild(ParticleStore& store, float cellSize) {
  ownWork_.reserve(workBytes(store.size()));
  rebuild(store, cellSize, ownWork_.bytes());
}

void CellGrid::rebuild(ParticleStore& store, float cellSize, std::span<std::byte> work) {
  const std::size_t n = store.size();
  if (work.size() < workBytes(n) || reinterpret_cast<std::uintptr_t>(work.data()) % 8 != 0)
    throw std::invalid_argument("CellGrid::rebuild: the work memory is too small or not 8-byte aligned");
  const float oldCellSize = cellSize_;
  const std::array<std::int64_t, 3> oldOrigin = origin_;
  const std::array<int, 3> oldAxes = axes_;
  const bool oldTorus = torus_;
  cellSize_ = cellSize;
  const float invH = 1.0f / cellSize;
  n_ = n;
  keys_ = reuseStorageAs<std::uint64_t>(work.data(), n);
  order_ = reuseStorageAs<std::uint32_t>(work.data() + n * 8, n);
  using Range = tbb::blocked_range<std::size_t>;
  // The lowest and highest cell coordinates (exact, so the same for any split; a NaN
  // counts as the lowest possible). Coordinates are counted from the lowest: when every
  // axis spans fewer than 2^21 - 1 cells nothing wraps (the usual case), so the order is
  // that of the true cell coordinates and no hash of cells is needed.
  struct Span {
    std::array<std::int64_t, 3> lo{INT64_MAX, INT64_MAX, INT64_MAX}, hi{INT64_MIN, INT64_MIN, INT64_MIN};
    void add(const Span& o) {
      for (int a = 0; a < 3; ++a) {
        lo[a] = std::min(lo[a], o.lo[a]);
        hi[a] = std::max(hi[a], o.hi[a]);
      }
    }
  };
  const Span span = tbb::parallel_reduce(
      Range(0, n, 8192), Span{},
      [&](const Range& r, Span sp) {
        const float* p[3] = {store.px.data(), store.py.data(), store.pz.data()};
        for (int a = 0; a < 3; ++a) {
          float lo = INFINITY, hi = -INFINITY;
          bool nan = false;
          for (std::size_t i = r.begin(); i != r.end(); ++i) {
            const float x = p[a][i];
            nan = nan || !(x == x);
            lo = std::min(lo, x);
            hi = std::max(hi, x);
          }
          // floor is monotonic: the extreme coordinates are those of the extreme values.
          sp.lo[a] = std::min(sp.lo[a], nan ? cellCoord(NAN, invH) : cellCoord(lo, invH));
          sp.hi[a] = std::max(sp.hi[a], cellCoord(hi, invH));
        }
        return sp;
      },
      [](Span a, const Span& b) {
        a.add(b);
        return a;
      });
  torus_ = false;
  for (int a = 0; a < 3; ++a) {
    origin_[a] = n > 0 ? span.lo[a] : 0;
    extent_[a] = n > 0 ? span.hi[a] - span.lo[a] : 0;
    if (n > 0 && span.hi[a] - span.lo[a] >= static_cast<std::int64_t>(kMask)) torus_ = true;
  }
  // Keys in parallel over fixed blocks (each key is written once), first as (z, y, x),
  // with each axis's sums of cell coordinates and of their squares: exact integers, so
  // the same for any split and any particle order.
  struct Moments {
    std::array<U128, 3> sum{}, squares{};
    void add(const Moments& o) {
      for (int a = 0; a < 3; ++a) {
        sum[a] += o.sum[a];
        squares[a] += o.squares[a];
      }
    }
  };
  const Moments moments = tbb::parallel_reduce(
      Range(0, n, 8192), Moments{},
      [&](const Range& r, Moments m) {
        for (std::size_t b = r.begin(); b < r.end(); b += 8192) {
          std::array<std::uint64_t, 3> sum{}, squares{};  // 8192 * (2^21)^2 fits
          for (std::size_t i = b; i < std::min(r.end(), b + 8192); ++i) {
            const std::uint64_t c[3] = {wrappedCoord(store.px[i], invH, origin_[0]),
                                        wrappedCoord(store.py[i], invH, origin_[1]),
                                        wrappedCoord(store.pz[i], invH, origin_[2])};
            keys_[i] = pack(c[0], c[1], c[2]);
            for (int a = 0; a < 3; ++a) {
              sum[a] += c[a];
              squares[a] += c[a] * c[a];
            }
          }
          for (int a = 0; a < 3; ++a) {
            m.sum[a] += sum[a];
            m.squares[a] += squares[a];
          }
        }
        return m;
      },
      [](Moments a, const Moments& b) {
        a.add(b);
        return a;
      });
  // The layers' axis (the key's major field). Layers are the unit of parallel work, so
  // a scene flat in z (a dam in the x-y plane) must not get one or two of them. The
  // spread that decides is the variance of the cell coordinates, not the bounding box,
  // so a few particles flung far (a splash) do not turn a pool's layers on their side:
  // z, unless y's variance is 2.25 times z's plus one cell squared (a standard deviation
  // half as large again), and then x likewise against the one chosen. The margin keeps a
  // scene about as wide as deep on z. Exact integers of the positions alone: a checkpoint
  // restore rebuilds the same order. (n^2 var = n sum c^2 - (sum c)^2, below 2^107.)
  std::array<U128, 3> spread{};
  const U128 count = n;
  for (int a = 0; a < 3; ++a) spread[a] = count * moments.squares[a] - moments.sum[a] * moments.sum[a];
  int major = 2;
  for (const int a : {1, 0})
    if (4 * spread[a] >= 9 * spread[major] + 4 * count * count) major = a;
  if (fixedAxis_ >= 0 && fixedAxis_ < 3) major = fixedAxis_;
  axes_ = major == 2 ? std::array<int, 3>{0, 1, 2} : major == 1 ? std::array<int, 3>{0, 2, 1} : std::array<int, 3>{1, 2, 0};
  if (major != 2)
    tbb::parallel_for(Range(0, n, 8192), [&](const Range& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) {
        const std::uint64_t k = keys_[i];
        const std::uint64_t c[3] = {k & kMask, (k >> kBits) & kMask, k >> (2 * kBits)};
        keys_[i] = pack(c[axes_[0]], c[axes_[1]], c[axes_[2]]);
      }
    });
  // Whether the keys are already in order: a logical "and", the same for any split.
  const bool sorted = tbb::parallel_reduce(
      Range(1, std::max<std::size_t>(n, 1), 8192), true,
      [&](const Range& r, bool ok) {
        for (std::size_t i = r.begin(); i != r.end() && ok; ++i) ok = keys_[i] >= keys_[i - 1];
        return ok;
      },
      [](bool a, bool b) { return a && b; });
  reordered_ = !sorted;
  Previous previous;
  previous.valid = !torus_ && !oldTorus && oldCellSize == cellSize && oldAxes == axes_ && !cellStart_.empty() &&
                   cellStart_.back() == n;
  for (int f = 0; f < 3; ++f) previous.shift[f] = oldOrigin[axes_[f]] - origin_[axes_[f]];
  if (!sorted) sortKeys(previous);
  buildCells();
  if (torus_) buildHash();
  // The keys are dead now: their memory is the store's scratch for its integer arrays.
  if (!sorted) store.permute({order_, n}, {reuseStorageAs<std::uint32_t>(work.data(), n), n});
  keys_ = nullptr;
  order_ = nullptr;
}

// The 13 forward cells lie in 5 rows of constant (middle, major) key field; since cells
// are sorted by key and each row's target keys grow with c, one cursor per offset walks the
// sorted cell keys (amortised O(1) per lookup when cells come in order; a jump seeks).
// Offsets that wrap around the 21-bit torus use the hash table instead.
std::span<const SlotRange> CellGrid::ForwardRanges::of(std::size_t c) {
  const CellGrid& g = *grid_;
  const std::size_t cells = g.cellCount();
  const std::uint64_t* keys = g.cellKey_.data();
  // After a jump every cursor seeks (lower_bound) the first time it is used again.
  if (previous_ == SIZE_MAX || c != previous_ + 1) unseeked_ = (1u << kForward.size()) - 1;
  previous_ = c;
  const std::uint64_t k = keys[c];
  const std::uint64_t x = k & kMask, y = (k >> kBits) & kMask, z = k >> (2 * kBits);
  std::size_t n = 0;
  // Appends a slot range, merged with the last one where they touch.
  const auto append = [&](SlotRange r) {
    if (n > 0 && ranges_[n - 1].end == r.begin) ranges_[n - 1].end = r.end;
    else ranges_[n++] = r;
  };
  // The usual case, no offset wraps: the 13 cells are 5 rows of consecutive keys (x + 1
  // in the own row, x - 1 .. x + 1 in the 4 others), already in key order. One cursor
  // seeks each row's first key; the row's cells present follow it as consecutive cells,
  // so their slots are one range.
  const bool inside = x > 0 && x < kMask && y > 0 && y < kMask && z < kMask;
  if (inside) {
    for (std::size_t row = 0; row < kRowOffset.size(); ++row) {
      const std::size_t o = kRowOffset[row];  // the row's first offset: its cursor
      const auto& off = kForward[o];
      const std::uint64_t nk = pack(x + static_cast<std::uint64_t>(off[2]), y + static_cast<std::uint64_t>(off[1]),
                                    z + static_cast<std::uint64_t>(off[0]));
      std::size_t cur = cursor_[o];
      if (((unseeked_ >> o) & 1u) != 0 || (cur > 0 && keys[cur - 1] >= nk)) {
        cur = static_cast<std::size_t>(std::lower_bound(keys, keys + cells, nk) - keys);
        unseeked_ &= ~(1u << o);
      }
      const std::size_t from = cur;
      while (cur < cells && keys[cur] < nk) ++cur;
      steps_ += cur - from;
      const std::uint64_t width = row == 0 ? 1 : 3;
      // The row's other offsets' cursors too, in case the next cell takes the path below.
      for (std::size_t t = 0; t < width; ++t) cursor_[o + t] = cur;
      const std::size_t first = cur;
      while (cur < cells && keys[cur] < nk + width) ++cur;  // keys ascend and are distinct
      if (cur > first) append({g.cellStart_[first], g.cellStart_[cur]});
    }
    return {ranges_.data(), n};
  }
  // Otherwise offset by offset; wrapping ones go through the hash table (torus) or find
  // nothing.
  std::array<std::uint32_t, 13> found;  // the first nf are set
  std::size_t nf = 0;
  for (std::size_t o = 0; o < kForward.size(); ++o) {
    const auto& off = kForward[o];
    const std::uint64_t nx = x + static_cast<std::uint64_t>(off[2]);
    const std::uint64_t ny = y + static_cast<std::uint64_t>(off[1]);
    const std::uint64_t nz = z + static_cast<std::uint64_t>(off[0]);
    const bool wraps = ((nx | ny | nz) & ~kMask) != 0;
    const std::uint64_t nk = pack(nx & kMask, ny & kMask, nz & kMask);
    std::int64_t cell = -1;
    if (wraps) {
      // Without wrapping (no torus) a coordinate past the ends is no cell at all.
      cell = g.torus_ ? g.findCell(nk) : -1;
    } else {
      std::size_t cur = cursor_[o];  // a local: the walk below stays in a register
      const bool unseeked = (unseeked_ >> o) & 1u;
      // After a jump. (The second test is defensive: for cells in ascending order an
      // offset's targets only grow, and wrapped targets never move the cursor.)
      if (unseeked || (cur > 0 && keys[cur - 1] >= nk)) {
        cur = static_cast<std::size_t>(std::lower_bound(keys, keys + cells, nk) - keys);
        unseeked_ &= ~(1u << o);
      }
      const std::size_t from = cur;
      while (cur < cells && keys[cur] < nk) ++cur;
      steps_ += cur - from;
      if (cur < cells && keys[cur] == nk) cell = static_cast<std::int64_t>(cur);
      cursor_[o] = cur;
    }
    if (cell >= 0 && static_cast<std::size_t>(cell) != c) found[nf++] = static_cast<std::uint32_t>(cell);
  }
  // At most 13 entries: an insertion sort (cell indices are distinct: keys differ).
  for (std::size_t a = 1; a < nf; ++a)
    for (std::size_t b = a; b > 0 && found[b - 1] > found[b]; --b) std::swap(found[b - 1], found[b]);
  for (std::size_t f = 0; f < nf; ++f) append({g.cellStart_[found[f]], g.cellStart_[found[f] + 1]});
  return {ranges_.data(), n};
}

namespace {

// Orders the pairs (keys[i], order[i]) by key, then by order, in place. With `order`
// the slots the keys came from, this is the stable sort by key. Gives up (returns
// false, the pairs partly sorted) once it has moved more than `budget` pairs in all.
bool insertionSort(std::uint64_t* keys, std::uint32_t* order, std::size_t n, std::size_t budget = SIZE_MAX) {
  for (std::size_t i = 1; i < n; ++i) {
    const std::uint64_t k = keys[i];
    const std::uint32_t o = order[i];
    std::size_t j = i;
    for (; j > 0 && (keys[j - 1] > k || (keys[j - 1] == k && order[j - 1] > o)); --j) {
      keys[j] = keys[j - 1];
      order[j] = order[j - 1];
    }
    keys[j] = k;
    order[j] = o;
    if (i - j > budget) return false;
    budget -= i - j;
  }
  return true;
}

// The same order by an in-place most-significant-digit radix sort (American flag sort):
// bytes from `shift` down, skipping those in which no key differs (`varying`); small
// buckets finish by insertion, and buckets of equal keys by slot. In place, so a
// rebuild needs no sort buffer (12 bytes a particle, as an LSD radix sort would).
void radixSort(std::uint64_t* keys, std::uint32_t* order, std::size_t n, int shift, std::uint64_t varying,
               bool parallel) {
  constexpr std::size_t kSmall = 48;
  if (n <= kSmall) {
    insertionSort(keys, order, n);
    return;
  }
  while (shift >= 0 && ((varying >> shift) & 0xFF) == 0) shift -= 8;
  if (shift < 0) {  // every key equal: by slot only
    std::sort(order, order + n);
    return;
  }
  std::array<std::size_t, 257> start{};
  for (std::size_t i = 0; i < n; ++i) ++start[((keys[i] >> shift) & 0xFF) + 1];
  for (std::size_t b = 1; b < start.size(); ++b) start[b] += start[b - 1];
  std::array<std::size_t, 256> next;
  std::copy(start.begin(), start.end() - 1, next.begin());
  // Each element not in its bucket's range is carried around its cycle of displaced
  // elements until the one that belongs at the starting position comes back.
  for (std::size_t b = 0; b < 256; ++b) {
    while (next[b] < start[b + 1]) {
      std::uint64_t k = keys[next[b]];
      std::uint32_t o = order[next[b]];
      for (std::size_t d = (k >> shift) & 0xFF; d != b; d = (k >> shift) & 0xFF) {
        const std::size_t to = next[d]++;
        std::swap(k, keys[to]);
        std::swap(o, order[to]);
      }
      keys[next[b]] = k;
      order[next[b]] = o;
      ++next[b];
    }
  }
  // The buckets are independent: sorted in parallel (the order is total, so the result
  // is the same for any split). Only the first level splits: below it the buckets are
  // small enough for one task.
  const auto sortBucket = [&](std::size_t b) {
    if (start[b + 1] - start[b] > 1)
      radixSort(keys + start[b], order + start[b], start[b + 1] - start[b], shift - 8, varying, false);
  };
  if (parallel)
    tbb::parallel_for(std::size_t{0}, std::size_t{256}, sortBucket);
  else
    for (std::size_t b = 0; b < 256; ++b) sortBucket(b);
}

}  // namespace

// Stable sort of the particle slots by key. Nearly sorted input (the usual case from
// one substep to the next) takes an insertion sort; otherwise the in-place radix sort.
// Both run in parallel: the order (key, then slot) is total, so any split of the work
// gives the same result.
void CellGrid::sortKeys(const Previous& previous) {
  using Range = tbb::blocked_range<std::size_t>;
  const std::size_t n = n_;
  std::uint64_t* keys = keys_;
  std::uint32_t* order = order_;
  if (previous.valid && sortMovers(previous)) return;
  tbb::parallel_for(Range(0, n, 8192), [&](const Range& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) order[i] = static_cast<std::uint32_t>(i);
  });

  // Insertion sort while the data is nearly sorted; it gives up (the radix sort then
  // finishes from wherever it stopped, still correct) once it has moved more than a few
  // slots per particle, so its worst case stays O(n). Fixed blocks are sorted first, in
  // parallel; one pass over the whole array then moves only the pairs that crossed a
  // block boundary.
  const std::size_t descents = tbb::parallel_reduce(
      Range(1, std::max<std::size_t>(n, 1), 8192), std::size_t{0},
      [&](const Range& r, std::size_t d) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) d += keys[i] < keys[i - 1];
        return d;
      },
      std::plus<>());
  if (descents * 32 < n) {
    constexpr std::size_t kBlock = 16384;
    const bool blocks = tbb::parallel_reduce(
        Range(0, (n + kBlock - 1) / kBlock, 1), true,
        [&](const Range& r, bool ok) {
          for (std::size_t b = r.begin(); b != r.end() && ok; ++b) {
            const std::size_t from = b * kBlock, len = std::min(kBlock, n - from);
            ok = insertionSort(keys + from, order + from, len, 8 * len);
          }
          return ok;
        },
        [](bool a, bool b) { return a && b; });
    if (blocks && insertionSort(keys, order, n, 8 * n)) return;
  }

  std::uint64_t allOr = 0, allAnd = ~std::uint64_t{0};
  for (std::size_t i = 0; i < n; ++i) {
    allOr |= keys[i];
    allAnd &= keys[i];
  }
  radixSort(keys, order, n, 56, allOr ^ allAnd, true);
}

// The usual rebuild of a moving fluid: the slots are still in the order of the last
// rebuild's cells, and a few particles (1-3% at a rebuild of the 200,000 seed pool) have
// changed cell. Those that stayed keep their old cell's key, so they are already in
// order; the movers are taken out, sorted by (key, slot), and merged back from the end.
// The same order (key, then slot) as the sorts below, in O(n + m log m) with one serial
// pass each way; the sorts below took 2-3 times as long, most of it serial (the radix
// sort's first level). Declines (false, keys untouched) when more than n / 32 moved.
bool CellGrid::sortMovers(const Previous& previous) {
  using Range = tbb::blocked_range<std::size_t>;
  const std::size_t n = n_, cells = cellCount();
  std::uint64_t* keys = keys_;
  std::uint32_t* order = order_;
  // The old cell's key in this rebuild's frame, or kEmpty when a field falls outside
  // (no particle of that cell can have stayed). Adding the same shift to every cell's
  // fields keeps their order, so the keys of the particles that stayed ascend.
  const auto oldKey = [&](std::size_t c) {
    const std::uint64_t k = cellKey_[c];
    const std::uint64_t field[3] = {k & kMask, (k >> kBits) & kMask, k >> (2 * kBits)};
    std::uint64_t moved[3];
    for (int f = 0; f < 3; ++f) {
      const std::int64_t v = static_cast<std::int64_t>(field[f]) + previous.shift[f];
      if (v < 0 || v > static_cast<std::int64_t>(kMask)) return kEmpty;
      moved[f] = static_cast<std::uint64_t>(v);
    }
    return pack(moved[0], moved[1], moved[2]);
  };
  const std::size_t moved = tbb::parallel_reduce(
      Range(0, cells, 1024), std::size_t{0},
      [&](const Range& r, std::size_t m) {
        for (std::size_t c = r.begin(); c != r.end(); ++c) {
          const std::uint64_t k = oldKey(c);
          for (std::uint32_t i = cellStart_[c]; i < cellStart_[c + 1]; ++i) m += keys[i] != k;
        }
        return m;
      },
      std::plus<>());
  if (moved * 32 > n) return false;
  if (movers_.capacity() < moved) movers_.reserve(moved);  // exactly: resize alone would double it
  movers_.resize(moved);
  // The particles that stayed move to the front, in slot order; the movers aside.
  std::size_t stayed = 0, out = 0;
  for (std::size_t c = 0; c < cells; ++c) {
    const std::uint64_t k = oldKey(c);
    for (std::uint32_t i = cellStart_[c]; i < cellStart_[c + 1]; ++i) {
      if (keys[i] == k) {
        keys[stayed] = k;
        order[stayed++] = i;
      } else {
        movers_[out++] = {keys[i], i};
      }
    }
  }
  std::sort(movers_.begin(), movers_.end());
  // Merged from the back: the largest of the two remaining heads goes to the last free
  // place, which is never ahead of the stayed particles still to be read.
  std::size_t a = stayed, b = moved, w = n;
  while (b > 0) {
    const auto& m = movers_[b - 1];
    --w;
    if (a > 0 && (keys[a - 1] > m.first || (keys[a - 1] == m.first && order[a - 1] > m.second))) {
      --a;
      keys[w] = keys[a];
      order[w] = order[a];
    } else {
      --b;
      keys[w] = m.first;
      order[w] = m.second;
    }
  }
  return true;
}

void CellGrid::buildCells() {
  const std::size_t n = n_;
  cellStart_.clear();
  cellKey_.clear();
  layers_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    if (i == 0 || keys_[i] != keys_[i - 1]) {
      cellStart_.push_back(static_cast<std::uint32_t>(i));
      cellKey_.push_back(keys_[i]);
      if (i == 0 || (keys_[i] >> (2 * kBits)) != (keys_[i - 1] >> (2 * kBits)))
        layers_.push_back({static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(i)});
    }
    layers_.back().end = static_cast<std::uint32_t>(i + 1);
  }
  cellStart_.push_back(static_cast<std::uint32_t>(n));
  // Phases of the layers (see layersByPhase). Layer k's pairs reach layer k + 1 only
  // when their major-axis coordinates are consecutive; the last layer reaches the first
  // only across the wrap (coordinate 2^21 - 1 next to 0).
  for (auto& p : phases_) p.clear();
  phases_.resize(3);
  const std::size_t count = layers_.size();
  const bool wraps = count > 2 && (keys_[layers_.front().begin] >> (2 * kBits)) == 0 &&
                     (keys_[layers_.back().begin] >> (2 * kBits)) == kMask;
  for (std::size_t k = 0; k < count; ++k) {
    const bool alone = wraps && count % 2 == 1 && k + 1 == count;
    phases_[alone ? 2 : k % 2].push_back(static_cast<std::uint32_t>(k));
  }
}

void CellGrid::buildHash() {
  const std::size_t cells = cellKey_.size();
  std::size_t cap = 16;
  while (cap < 2 * cells) cap *= 2;
  hashKeys_.assign(cap, kEmpty);
  hashCells_.resize(cap);
  hashMask_ = cap - 1;
  for (std::size_t c = 0; c < cells; ++c) {
    std::uint64_t h = hashKey(cellKey_[c]) & hashMask_;
    while (hashKeys_[h] != kEmpty) h = (h + 1) & hashMask_;
    hashKeys_[h] = cellKey_[c];
    hashCells_[h] = static_cast<std::uint32_t>(c);
  }
}

std::int64_t CellGrid::findCell(std::uint64_t key) const {
  std::uint64_t h = hashKey(key) & hashMask_;
  while (true) {
    const std::uint64_t k = hashKeys_[h];
    if (k == key) return hashCells_[h];
    if (k == kEmpty) return -1;
    h = (h + 1) & hashMask_;
  }
}

std::size_t CellGrid::memoryBytes() const {
  std::size_t phases = 0;
  for (const auto& p : phases_) phases += p.capacity() * 4;
  return ownWork_.size() + cellStart_.capacity() * 4 + cellKey_.capacity() * 8 +
         layers_.capacity() * sizeof(SlotRange) + phases_.capacity() * sizeof(phases_[0]) + phases +
         hashKeys_.capacity() * 8 + hashCells_.capacity() * 4 + movers_.capacity() * sizeof(movers_[0]);
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> bruteForcePairs(const ParticleStore& s,
                                                                     float cutoff) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  const float c2 = cutoff * cutoff;
  for (std::uint32_t i = 0; i < s.size(); ++i)
    for (std::uint32_t j = i + 1; j < s.size(); ++j) {
      const float dx = s.px[j] - s.px[i], dy = s.py[j] - s.py[i], dz = s.pz[j] - s.pz[i];
      if (dx * dx + dy * dy + dz * dz < c2) out.emplace_back(i, j);
    }
  return out;
}

}  // namespace softsub::neighbors
