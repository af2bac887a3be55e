#pragma once
/// The pair kernel: one formula for every pair of particles, whatever their materials.
#include <bit>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "core/particle_store.h"
#include "forces/interaction_table.h"
#include "neighbors/cell_grid.h"

namespace softsub::fluid {

/// A half pair list (Verlet list): for each slot i, the slots j of every pair within
/// its cutoff plus a skin, each unordered pair once. Valid while the two largest
/// displacements since build() add up to less than the skin and the store has not been
/// reordered (solver::Simulation checks both).
/// What else a pair list needs beyond the interaction table (rigid bodies).
struct ListOptions {
  /// Per material: list radius before the skin; empty: each row's longest cutoff. Rows
  /// with contacts (rigid bodies) list pairs out to their contact distance too.
  std::span<const float> rowRadius;
  /// Pairs of two particles with the same owner >= this are not listed (the particles
  /// of one rigid body never interact). The default lists every pair.
  std::uint32_t exclusiveOwnersFrom = UINT32_MAX;
  /// A layer whose candidates lie within this many slots from its first one keeps
  /// 16-bit offsets (PairList::Layer); at most 65,536. Tests lower it to exercise the
  /// 32-bit form on small inputs.
  std::uint32_t narrowSpan = 65536;
  /// Where the table has a closed form the kernel evaluates in registers
  /// (InteractionTable::closedFormLj), list groups of 8 slots (Layer::grouped) for that
  /// kernel. Tests turn it off to run the table kernel on such a table.
  bool closedForm = true;
};

class PairList {
 public:
  PairList();
  ~PairList();
  PairList(PairList&&) noexcept;
  PairList& operator=(PairList&&) noexcept;

  /// Lists every pair closer than (row radius + skin) using `grid` (rebuilt on `store`).
  /// Built in parallel, one task per layer of the grid (CellGrid::layers), each with its
  /// own partner array: the list is the same for any number of threads.
  void build(const neighbors::CellGrid& grid, const forces::InteractionTable& table,
             const ParticleStore& store, float skin, const ListOptions& options = {});
  /// build(), and while each layer's list is fresh in cache, its pairs' forces added to
  /// store.f as accumulatePairForces would (bitwise the same: the layers run phase by
  /// phase, in the kernel's order). For a rebuild followed by a force evaluation.
  void buildAndAccumulate(const neighbors::CellGrid& grid, const forces::InteractionTable& table, ParticleStore& store,
                          float skin, const ListOptions& options = {});
  /// Partners of slot i, as slots (finds i's layer and copies: for tests, not hot loops).
  [[nodiscard]] std::vector<std::uint32_t> partners(std::size_t i) const;
  /// Calls fn(i, j) for every listed pair, slot i ascending, each i's partners in list
  /// order (grouped layers: window by window or group by group, each one's slots
  /// ascending).
  template <class Fn>
  void forEachPair(Fn&& fn) const {
    for (std::size_t l = 0; l < layerCount_; ++l) {
      const Layer& layer = layers_[l];
      layer.forEachPair([&](std::uint32_t k, std::uint32_t j) { fn(layer.slots.begin + k, j); });
    }
  }
  /// Whether the last build listed groups for the closed-form kernel (Layer::grouped).
  [[nodiscard]] bool grouped() const { return grouped_; }
  /// Whether build() lists groups for a store of `particles` slots with this table and
  /// these options: the table has a closed form (one material, the true Lennard-Jones
  /// force), options.closedForm, no rigid owners to exclude, and fewer than 2^27 slots
  /// (a group's index has 24 bits).
  [[nodiscard]] static bool groups(const forces::InteractionTable& table, std::size_t particles,
                                   const ListOptions& options);
  /// Number of listed pairs.
  [[nodiscard]] std::size_t pairCount() const;
  /// Bytes reserved.
  [[nodiscard]] std::size_t memoryBytes() const;

  /// One layer of the grid: its slots, and their partners one after another (slot
  /// slots.begin + k has list entries start[k] .. start[k + 1]). Why two encodings: a
  /// layer's partners lie in it and the next layer, so almost always within 65,536 slots
  /// of its first slot; they are then kept as 16-bit offsets from it (`narrow`), which
  /// halves the list's memory and the kernel's reads of it. Layers whose partners reach
  /// further (very large layers, the wrap-around of the grid) keep 32-bit slots.
  ///
  /// Grouped layers (the closed-form kernel, ListOptions::closedForm) list instead, per
  /// slot, the aligned groups of 8 slots [b + 8 g, b + 8 g + 8) holding its partners
  /// (b: span.begin rounded down to a multiple of 8) and, for each, the lanes that are
  /// partners (bit c: slot b + 8 g + c). The kernel evaluates a group's 8 lanes at once
  /// from the store's arrays, with no gather, and masks the lanes that are not partners.
  /// `span` is then the slots the layer's pairs touch. Narrow grouped layers (all of
  /// them but very large layers and some across the grid's wrap) keep instead, in
  /// `packed`, windows of 8 slots that start anywhere: 16-bit codes with no `start`, for
  /// each slot in turn its windows in list order, each as (w - previous w) << 7 | the
  /// lanes 1 to 7 (bit c - 1: slot w + c is a partner; lane 0, slot w itself, always
  /// is), the first counted from the slot's own slot minus 7; a window's step is 8 or
  /// more (windows of one run of ascending groups do not overlap), so codes whose step
  /// is below 8 are special: jump codes (step 1, the low 7 bits a signed count of
  /// kJumpSlots slots) bring the next window 8 to 263 slots ahead where it would be
  /// less than 8 or more than 511 slots on (counted modulo 2^32, or as signed offsets:
  /// the same slots), and a code below 128 (step 0) ends the slot: its low 7 bits
  /// count the slot's outer windows (below). Each window starts at the lowest
  /// partner not yet in a window (greedy), which needs about a sixth fewer windows than
  /// aligned groups of 8 (9.5 against 11.4 a particle in the LJ liquid): the kernel's
  /// cost is per window. Why codes:
  /// consecutive windows of a slot are near each other (the rest of its cell, then rows
  /// of neighbouring cells), so a step fits 9 bits but for the jump to the next layer,
  /// and the kernel walks each layer's slots in order anyway: 2 bytes a window and 4 a
  /// slot (11.3 codes, about 23 bytes a particle in the LJ liquid, against 53 for 32-bit
  /// entries with row starts), which keeps the whole simulation under 100 bytes a particle.
  /// Outer windows: a window none of whose partners lay within the cutoff when the list
  /// was built (only the skin's shell: a fifth to a third of the Lennard-Jones liquid's
  /// windows) and starts after its slot (not across the grid's wrap) is kept apart, in
  /// slot order: w - slot - 1 in `outer` (16 bits: a narrow layer's span) and its lanes 1 to 7 in
  /// `outerLanes`, the count of each slot's in its end code. The kernel tests such a window's distances first
  /// and evaluates it only when a partner has come within the cutoff (about one test in fifty in the liquid:
  /// a branch the predictor knows), in a pass of its own after the layer's windows, so that no slot's loop
  /// gets a second, unpredictable exit. The same pairs, a byte more a window; only the order of the sums
  /// changes. Wide grouped layers keep one 32-bit entry g << 8 | lanes per aligned group, with `start`, and
  /// the kernel adds their forces straight to the store.
  struct Layer {
    neighbors::SlotRange slots;
    std::vector<std::uint32_t> start;
    bool narrow = true;
    bool grouped = false;
    std::vector<std::uint16_t> near;    ///< narrow, not grouped: partner slot - slots.begin
    std::vector<std::uint32_t> far;     ///< not narrow, not grouped: partner slot
    std::vector<std::uint32_t> groups;  ///< grouped, not narrow: g << 8 | partner lanes
    std::vector<std::uint16_t> packed;  ///< grouped and narrow: the codes above
    std::vector<std::uint16_t> outer;   ///< packed: the outer windows' starts above
    std::vector<std::uint8_t> outerLanes;  ///< packed: the outer windows' lanes above
    neighbors::SlotRange span;          ///< the slots of the layer and of its cells' candidate ranges
    /// Whether the layer keeps its groups in `packed`.
    [[nodiscard]] bool isPacked() const { return grouped && narrow; }
    /// The slot of list entry q (layers that are not grouped).
    [[nodiscard]] std::uint32_t partner(std::uint32_t q) const {
      return narrow ? slots.begin + near[q] : far[q];
    }
    /// Calls fn(k, j) for each partner j of each slot slots.begin + k, k ascending, each
    /// slot's partners in list order (grouped layers: window by window or group by group,
    /// each one's slots ascending).
    template <class Fn>
    void forEachPair(Fn&& fn) const {
      const std::uint32_t rows = slots.end - slots.begin;
      if (!isPacked()) {
        for (std::uint32_t k = 0; k < rows; ++k) forEachListed(k, [&](std::uint32_t j) { fn(k, j); });
        return;
      }
      std::size_t q = 0, o = 0;
      for (std::uint32_t k = 0; k < rows; ++k) {
        std::uint32_t w = slots.begin + k - 7;  // modulo 2^32 (the kernel: signed, the same slots)
        std::uint32_t e = packed[q++];
        for (; !isEnd(e); e = packed[q++]) {
          if (!isWindow(e)) {  // a jump
            w += jumpOf(e);
            continue;
          }
          w += e >> kStepShift;
          for (std::uint32_t bits = windowLanes(e); bits != 0; bits &= bits - 1)
            fn(k, w + static_cast<std::uint32_t>(std::countr_zero(bits)));
        }
        for (const std::size_t last = o + e; o < last; ++o) {
          const std::uint32_t ow = slots.begin + k + 1 + outer[o];
          for (std::uint32_t bits = windowLanes(outerLanes[o]); bits != 0; bits &= bits - 1)
            fn(k, ow + static_cast<std::uint32_t>(std::countr_zero(bits)));
        }
      }
    }
    /// Calls fn(j) for each partner of slot slots.begin + k, in list order. Packed
    /// layers are walked from their first slot: for tests and tools, not hot loops.
    template <class Fn>
    void forEachPartner(std::uint32_t k, Fn&& fn) const {
      if (isPacked()) {
        forEachPair([&](std::uint32_t row, std::uint32_t j) {
          if (row == k) fn(j);
        });
        return;
      }
      forEachListed(k, fn);
    }
    /// Number of list entries: pairs; groups in wide grouped layers; codes in packed ones
    /// (outer ones included).
    [[nodiscard]] std::size_t size() const {
      if (isPacked()) return packed.size() + outer.size();
      return start.empty() ? 0 : start.back();
    }
    /// forEachPartner for a layer that is not packed (row starts).
    template <class Fn>
    void forEachListed(std::uint32_t k, Fn&& fn) const {
      for (std::uint32_t q = start[k]; q < start[k + 1]; ++q) {
        if (!grouped) {
          fn(partner(q));
          continue;
        }
        const std::uint32_t e = groups[q];
        for (std::uint32_t bits = e & 255u; bits != 0; bits &= bits - 1)
          fn((span.begin & ~7u) + (e >> 8) * 8 + static_cast<std::uint32_t>(std::countr_zero(bits)));
      }
    }
    /// Packed codes: a window's step is code >> kStepShift (kMinStep or more).
    static constexpr std::uint32_t kStepShift = 7;
    static constexpr std::uint32_t kMinStep = 8;
    /// The slots of one unit of a packed jump code.
    static constexpr std::int32_t kJumpSlots = 256;
    /// Whether a packed code is a window (step kMinStep or more).
    [[nodiscard]] static constexpr bool isWindow(std::uint32_t code) { return code >= kMinStep << kStepShift; }
    /// Whether a packed code is a jump (step 1).
    [[nodiscard]] static constexpr bool isJump(std::uint32_t code) { return code >> kStepShift == 1; }
    /// Whether a packed code ends its slot (step 0); its value is the slot's outer windows.
    [[nodiscard]] static constexpr bool isEnd(std::uint32_t code) { return code >> kStepShift == 0; }
    /// The most outer windows a slot keeps (its end code's 7 bits).
    static constexpr std::uint32_t kOuterMost = 127;
    /// The slots a packed jump code moves by, modulo 2^32 (its low 7 bits, signed).
    [[nodiscard]] static constexpr std::uint32_t jumpOf(std::uint32_t code) {
      const std::int32_t units = static_cast<std::int32_t>(static_cast<std::int8_t>((code & 127u) << 1)) >> 1;
      return static_cast<std::uint32_t>(units * kJumpSlots);
    }
    /// The partner lanes of a packed window code (bit c: slot w + c).
    [[nodiscard]] static constexpr std::uint32_t windowLanes(std::uint32_t code) { return 1u | (code & 127u) << 1; }
  };
  [[nodiscard]] std::span<const Layer> layers() const { return {layers_.data(), layerCount_}; }
  /// The layers grouped in phases (CellGrid::layersByPhase, copied at build): a pair of
  /// a layer's slot i lists j in the same layer or the next, so the layers of one phase
  /// may add forces to their i and j in parallel without sharing a slot.
  [[nodiscard]] const std::vector<std::vector<std::uint32_t>>& phases() const { return phases_; }
  /// Whether every layer is packed, its sums reaching no further than the next layer's
  /// slots: setPairForces then runs the layers without phases.
  [[nodiscard]] bool packedOnly() const { return packedOnly_; }

 private:
  struct Scratch;
  void build(const neighbors::CellGrid& grid, const forces::InteractionTable& table, const ParticleStore& store,
             float skin, const ListOptions& options, ParticleStore* forces);
  std::vector<Layer> layers_;
  std::size_t layerCount_ = 0;  // layers_ in use (the rest keep their memory for later)
  friend void accumulatePairForces(const PairList&, const forces::InteractionTable&, ParticleStore&);
  friend void setPairForces(const PairList&, const forces::InteractionTable&, ParticleStore&);
  std::vector<std::vector<std::uint32_t>> phases_;
  bool grouped_ = false;
  bool packedOnly_ = false;     // every layer packed, its sums within its own and the next layer
  std::vector<float> rowCut2_;  // each material row's squared list radius
  std::vector<std::uint32_t> firstCell_;  // each layer's first cell (build scratch)
  std::unique_ptr<Scratch> scratch_;
};

/// Adds to store.f the forces of every listed pair closer than its cutoff (Newton's
/// third law: what i gets, j gets with the opposite sign):
///   f_i += -F(r) n + damping (v_j - v_i) + k ((v_j - v_i) . n) n,  n = (x_j - x_i) / r
/// with F the pair's sampled function (positive = repulsion), or, for a grouped list,
/// the table's closed form (InteractionTable::closedFormLj). No branch on function kind
/// per pair, no virtual call, no allocation once warmed up. Runs the list's layers in
/// parallel phase by phase; every force is summed in the same order whatever the number
/// of threads, so the result is bitwise the same for any thread count.
void accumulatePairForces(const PairList& list, const forces::InteractionTable& table, ParticleStore& store);

/// Sets store.f to the forces of every listed pair: zeroes it, then adds them as
/// accumulatePairForces does, to the bit. A list of packed layers only (packedOnly():
/// the Lennard-Jones liquid) runs all its layers at once instead of phase by phase
/// (see pair_forces.cpp).
void setPairForces(const PairList& list, const forces::InteractionTable& table, ParticleStore& store);

/// Adds to store.f the forces of every pair closer than its cutoff, each pair once
/// (Newton's third law: what i gets, j gets with the opposite sign):
///   f_i += -F(r) n + damping (v_j - v_i) + k ((v_j - v_i) . n) n,  n = (x_j - x_i) / r
/// with F the pair's sampled function. `store` must be in the order `grid` was rebuilt
/// with. Builds a pair list with no skin (allocates): for tests and one-off use.
void accumulatePairForces(const neighbors::CellGrid& grid, const forces::InteractionTable& table,
                          ParticleStore& store);

/// The instruction set the pair list build and the pair kernel run with. Both exist
/// twice, compiled from one source: for the baseline (x86-64's SSE2, or whatever the
/// build targets) and, on x86-64 built by GCC, for AVX2 with FMA, which the CPU's
/// support selects at start-up (Avx2 needs both). Both copies do the same IEEE
/// operations in the same order, fused multiply-adds only where the source writes one:
/// the lists and forces are bitwise the same (tests/fluid), only the speed differs.
enum class Simd { Baseline, Avx2 };
/// 1 where this build makes the AVX2 copies of its hot loops (GCC on x86-64, the build not
/// already targeting AVX2 everywhere, as SOFTSUB_NATIVE does): the pair list build and
/// kernel here, and the solver's sweep (solver/simulation.cpp), both chosen by simdInUse().
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__AVX2__)
#define SOFTSUB_AVX2_COPY 1
#else
#define SOFTSUB_AVX2_COPY 0
#endif
/// The copy in use (Avx2 where the CPU has AVX2 and FMA and the build made that copy).
[[nodiscard]] Simd simdInUse();
/// Selects a copy for what follows (tests, benchmarks); false, and nothing changes,
/// when this build or CPU has no such copy. Not meant to change during a step.
bool useSimd(Simd level);

/// The same sum by brute force over all pairs, in double precision, straight from the
/// functions' formulas (not the tables). Reference for tests; O(n^2).
void referencePairForces(const forces::InteractionTable& table, const ParticleStore& store,
                         std::vector<double>& fx, std::vector<double>& fy, std::vector<double>& fz);

}  // namespace softsub::fluid
