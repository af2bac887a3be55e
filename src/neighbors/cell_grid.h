#pragma once
/// The neighbour grid: particles sorted by cell, neighbour cells found by walking the
/// sorted cell keys. Memory is O(particles) whatever the spatial extent.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "core/particle_store.h"
#include "core/work_buffer.h"

namespace softsub::neighbors {

/// A half-open range [begin, end) of particle slots.
struct SlotRange {
  std::uint32_t begin = 0;
  std::uint32_t end = 0;
};

/// Uniform cell list; the caller picks the cell size (the solver: longest cutoff + skin).
///
/// Why this layout: cell coordinates, counted from the lowest occupied cell of each axis,
/// are wrapped to 21 bits per axis and packed into one 64-bit key (major, middle, minor
/// axis: (z, y, x) unless the particles spread clearly more along y or x, see
/// keyAxes()); they wrap only when an axis spans 2^21 - 1 cells or more (a particle
/// flung far away), and only then is a hash of the occupied cells built for the offsets
/// that wrap. Sorting particles by key puts each cell's particles next to each other and
/// keeps rows of cells contiguous, so the three cells (minor - 1 .. minor + 1) of a
/// neighbouring row usually form a single slot range. Wrapping can only make far-apart
/// cells share a key (then the distance test rejects their pairs); it never separates
/// true neighbours, and no array is ever sized by the spatial extent.
///
/// Each unordered pair of neighbouring cells is listed once (a half shell of 13
/// forward neighbours), so every particle pair within the cell size is visited exactly
/// once: the basis for applying Newton's third law.
class CellGrid {
 public:
  /// Bits of each coordinate in a cell's sort key (minor, middle, major from bit 0).
  static constexpr int kKeyBits = 21;
  /// The layers' axis is chosen by each rebuild from the particles' spread (keyAxes()).
  CellGrid() = default;
  /// The layers' axis fixed: 0 x, 1 y, 2 z (tests and tools that need a known layout);
  /// -1 chooses, as the default constructor does.
  explicit CellGrid(int layerAxis) : fixedAxis_(layerAxis) {}

  /// Sorts `store` by cell of size `cellSize` (> 0) and rebuilds the cell lists.
  /// Permutes the store only when the order changed, and then its forces come back zero
  /// (ParticleStore::permute). Works in a buffer of its own (no allocation once warmed
  /// up).
  void rebuild(ParticleStore& store, float cellSize);
  /// The same, working in `work` (at least workBytes(store.size()) bytes, 8-byte
  /// aligned; std::invalid_argument otherwise), whose contents it overwrites: the solver
  /// lends the memory of its list reference positions, dead during a rebuild.
  void rebuild(ParticleStore& store, float cellSize, std::span<std::byte> work);
  /// Bytes of work a rebuild of n particles needs: a sort key and a slot each.
  [[nodiscard]] static constexpr std::size_t workBytes(std::size_t n) { return n * 12; }

  /// Number of occupied cells.
  [[nodiscard]] std::size_t cellCount() const { return cellStart_.empty() ? 0 : cellStart_.size() - 1; }
  /// Slots of the particles in cell c.
  [[nodiscard]] SlotRange cell(std::size_t c) const {
    return {cellStart_[c], cellStart_[c + 1]};
  }
  /// Cell c's coordinates along the sort key's minor, middle and major axes (keyAxes()),
  /// counted from the lowest occupied cell of each: floor(position * (1 / cellSize()),
  /// the reciprocal rounded to float) of its particles at the last rebuild, less that
  /// of the lowest. Exact unless wraps().
  /// Non-decreasing along the major axis in cell order.
  [[nodiscard]] std::array<std::uint32_t, 3> cellFields(std::size_t c) const {
    constexpr std::uint64_t mask = (std::uint64_t{1} << kKeyBits) - 1;
    const std::uint64_t key = cellKey_[c];
    return {static_cast<std::uint32_t>(key & mask), static_cast<std::uint32_t>((key >> kKeyBits) & mask),
            static_cast<std::uint32_t>((key >> (2 * kKeyBits)) & mask)};
  }
  /// The largest cellFields() value along each key field (minor, middle, major) that
  /// the last rebuild's particles span. Exact unless wraps().
  [[nodiscard]] std::array<std::uint32_t, 3> fieldsMax() const {
    return {static_cast<std::uint32_t>(extent_[axes_[0]]), static_cast<std::uint32_t>(extent_[axes_[1]]),
            static_cast<std::uint32_t>(extent_[axes_[2]])};
  }
  /// Whether the last rebuild's coordinates wrapped (an axis spanning 2^21 - 1 cells or
  /// more): far-apart cells may then share a key.
  [[nodiscard]] bool wraps() const { return torus_; }
  /// Finds the slot ranges of a cell's forward neighbour cells (merged where
  /// contiguous). Pairs (i in cell c, j in these ranges) plus pairs i < j inside cell c
  /// are every candidate pair exactly once.
  ///
  /// Why a walker and not a stored table: the ranges are found by walking the sorted
  /// cell keys, one cursor per forward offset, which costs amortised O(1) per cell when
  /// cells are visited in ascending order. Each task of a parallel pass (the pair list:
  /// one layer each) walks its own cells, so the ranges are never stored (16 bytes a
  /// particle saved) and never found serially. Cheap to make: one per task.
  class ForwardRanges {
   public:
    explicit ForwardRanges(const CellGrid& grid) : grid_(&grid) {}
    /// Cell c's forward ranges, valid until the next call. Fastest when c is the cell
    /// after the previous call's; any order is correct.
    std::span<const SlotRange> of(std::size_t c);
    /// Cursor steps taken so far (tests: a walk stays short after a jump).
    [[nodiscard]] std::size_t steps() const { return steps_; }

   private:
    const CellGrid* grid_;
    std::size_t previous_ = SIZE_MAX;
    std::size_t steps_ = 0;
    std::uint32_t unseeked_ = 0;  // bit o: cursor o has not been placed since the last jump
    std::array<std::size_t, 13> cursor_{};
    std::array<SlotRange, 13> ranges_{};
  };
  /// Slot ranges of the layers: the cells of one coordinate on the sort key's major axis
  /// (keyAxes()[2]) are contiguous slots. A cell's forward neighbours lie in its own
  /// layer or the next one, so the pairs of layers k and k + 2 never share a particle: the
  /// basis for deterministic parallel work (layersByPhase).
  [[nodiscard]] std::span<const SlotRange> layers() const { return layers_; }
  /// The layers' indices grouped into phases: within a phase no two layers are
  /// neighbours, so tasks of one phase that write to their own layer and the next one
  /// never write to the same slot. Phases: even layers, odd layers, and, when the last
  /// layer wraps around to the first (an odd count of major-axis coordinates that meet
  /// across the 21-bit wrap), that last layer alone.
  [[nodiscard]] const std::vector<std::vector<std::uint32_t>>& layersByPhase() const { return phases_; }
  /// The physical axes (0 x, 1 y, 2 z) of the sort key's minor, middle and major field,
  /// as the last rebuild chose them: the major one is the layers' axis, z unless the
  /// particles spread clearly more along y or x (see rebuild in cell_grid.cpp).
  [[nodiscard]] std::array<int, 3> keyAxes() const { return axes_; }
  /// The cell size used by the last rebuild.
  [[nodiscard]] float cellSize() const { return cellSize_; }
  /// Whether the last rebuild had to reorder the store.
  [[nodiscard]] bool reordered() const { return reordered_; }

  /// Calls fn(i, j) for every candidate pair (i != j, each unordered pair once).
  template <class Fn>
  void forEachCandidatePair(Fn&& fn) const {
    ForwardRanges forward(*this);
    for (std::size_t c = 0; c < cellCount(); ++c) {
      const SlotRange own = cell(c);
      const std::span<const SlotRange> ranges = forward.of(c);
      for (std::uint32_t i = own.begin; i < own.end; ++i) {
        for (std::uint32_t j = i + 1; j < own.end; ++j) fn(i, j);
        for (const SlotRange& r : ranges)
          for (std::uint32_t j = r.begin; j < r.end; ++j) fn(i, j);
      }
    }
  }

  /// Bytes currently reserved by the grid's buffers.
  [[nodiscard]] std::size_t memoryBytes() const;

 private:
  // The cells of the last rebuild, in the keys of this one, for sortKeys(): set by
  // rebuild() before the new keys, valid when that rebuild's cells describe the same
  // slots (same count, cell size and key axes, no wrap).
  struct Previous {
    bool valid = false;
    std::array<std::int64_t, 3> shift{};  // added to each key field (minor, middle, major)
  };
  void sortKeys(const Previous& previous);
  bool sortMovers(const Previous& previous);
  void buildCells();
  void buildHash();
  [[nodiscard]] std::int64_t findCell(std::uint64_t key) const;

  float cellSize_ = 0;
  bool reordered_ = false;
  // During a rebuild: each slot's key and, once sorted, the slot it came from; both live
  // in the work memory (ownWork_ or the caller's), dead once the store is reordered.
  std::uint64_t* keys_ = nullptr;
  std::uint32_t* order_ = nullptr;
  std::size_t n_ = 0;
  WorkBuffer ownWork_;  // the work memory when the caller lends none
  std::vector<std::uint32_t> cellStart_;   // cellCount()+1 slot offsets
  std::vector<std::uint64_t> cellKey_;     // key of each cell
  std::vector<std::uint64_t> hashKeys_;    // open addressing, capacity power of two
  std::vector<std::uint32_t> hashCells_;
  std::vector<SlotRange> layers_;
  // The particles that changed cell since the last rebuild (sortMovers), as (key, slot).
  std::vector<std::pair<std::uint64_t, std::uint32_t>> movers_;
  std::vector<std::vector<std::uint32_t>> phases_;
  std::uint64_t hashMask_ = 0;
  std::array<std::int64_t, 3> origin_{};  // the lowest cell coordinates of the last rebuild
  std::array<std::int64_t, 3> extent_{};  // highest less lowest, per physical axis
  bool torus_ = false;  // some axis spans 2^21 - 1 cells or more: coordinates wrap
  std::array<int, 3> axes_{0, 1, 2};  // physical axis of each key field (minor, middle, major)
  int fixedAxis_ = -1;                // the layers' axis when fixed, else -1
};

/// Brute-force reference: every pair (i < j) closer than `cutoff`, O(n^2). Tests only.
std::vector<std::pair<std::uint32_t, std::uint32_t>> bruteForcePairs(const ParticleStore& store,
                                                                     float cutoff);

}  // namespace softsub::neighbors
