// The hot loops of the pair list build and the pair kernel. Included twice by
// pair_forces.cpp: once for the baseline instruction set and, on x86-64 with GCC, once
// more under `#pragma GCC target("avx2,fma")` (docs/architecture.md, "One source, two
// instruction sets"). Not a header: it has no includes of its own and defines functions
// in whatever namespace includes it. SOFTSUB_KERNEL_AVX is 1 for the AVX2 copy.

// Why a pair list: most candidates of a cell stencil are out of range, and sorting
// plus filtering them costs as much as the forces. The list keeps the pairs within
// cutoff + skin and serves several substeps. To build it, per cell the candidates (own
// cell first, then the forward neighbour cells) are copied into a contiguous buffer;
// per particle, eight candidates at a time give a bit mask of those within reach, and
// the set bits' entries go straight into the list (filter()).
struct Candidates {
  const float* __restrict x;
  const float* __restrict y;
  const float* __restrict z;
  const std::uint32_t* __restrict entry;  // what the list stores for the candidate
  const std::uint32_t* __restrict owner;  // filled only when the list excludes owners
};

// How many candidates filter() tests at a time; the candidate buffers have this many
// readable entries past their end.
inline constexpr std::uint32_t kFilterBlock = 8;

// Bit c set: buffer entry k + c (c < 8) is closer than sqrt(cut2) to (xi, yi, zi). The
// squared distance is dx * dx + dy * dy + dz * dz in this order and without fused
// multiply-adds in every form below, so every form keeps the same entries.
// With kInner, bit c + 8 set too where the entry is also closer than sqrt(inner2) (the
// packed list's outer windows: fillPacked); without, inner2 is not looked at (the plain
// list's filter pays for no second comparison).
template <bool kInner>
inline std::uint32_t nearMasks(const Candidates& b, std::uint32_t k, float xi, float yi, float zi, float cut2,
                               float inner2) {
#if SOFTSUB_KERNEL_AVX || defined(__AVX__)
  const __m256 dx = _mm256_sub_ps(_mm256_loadu_ps(b.x + k), _mm256_set1_ps(xi));
  const __m256 dy = _mm256_sub_ps(_mm256_loadu_ps(b.y + k), _mm256_set1_ps(yi));
  const __m256 dz = _mm256_sub_ps(_mm256_loadu_ps(b.z + k), _mm256_set1_ps(zi));
  const __m256 r2 = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(dx, dx), _mm256_mul_ps(dy, dy)), _mm256_mul_ps(dz, dz));
  const auto bits = static_cast<std::uint32_t>(_mm256_movemask_ps(_mm256_cmp_ps(r2, _mm256_set1_ps(cut2), _CMP_LT_OQ)));
  if constexpr (!kInner) return bits;
  return bits |
         static_cast<std::uint32_t>(_mm256_movemask_ps(_mm256_cmp_ps(r2, _mm256_set1_ps(inner2), _CMP_LT_OQ))) << 8;
#elif defined(__SSE2__)
  std::uint32_t bits = 0;
  for (std::uint32_t h = 0; h < 8; h += 4) {
    const __m128 dx = _mm_sub_ps(_mm_loadu_ps(b.x + k + h), _mm_set1_ps(xi));
    const __m128 dy = _mm_sub_ps(_mm_loadu_ps(b.y + k + h), _mm_set1_ps(yi));
    const __m128 dz = _mm_sub_ps(_mm_loadu_ps(b.z + k + h), _mm_set1_ps(zi));
    const __m128 r2 = _mm_add_ps(_mm_add_ps(_mm_mul_ps(dx, dx), _mm_mul_ps(dy, dy)), _mm_mul_ps(dz, dz));
    bits |= static_cast<std::uint32_t>(_mm_movemask_ps(_mm_cmplt_ps(r2, _mm_set1_ps(cut2)))) << h;
    if constexpr (kInner)
      bits |= static_cast<std::uint32_t>(_mm_movemask_ps(_mm_cmplt_ps(r2, _mm_set1_ps(inner2)))) << (h + 8);
  }
  return bits;
#else
  std::uint32_t bits = 0;
  for (std::uint32_t c = 0; c < 8; ++c) {
    const float dx = b.x[k + c] - xi, dy = b.y[k + c] - yi, dz = b.z[k + c] - zi;
    const float r2 = dx * dx + dy * dy + dz * dz;
    bits |= (r2 < cut2 ? 1u : 0u) << c;
    if constexpr (kInner) bits |= (r2 < inner2 ? 1u : 0u) << (c + 8);
  }
  return bits;
#endif
}
inline std::uint32_t nearMask(const Candidates& b, std::uint32_t k, float xi, float yi, float zi, float cut2) {
  return nearMasks<false>(b, k, xi, yi, zi, cut2, 0.0f);
}

#if SOFTSUB_KERNEL_AVX || defined(__AVX2__)
// For each 8-bit mask, the positions of its set bits in ascending order, one byte each
// (the rest 0): the lane order that packs the kept entries of a block to its front.
struct PackOrder {
  std::uint64_t lanes[256];
  constexpr PackOrder() : lanes() {
    for (std::uint32_t m = 0; m < 256; ++m) {
      std::uint64_t v = 0;
      for (std::uint32_t c = 0, n = 0; c < 8; ++c)
        if (m & (1u << c)) v |= static_cast<std::uint64_t>(c) << (8 * n++);
      lanes[m] = v;
    }
  }
};
inline constexpr PackOrder kPackOrder{};

// Writes the entries of a block's set bits to out, in order, as one 8-wide store (out
// has room for 8): a permutation instead of a loop over the bits, whose exits the branch
// predictor cannot foresee.
template <class Out>
inline void packKept(const std::uint32_t* entry, std::uint32_t keep, Out* out) {
  const __m256i order = _mm256_cvtepu8_epi32(_mm_cvtsi64_si128(static_cast<long long>(kPackOrder.lanes[keep])));
  const __m256i kept = _mm256_permutevar8x32_epi32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(entry)), order);
  if constexpr (sizeof(Out) == 4) {
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out), kept);
  } else {  // 16-bit entries (< 65,536): pack, then bring the two halves together
    const __m256i packed = _mm256_permute4x64_epi64(_mm256_packus_epi32(kept, kept), 0x08);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out), _mm256_castsi256_si128(packed));
  }
}
#endif

// The list entries of buffer entries [from, len) closer than sqrt(cut2) to (xi, yi, zi)
// go to out, in buffer order; out has room for `room` >= len - from entries. kExclusive:
// candidates of owner `own` are dropped too (a rigid body's particles never pair with
// each other). Returns how many. Why masks: about one candidate in six is kept, and a
// loop that wrote every candidate and advanced by its comparison (a branch-free
// compaction) was half the list build's time, one dependent step per candidate; here
// eight candidates cost one comparison, and the kept ones one permutation (AVX2), or
// the old compaction over the block only when it keeps some (baseline).
template <bool kExclusive, class Out>
inline std::uint32_t filter(const Candidates& b, std::uint32_t from, std::uint32_t len, float xi, float yi,
                            float zi, float cut2, std::uint32_t own, Out* __restrict out, std::uint32_t room) {
  std::uint32_t n = 0;
  for (std::uint32_t k = from; k < len; k += kFilterBlock) {
    std::uint32_t keep = nearMask(b, k, xi, yi, zi, cut2);
    if (len - k < kFilterBlock) keep &= (1u << (len - k)) - 1u;
    if constexpr (kExclusive)
      for (std::uint32_t bits = keep; bits != 0; bits &= bits - 1)
        if (b.owner[k + static_cast<std::uint32_t>(__builtin_ctz(bits))] == own)
          keep &= ~(1u << __builtin_ctz(bits));
    if (n + kFilterBlock <= room) {  // almost always: the list keeps no slack for this
#if SOFTSUB_KERNEL_AVX || defined(__AVX2__)
      packKept(b.entry + k, keep, out + n);
      n += static_cast<std::uint32_t>(__builtin_popcount(keep));
#else
      // Without a lane permutation: all eight written, the kept ones counted.
      if (keep != 0)
        for (std::uint32_t c = 0; c < kFilterBlock; ++c) {
          out[n] = static_cast<Out>(b.entry[k + c]);
          n += (keep >> c) & 1u;
        }
#endif
      continue;
    }
    for (; keep != 0; keep &= keep - 1) out[n++] = static_cast<Out>(b.entry[k + static_cast<std::uint32_t>(__builtin_ctz(keep))]);
  }
  return n;
}

// Makes room for `needed` entries in a layer's list. It grows by an eighth, not by
// doubling: a list keeps its capacity from one build to the next (no allocation once
// warmed up), so what matters is how far the capacity overshoots the list for good
// (doubling left 8-10 bytes a particle unused), not the few copies of the first build.
// No fixed minimum: a scene of sparse layers (spray, a thin column) would pay it per
// layer.
template <class V>
void grow(V& list, std::size_t needed) {
  const std::size_t target = std::max<std::size_t>(needed, list.size() + list.size() / 8);
  list.reserve(target);  // exactly: resize alone would double the capacity
  list.resize(target);
}

// Gives back the capacity of a list that has shrunk to under four fifths of it, keeping
// an eighth for growth. A layer's content changes as the fluid moves (a layer that once
// held the pool's densest part may later hold spray), and without this each layer would
// keep the largest list it ever had: in the seed scene the sum of those maxima was half
// as much again as the lists in use. Costs one allocation and copy of the layer's list
// at the rebuilds where it happens.
template <class V>
void trim(V& list, std::size_t used) {
  if (list.capacity() <= used + used / 4 + kFilterBlock) return;
  V kept;
  kept.reserve(used + used / 8);
  kept.assign(list.begin(), list.begin() + static_cast<std::ptrdiff_t>(used));
  list.swap(kept);
}

// One layer of PairList::build: its partners, written into its list (see build()).
// Scratch: PairList's per-thread buffers (deduced: the type is private to PairList).
// Copies the positions of slots [b, b + m) into a cell's candidate buffers (x, y, z) and
// their list entries (slot - entryBase) into entry. With `whole` (the caller checked
// that slots up to b + m + kFilterBlock exist and that the buffers have kFilterBlock
// entries of room past the range), in whole blocks, the last one running past the range:
// its excess lands where the next range goes, or in the buffers' padding. Fixed-size
// blocks through unaliased pointers vectorise; a cell's ranges are short (a row of three
// cells: about 8 slots for a resting goo), so a loop with a remainder spent its time in
// the remainder.
inline void copyCandidates(const float* __restrict px, const float* __restrict py, const float* __restrict pz,
                           std::uint32_t b, std::uint32_t m, std::uint32_t entryBase, bool whole,
                           float* __restrict x, float* __restrict y, float* __restrict z,
                           std::uint32_t* __restrict entry) {
  const std::uint32_t first = b - entryBase;  // modulo 2^32, as slot - entryBase
  px += b;
  py += b;
  pz += b;
  // Offsets as std::size_t: with 32-bit ones GCC cannot prove the accesses contiguous.
  const std::size_t count = whole ? (m + kFilterBlock - 1) / kFilterBlock * kFilterBlock : m;
  if (whole) {
    for (std::size_t q = 0; q < count; q += kFilterBlock)
      for (std::size_t t = q; t < q + kFilterBlock; ++t) {
        x[t] = px[t];
        y[t] = py[t];
        z[t] = pz[t];
        entry[t] = first + static_cast<std::uint32_t>(t);
      }
    return;
  }
  for (std::size_t t = 0; t < count; ++t) {
    x[t] = px[t];
    y[t] = py[t];
    z[t] = pz[t];
    entry[t] = first + static_cast<std::uint32_t>(t);
  }
}

// The positions of the store's 8 slots from `first`, the slots past the store's end as
// 0: its last, partial group or window, for the list build and the kernel, which read
// 8 slots at a time (the padding lanes are never partners).
inline void paddedGroup(const ParticleStore& s, std::uint32_t first, float (&x)[8], float (&y)[8], float (&z)[8]) {
  const auto n = static_cast<std::uint32_t>(s.size());
  for (std::uint32_t c = 0; c < 8; ++c) {
    const bool in = first + c < n;
    x[c] = in ? s.px[first + c] : 0.0f;
    y[c] = in ? s.py[first + c] : 0.0f;
    z[c] = in ? s.pz[first + c] : 0.0f;
  }
}

// The lanes of the store's group of 8 slots from g8 (a multiple of 8) closer to
// (xi, yi, zi) than cut2 squared; the store's last, partial group padded (paddedGroup).
// `store`: the store's position arrays; n: its size (read once by the caller, not per
// group).
// With inner2 (listAligned's), bit c + 8: lane c is also closer than sqrt(inner2).
template <bool kInner>
inline std::uint32_t groupNear(const ParticleStore& s, const Candidates& store, std::uint32_t n, std::uint32_t g8,
                               float xi, float yi, float zi, float cut2, float inner2) {
  if (g8 + 8 <= n) [[likely]]
    return nearMasks<kInner>(store, g8, xi, yi, zi, cut2, inner2);
  float x[8], y[8], z[8];
  paddedGroup(s, g8, x, y, z);
  return nearMasks<kInner>(Candidates{x, y, z, nullptr, nullptr}, 0, xi, yi, zi, cut2, inner2);
}

// A grouped layer's list (PairList::Layer::grouped) for slot i: the aligned groups of 8
// slots that hold its partners among [b, e) (one candidate range: the rest of i's cell,
// or a forward range), each as (g - lo / 8) << 8 | the lanes that are partners (with
// kInner, for a packed layer, whose g fits 16 bits: (g - lo / 8) << 16 | the partner
// lanes closer than sqrt(inner2) << 8 | the lanes that are partners), from out[at] on (at most one per group the range touches); returns the new length. Wide
// layers keep these entries, packed ones turn them into windows (packWindows). The
// groups are tested straight from the store's arrays, 8 slots at a time with the same
// distance test as filter(), so a grouped list lists exactly the pairs a plain one
// does. A group that two ranges share (one ends and the next begins inside it) is
// listed twice with disjoint lanes: each pair is still evaluated once. The lanes of
// [b, e) in the range's first and last group are found once (per group they were a
// fifth of the loop),
// and the loop has no branch per group: GCC otherwise kept the length in memory and
// branched on every group (twice the build's time). Inlined into the layer's loop (GCC
// stopped doing so by itself when groupNear was shared: a call per range, 6 a slot).
template <bool kInner = false>
[[gnu::always_inline]] inline std::uint32_t listAligned(const ParticleStore& s, std::uint32_t i, float cut2,
                                                        std::uint32_t b, std::uint32_t e, std::uint32_t lo,
                                                        std::uint32_t* __restrict out, std::uint32_t at,
                                                        float inner2 = 0.0f) {
  if (b >= e) return at;
  const float xi = s.px[i], yi = s.py[i], zi = s.pz[i];
  const auto n = static_cast<std::uint32_t>(s.size());
  const Candidates store{s.px.data(), s.py.data(), s.pz.data(), nullptr, nullptr};
  const std::uint32_t first = ((b & ~7u) - lo) / 8, last = ((e - 1) / 8 * 8 - lo) / 8;
  const std::uint32_t lastLanes = 0xFFu >> ((8 - e % 8) % 8);
  std::uint32_t edge = 0xFFu << (b % 8);
  std::uint32_t a = at;
  for (std::uint32_t g = first; g <= last; ++g) {
    const std::uint32_t near = groupNear<kInner>(s, store, n, lo + 8 * g, xi, yi, zi, cut2, inner2);
    const std::uint32_t lanes = near & edge & (g == last ? lastLanes : 0xFFu);
    edge = 0xFFu;
    if constexpr (kInner)
      out[a] = g << 16 | (near >> 8 & lanes) << 8 | lanes;
    else
      out[a] = g << 8 | lanes;
    a += lanes != 0 ? 1u : 0u;
  }
  return a;
}

// Slot i's aligned groups (listAligned<true>'s entries, `count` of them, counted from
// slot lo) as packed window codes (PairList::Layer::packed) from out[at] on, without
// the end code, and its outer windows from outer[0] and outerLanes[0] on; returns the
// new length and the outer windows' count (at most kOuterMost). Room: 6 codes per
// entry in out (a window per entry at most, each after up to 5 jumps in a narrow
// layer's span), and one per entry in outer; fillPacked adds one for the end code.
// Greedy: a window starts at the lowest partner not yet in one and takes the partners
// among its 8 slots. A window that starts at lane `off` of group g covers lanes off
// and up of g and the lanes below off of g + 1, so each entry either adds to the open
// window (a group two ranges share, or the next group) or starts one at its lowest
// partner left, with one branch per entry and none per window (the LJ liquid's
// build: 4.2-4.3 ms against 3.2 for aligned groups; keeping the waiting partners in a
// 64-bit mask and writing windows in a loop took 4.8). A window is written when the
// next one starts (or the slot ends): to `outer` when none of its partners is closer
// than the inner distance and it starts after slot i, else to `out`. Entries come in ascending order but where a forward cell lies across the
// grid's wrap; a window then starts behind the last one, after jump codes: still each
// pair in exactly one window.
struct PackedCounts {
  std::uint32_t at, outer;
};
inline PackedCounts packWindows(std::uint32_t i, std::uint32_t lo, const std::uint32_t* __restrict entry,
                                std::uint32_t count, std::uint16_t* __restrict out, std::uint32_t at,
                                std::uint16_t* __restrict outer, std::uint8_t* __restrict outerLanes) {
  using Layer = PairList::Layer;
  // The last window written to `out`'s first slot, modulo 2^32 (the kernel counts
  // signed: the same slots).
  std::uint32_t prev = i - 7;
  std::uint32_t outers = 0;
  // The open window: its group (from lo), first lane, first slot, lanes (bit c: slot
  // w + c) and whether a partner of it is within the inner distance.
  std::uint32_t wg = UINT32_MAX - 1, off = 0, w = 0, lanes = 0;
  bool inner = false;
  const auto write = [&] {
    // Only a window ahead of its slot: one behind it (across the grid's wrap) has no
    // 16-bit offset from it. Ahead, w - i - 1 < 65,536 (a narrow layer's span).
    if (!inner && w > i && outers < Layer::kOuterMost) {
      outer[outers] = static_cast<std::uint16_t>(w - (i + 1));
      outerLanes[outers++] = static_cast<std::uint8_t>((lanes & 255u) >> 1);
      return;
    }
    std::uint32_t step = w - prev;
    while (step - Layer::kMinStep > 511 - Layer::kMinStep) [[unlikely]] {  // jumps: 8 to 263 slots ahead after them
      const std::int64_t ahead = static_cast<std::int32_t>(step) - static_cast<std::int64_t>(Layer::kMinStep);
      const std::int64_t units = std::clamp<std::int64_t>(
          ahead < 0 ? -((-ahead + Layer::kJumpSlots - 1) / Layer::kJumpSlots) : ahead / Layer::kJumpSlots, -64, 63);
      const auto code = static_cast<std::uint16_t>(1u << Layer::kStepShift | (static_cast<std::uint32_t>(units) & 127u));
      out[at++] = code;
      prev += Layer::jumpOf(code);
      step = w - prev;
    }
    out[at++] = static_cast<std::uint16_t>(step << Layer::kStepShift | (lanes & 255u) >> 1);
    prev = w;
  };
  for (std::uint32_t q = 0; q < count; ++q) {
    const std::uint32_t g = entry[q] >> 16, m = entry[q] & 255u, near = entry[q] >> 8 & 255u;
    const std::uint32_t dg = g - wg;  // modulo 2^32
    // The lanes the open window covers in this group, and where they are in the window.
    const std::uint32_t covered = dg == 0 ? m & (0xFFu << off) : dg == 1 ? m & ((1u << off) - 1u) : 0u;
    lanes |= dg == 0 ? covered >> off : covered << (8 - off);
    inner = inner || (near & covered) != 0;
    const std::uint32_t left = m & ~covered;
    if (left == 0) continue;
    if (wg != UINT32_MAX - 1) write();
    off = static_cast<std::uint32_t>(std::countr_zero(left));
    wg = g;
    w = lo + 8 * g + off;
    lanes = left >> off & 255u;
    inner = (near & left) != 0;
  }
  if (wg != UINT32_MAX - 1) write();
  return {at, outers};
}

// One layer's list. innerCut2: for a packed layer, the squared inner distance of its
// outer windows (packWindows; 0: none).
template <class Scratch>
void buildLayer(PairList::Layer& layer, neighbors::SlotRange slots, std::size_t cellBegin, std::size_t cellEnd,
                Scratch& buf, neighbors::CellGrid::ForwardRanges& forwardRanges, const neighbors::CellGrid& grid,
                const ParticleStore& s, const ListOptions& options, const float* rowCut2, bool grouped,
                float innerCut2) {
  const bool exclusive = options.exclusiveOwnersFrom != UINT32_MAX;
  layer.slots = slots;
  layer.grouped = grouped;
  const std::size_t rows = layer.slots.end - layer.slots.begin;
  // Narrow (16-bit offsets) when every candidate lies within 65,536 slots from the
  // layer's first one.
  // The layer's cells' forward ranges are found once (the walker) and kept for the
  // fill below.
  std::uint32_t lowest = layer.slots.begin, highest = layer.slots.end;
  buf.ranges.clear();
  buf.rangeStart.clear();
  for (std::size_t c = cellBegin; c < cellEnd; ++c) {
    buf.rangeStart.push_back(static_cast<std::uint32_t>(buf.ranges.size()));
    for (const neighbors::SlotRange& r : forwardRanges.of(c)) {
      lowest = std::min(lowest, r.begin);
      highest = std::max(highest, r.end);
      buf.ranges.push_back(r);
    }
  }
  buf.rangeStart.push_back(static_cast<std::uint32_t>(buf.ranges.size()));
  layer.narrow = lowest >= layer.slots.begin &&
                 highest - layer.slots.begin <= std::min<std::uint32_t>(options.narrowSpan, 65536);
  layer.span = {lowest, highest};
  const bool packed = layer.isPacked();
  if (!packed) {
    if (layer.start.capacity() < rows + 1) layer.start.reserve(rows + 1 + rows / 8);  // see grow()
    layer.start.resize(rows + 1);
  }
  // The list is written in place: its vector is used up to its capacity, grown when a
  // particle's candidates might not fit, and cut to what was listed at the end.
  auto fill = [&](auto& out, std::uint32_t entryBase) {
    out.resize(out.capacity());
    std::uint32_t listed = 0;
    for (std::size_t c = cellBegin; c < cellEnd; ++c) {
      const neighbors::SlotRange own = grid.cell(c);
      const std::size_t cl = c - cellBegin;
      const std::span<const neighbors::SlotRange> forward(buf.ranges.data() + buf.rangeStart[cl],
                                                          buf.ranges.data() + buf.rangeStart[cl + 1]);
      std::uint32_t len = own.end - own.begin;
      for (const neighbors::SlotRange& r : forward) len += r.end - r.begin;
      if (buf.x.size() < len + kFilterBlock) {  // filter() reads up to a block past len
        for (auto* v : {&buf.x, &buf.y, &buf.z}) v->resize(len + kFilterBlock);
        for (auto* v : {&buf.entry, &buf.owner, &buf.kept}) v->resize(len + kFilterBlock);
      }
      std::uint32_t k = 0;
      auto append = [&](std::uint32_t b, std::uint32_t e) {
        copyCandidates(s.px.data(), s.py.data(), s.pz.data(), b, e - b, entryBase, e + kFilterBlock <= s.size(),
                       buf.x.data() + k, buf.y.data() + k, buf.z.data() + k, buf.entry.data() + k);
        if (exclusive)
          for (std::uint32_t j = b; j < e; ++j) buf.owner[k + (j - b)] = s.owner[j];
        k += e - b;
      };
      append(own.begin, own.end);
      for (const neighbors::SlotRange& r : forward) append(r.begin, r.end);
      const Candidates b{buf.x.data(), buf.y.data(), buf.z.data(), buf.entry.data(), buf.owner.data()};
      for (std::uint32_t i = own.begin; i < own.end; ++i) {
        layer.start[i - layer.slots.begin] = listed;
        const std::uint32_t from = i - own.begin + 1;
        const float cut2 = rowCut2[s.material[i]];
        const auto filterInto = [&](auto* to, std::uint32_t room) {
          return exclusive && s.owner[i] >= options.exclusiveOwnersFrom
                     ? filter<true>(b, from, len, s.px[i], s.py[i], s.pz[i], cut2, s.owner[i], to, room)
                     : filter<false>(b, from, len, s.px[i], s.py[i], s.pz[i], cut2, 0, to, room);
        };
        const auto room = static_cast<std::uint32_t>(out.size()) - listed;
        if (room >= len - from) {  // every candidate would fit: straight into the list
          listed += filterInto(out.data() + listed, room);
          continue;
        }
        // Near the end of the list's capacity: the kept entries go through the scratch
        // buffer, and the list grows only by what was kept (growing by the candidates,
        // several times what a particle keeps, left the last growth's excess unused).
        const std::uint32_t kept = filterInto(buf.kept.data(), static_cast<std::uint32_t>(buf.kept.size()));
        if (out.size() < listed + kept) grow(out, listed + kept);
        using Out = typename std::remove_reference_t<decltype(out)>::value_type;
        for (std::uint32_t q = 0; q < kept; ++q) out[listed + q] = static_cast<Out>(buf.kept[q]);
        listed += kept;
      }
    }
    out.resize(listed);
    trim(out, listed);
    return listed;
  };
  // Grouped: no candidate buffer; each candidate range is tested group by group in the
  // store (listAligned). Rigid bodies never make a grouped list (one fluid), so no owners.
  auto fillGroups = [&](std::vector<std::uint32_t>& out) {
    const std::uint32_t lo = layer.span.begin & ~7u;
    out.resize(out.capacity());
    std::uint32_t listed = 0;
    for (std::size_t c = cellBegin; c < cellEnd; ++c) {
      const neighbors::SlotRange own = grid.cell(c);
      const std::size_t cl = c - cellBegin;
      const std::span<const neighbors::SlotRange> forward(buf.ranges.data() + buf.rangeStart[cl],
                                                          buf.ranges.data() + buf.rangeStart[cl + 1]);
      // The most groups one particle of the cell can list: each range's groups.
      std::uint32_t most = (own.end - own.begin) / 8 + 2;
      for (const neighbors::SlotRange& r : forward) most += (r.end - r.begin) / 8 + 2;
      for (std::uint32_t i = own.begin; i < own.end; ++i) {
        layer.start[i - layer.slots.begin] = listed;
        if (out.size() < listed + most) grow(out, listed + most);
        const float cut2 = rowCut2[s.material[i]];
        listed = listAligned(s, i, cut2, i + 1, own.end, lo, out.data(), listed);
        for (const neighbors::SlotRange& r : forward)
          listed = listAligned(s, i, cut2, r.begin, r.end, lo, out.data(), listed);
      }
    }
    out.resize(listed);
    trim(out, listed);
    return listed;
  };
  // Packed (narrow grouped layers): per slot, its aligned groups as fillGroups finds
  // them (listAligned, into the scratch buffer), then as windows (packWindows).
  auto fillPacked = [&](std::vector<std::uint16_t>& out) {
    const std::uint32_t lo = layer.span.begin & ~7u;
    out.resize(out.capacity());
    std::vector<std::uint16_t>& outer = layer.outer;
    std::vector<std::uint8_t>& outerLanes = layer.outerLanes;
    outer.resize(outer.capacity());
    outerLanes.resize(outerLanes.capacity());
    std::uint32_t listed = 0, outers = 0;
    for (std::size_t c = cellBegin; c < cellEnd; ++c) {
      const neighbors::SlotRange own = grid.cell(c);
      const std::size_t cl = c - cellBegin;
      const std::span<const neighbors::SlotRange> forward(buf.ranges.data() + buf.rangeStart[cl],
                                                          buf.ranges.data() + buf.rangeStart[cl + 1]);
      // The most groups one particle of the cell can list: each range's groups.
      std::uint32_t most = (own.end - own.begin) / 8 + 2;
      for (const neighbors::SlotRange& r : forward) most += (r.end - r.begin) / 8 + 2;
      if (buf.kept.size() < most) buf.kept.resize(most);
      std::uint32_t* const groups = buf.kept.data();
      for (std::uint32_t i = own.begin; i < own.end; ++i) {
        const float cut2 = rowCut2[s.material[i]];
        std::uint32_t count = listAligned<true>(s, i, cut2, i + 1, own.end, lo, groups, 0, innerCut2);
        for (const neighbors::SlotRange& r : forward)
          count = listAligned<true>(s, i, cut2, r.begin, r.end, lo, groups, count, innerCut2);
        if (out.size() < listed + 6 * count + 1) grow(out, listed + 6 * count + 1);
        if (outer.size() < outers + count) grow(outer, outers + count);
        if (outerLanes.size() < outers + count) grow(outerLanes, outers + count);
        const PackedCounts n =
            packWindows(i, lo, groups, count, out.data(), listed, outer.data() + outers, outerLanes.data() + outers);
        listed = n.at;
        outers += n.outer;
        out[listed++] = static_cast<std::uint16_t>(n.outer);  // the end code
      }
    }
    out.resize(listed);
    trim(out, listed);
    outer.resize(outers);
    trim(outer, outers);
    outerLanes.resize(outers);
    trim(outerLanes, outers);
    return listed;
  };
  const std::uint32_t listed = packed         ? fillPacked(layer.packed)
                               : grouped      ? fillGroups(layer.groups)
                               : layer.narrow ? fill(layer.near, layer.slots.begin)
                                              : fill(layer.far, 0u);
  // The other encodings' memory is given back (it is empty unless the layer just
  // changed encoding: a layer near the 65,536-slot span would otherwise keep both).
  if (grouped || !layer.narrow) std::vector<std::uint16_t>().swap(layer.near);
  if (grouped || layer.narrow) std::vector<std::uint32_t>().swap(layer.far);
  if (!grouped || packed) std::vector<std::uint32_t>().swap(layer.groups);
  if (!packed) {
    std::vector<std::uint16_t>().swap(layer.packed);
    std::vector<std::uint16_t>().swap(layer.outer);
    std::vector<std::uint8_t>().swap(layer.outerLanes);
  }
  if (packed) {
    std::vector<std::uint32_t>().swap(layer.start);
    return;
  }
  layer.start.back() = listed;
  trim(layer.start, rows + 1);
}

// The pair forces of a chunk as records (x, y, z, 0), for pass 5 of the kernel: three
// arrays in, one record per pair out, 8 (AVX) or 4 (SSE2) pairs per transposition. The
// arrays are padded to a whole block (the kernel's chunk size is a multiple of 8).
inline void toRecords(const float* __restrict gx, const float* __restrict gy, const float* __restrict gz,
                      Force* __restrict out, std::uint32_t n) {
#if SOFTSUB_KERNEL_AVX || defined(__AVX__)
  for (std::uint32_t c = 0; c < n; c += 8) {
    const __m256 x = _mm256_load_ps(gx + c), y = _mm256_load_ps(gy + c), z = _mm256_load_ps(gz + c);
    const __m256 zero = _mm256_setzero_ps();
    const __m256 xy0 = _mm256_unpacklo_ps(x, y), xy1 = _mm256_unpackhi_ps(x, y);  // pairs 0 1 4 5, 2 3 6 7
    const __m256 z0 = _mm256_unpacklo_ps(z, zero), z1 = _mm256_unpackhi_ps(z, zero);
    const __m256 r0 = _mm256_shuffle_ps(xy0, z0, 0x44), r1 = _mm256_shuffle_ps(xy0, z0, 0xEE);  // 0 4, 1 5
    const __m256 r2 = _mm256_shuffle_ps(xy1, z1, 0x44), r3 = _mm256_shuffle_ps(xy1, z1, 0xEE);  // 2 6, 3 7
    float* o = &out[c].x;
    _mm256_store_ps(o, _mm256_permute2f128_ps(r0, r1, 0x20));
    _mm256_store_ps(o + 8, _mm256_permute2f128_ps(r2, r3, 0x20));
    _mm256_store_ps(o + 16, _mm256_permute2f128_ps(r0, r1, 0x31));
    _mm256_store_ps(o + 24, _mm256_permute2f128_ps(r2, r3, 0x31));
  }
#elif defined(__SSE2__)
  for (std::uint32_t c = 0; c < n; c += 4) {
    const __m128 x = _mm_load_ps(gx + c), y = _mm_load_ps(gy + c), z = _mm_load_ps(gz + c);
    const __m128 zero = _mm_setzero_ps();
    const __m128 xy0 = _mm_unpacklo_ps(x, y), xy1 = _mm_unpackhi_ps(x, y);  // pairs 0 1, 2 3
    const __m128 z0 = _mm_unpacklo_ps(z, zero), z1 = _mm_unpackhi_ps(z, zero);
    float* o = &out[c].x;
    _mm_store_ps(o, _mm_movelh_ps(xy0, z0));
    _mm_store_ps(o + 4, _mm_movehl_ps(z0, xy0));
    _mm_store_ps(o + 8, _mm_movelh_ps(xy1, z1));
    _mm_store_ps(o + 12, _mm_movehl_ps(z1, xy1));
  }
#else
  for (std::uint32_t c = 0; c < n; ++c) out[c] = {gx[c], gy[c], gz[c], 0.0f};
#endif
}

// Pass 3 of the kernel: value[c] = p[0] + p[1] * frac[c] with p = samples + piece[c].
// A piece's two numbers are adjacent, so each pair's are one 8-byte load, and four
// loads give four pairs' values and slopes after two shuffles (GCC's own vectorisation
// loaded each number on its own and inserted it into its lane). The same IEEE
// operations as the plain loop (no FMA), so bitwise the same values.
inline void readTable(const float* __restrict samples, const std::int32_t* __restrict piece,
                      const float* __restrict frac, float* __restrict value, std::uint32_t n) {
  std::uint32_t c = 0;
#if defined(__SSE2__)
  // Pairs c and c + 1: (a_c, b_c, a_c+1, b_c+1).
  const auto two = [&](std::uint32_t k) {
    const __m128 lo = _mm_castpd_ps(_mm_load_sd(reinterpret_cast<const double*>(samples + piece[k])));
    return _mm_loadh_pi(lo, reinterpret_cast<const __m64*>(samples + piece[k + 1]));
  };
#if SOFTSUB_KERNEL_AVX || defined(__AVX__)
  for (; c + 8 <= n; c += 8) {
    const __m128 q0 = two(c), q1 = two(c + 2), q2 = two(c + 4), q3 = two(c + 6);
    const __m256 a = _mm256_set_m128(_mm_shuffle_ps(q2, q3, 0x88), _mm_shuffle_ps(q0, q1, 0x88));
    const __m256 b = _mm256_set_m128(_mm_shuffle_ps(q2, q3, 0xDD), _mm_shuffle_ps(q0, q1, 0xDD));
    _mm256_store_ps(value + c, _mm256_add_ps(a, _mm256_mul_ps(b, _mm256_load_ps(frac + c))));
  }
#else
  for (; c + 4 <= n; c += 4) {
    const __m128 q0 = two(c), q1 = two(c + 2);
    const __m128 a = _mm_shuffle_ps(q0, q1, 0x88), b = _mm_shuffle_ps(q0, q1, 0xDD);
    _mm_store_ps(value + c, _mm_add_ps(a, _mm_mul_ps(b, _mm_load_ps(frac + c))));
  }
#endif
#endif
  for (; c < n; ++c) {
    const float* p = samples + piece[c];
    value[c] = p[0] + p[1] * frac[c];
  }
}

// A force record in a register, and the two operations pass 5 needs on it: the same
// IEEE additions and subtractions per component as three scalar ones.
#if defined(__SSE2__)
using Quad = __m128;
inline Quad loadQuad(const Force& f) { return _mm_load_ps(&f.x); }
inline void storeQuad(Force& f, Quad q) { _mm_store_ps(&f.x, q); }
inline Quad addQuad(Quad a, Quad b) { return _mm_add_ps(a, b); }
inline Quad subQuad(Quad a, Quad b) { return _mm_sub_ps(a, b); }
inline Quad zeroQuad() { return _mm_setzero_ps(); }
#else
using Quad = Force;
inline Quad loadQuad(const Force& f) { return f; }
inline void storeQuad(Force& f, Quad q) { f = q; }
inline Quad addQuad(Quad a, Quad b) { return {a.x + b.x, a.y + b.y, a.z + b.z, a.w + b.w}; }
inline Quad subQuad(Quad a, Quad b) { return {a.x - b.x, a.y - b.y, a.z - b.z, a.w - b.w}; }
inline Quad zeroQuad() { return {}; }
#endif

// Which velocity terms a table's pairs have. None: a conservative model such as the LJ
// benchmark, whose velocities are never loaded. Damping: viscosity only (a fluid's own
// function: the relative-velocity term, 10 of the pair's 25 operations, is skipped).
// Full: both (a fluid/object pair's default).
enum class VelocityTerms { None, Damping, Full };

// The pairs of the slots of one layer (see accumulatePairForces). kTerms: the table's
// velocity terms. kOneMaterial: a table of one material, whose one entry's constants
// replace the per-pair gather of entries. All six instances are this one code path.
//
// The layer's list goes through in chunks of kChunk pairs, whatever slots they belong to
// (a fluid at rest lists only about 9 partners a slot: chunks per slot would spend their
// time starting and ending short loops). Each chunk runs in passes that keep the indirect
// loads apart from the arithmetic, so that the arithmetic (square root, division, clamps)
// runs 4 wide in SIMD registers: gather the partners' offsets and their pair entries slot
// by slot, compute distances and table positions, read the table, compute the forces,
// then add them up slot by slot in partner order. Each slot's sum runs across chunks and
// is added to its force when its last partner is done: the same order and the same
// operations per pair as a plain loop over slots and partners, so the sums do not depend
// on the chunking. Branch-free: a pair listed within the skin but out of range now
// contributes exactly 0.
template <VelocityTerms kTerms, bool kOneMaterial, class Index>
void layerPairForces(const PairList::Layer& layer, const Index* __restrict list, std::uint32_t jBase,
                     const forces::InteractionTable& table, ParticleStore& s) {
  constexpr std::uint32_t kChunk = 64;
  static_assert(kChunk % 8 == 0, "toRecords() works in blocks of 8");
  constexpr bool kVelocity = kTerms != VelocityTerms::None;
  constexpr bool kRelative = kTerms == VelocityTerms::Full;
  // One material (one pair entry): its constants, instead of a gather per pair.
  const forces::PairEntry one = table.entries().front();
  const std::size_t m = table.materials();
  const forces::PairEntry* entries = table.entries().data();
  const float* __restrict samples = table.samples().data();
  // Every slot below is counted from jBase (list entries are slots - jBase).
  const float* __restrict px = s.px.data() + jBase;
  const float* __restrict py = s.py.data() + jBase;
  const float* __restrict pz = s.pz.data() + jBase;
  const float* __restrict vx = s.vx.data() + jBase;
  const float* __restrict vy = s.vy.data() + jBase;
  const float* __restrict vz = s.vz.data() + jBase;
  Force* __restrict f = s.f.data() + jBase;
  const std::uint16_t* __restrict mat = s.material.data() + jBase;
  const std::uint32_t* __restrict start = layer.start.data();
  const std::uint32_t base = layer.slots.begin - jBase;
  const std::uint32_t rows = layer.slots.end - layer.slots.begin;
  const std::uint32_t total = start[rows];
  alignas(64) float dxs[kChunk], dys[kChunk], dzs[kChunk], cut2[kChunk], invDr[kChunk], lastK[kChunk];
  alignas(64) float dvxs[kChunk], dvys[kChunk], dvzs[kChunk], damp[kChunk], relv[kChunk];
  alignas(64) float inv[kChunk], frac[kChunk], value[kChunk];
  // Initialised once: toRecords() reads a short chunk's block up to its end, and those
  // entries (left from an earlier chunk, or 0) go to records that pass 5 never reads.
  alignas(64) float gxs[kChunk] = {}, gys[kChunk] = {}, gzs[kChunk] = {};
  alignas(64) Force records[kChunk];
  alignas(64) std::int32_t piece[kChunk], offset[kChunk];
  // The slot whose sum is running (row), and its sum.
  std::uint32_t row = 0;
  Quad sum = zeroQuad();
  for (std::uint32_t q0 = 0; q0 < total; q0 += kChunk) {
    const std::uint32_t n = std::min(kChunk, total - q0);
    const Index* js = list + q0;
    // 1. Gather, slot by slot: the partners' offsets and their pair entries.
    for (std::uint32_t r = row, c = 0; c < n; ++r) {
      const std::uint32_t end = std::min(start[r + 1] - q0, n);
      const std::uint32_t i = base + r;
      const forces::PairEntry* rowEntries = entries + mat[i] * m;
      const float xi = px[i], yi = py[i], zi = pz[i];
      const float uxi = vx[i], uyi = vy[i], uzi = vz[i];
      for (; c < end; ++c) {
        const std::uint32_t j = js[c];
        dxs[c] = px[j] - xi;
        dys[c] = py[j] - yi;
        dzs[c] = pz[j] - zi;
        if constexpr (!kOneMaterial) {
          const forces::PairEntry& e = rowEntries[mat[j]];
          cut2[c] = e.cutoff2;
          invDr[c] = e.invDr;
          lastK[c] = static_cast<float>(e.lastPiece);
          offset[c] = static_cast<std::int32_t>(e.offset);
          if constexpr (kVelocity) damp[c] = e.damping;
          if constexpr (kRelative) relv[c] = e.relativeVelocity;
        }
        if constexpr (kVelocity) {
          dvxs[c] = vx[j] - uxi;
          dvys[c] = vy[j] - uyi;
          dvzs[c] = vz[j] - uzi;
        }
      }
    }
    // 2. Distances and table positions (SIMD). Out of range: inv = 0, so the pair adds
    // 0; coincident particles have no direction (inv = 0): only damping acts. The
    // position is clamped into the table (a NaN distance too: the comparison fails).
    for (std::uint32_t c = 0; c < n; ++c) {
      const float r2 = dxs[c] * dxs[c] + dys[c] * dys[c] + dzs[c] * dzs[c];
      float cutoff2 = one.cutoff2, pieces = static_cast<float>(one.lastPiece), perR = one.invDr;
      std::int32_t first = static_cast<std::int32_t>(one.offset);
      if constexpr (!kOneMaterial) {
        cutoff2 = cut2[c];
        pieces = lastK[c];
        perR = invDr[c];
        first = offset[c];
      }
      const float in = r2 < cutoff2 ? 1.0f : 0.0f;
      const float r = std::sqrt(r2);
      // Divides unconditionally (by 1 for coincident particles) so that the loop has no
      // branch: a division under a condition is not vectorised (it could trap).
      const bool apart = r > 0;
      inv[c] = (apart ? in : 0.0f) / (apart ? r : 1.0f);
      if constexpr (kVelocity) damp[c] = (kOneMaterial ? one.damping : damp[c]) * in;
      const float tMax = pieces + 1.0f, tr = r * perR;
      const float t = tr < tMax ? tr : tMax;
      const std::int32_t k = std::min(static_cast<std::int32_t>(t), static_cast<std::int32_t>(pieces));
      piece[c] = first + 2 * k;
      frac[c] = t - static_cast<float>(k);
    }
    // 3. The sampled function (the one indirect read of the table).
    readTable(samples, piece, frac, value, n);
    // 4. The pair forces (SIMD): -F n, plus the velocity terms.
    for (std::uint32_t c = 0; c < n; ++c) {
      const float nx = dxs[c] * inv[c], ny = dys[c] * inv[c], nz = dzs[c] * inv[c];
      float gx = -value[c] * nx, gy = -value[c] * ny, gz = -value[c] * nz;
      if constexpr (kRelative) {
        const float vn = (kOneMaterial ? one.relativeVelocity : relv[c]) * (dvxs[c] * nx + dvys[c] * ny + dvzs[c] * nz);
        gx += vn * nx + damp[c] * dvxs[c];
        gy += vn * ny + damp[c] * dvys[c];
        gz += vn * nz + damp[c] * dvzs[c];
      } else if constexpr (kVelocity) {
        gx += damp[c] * dvxs[c];
        gy += damp[c] * dvys[c];
        gz += damp[c] * dvzs[c];
      }
      gxs[c] = gx;
      gys[c] = gy;
      gzs[c] = gz;
    }
    // 5. Newton's third law, slot by slot in partner order, on force records: one
    // 4-wide addition to the slot's sum and one read-modify-write of the partner's
    // record per pair. A slot whose partners end in this chunk gets its sum (slots
    // without partners get their 0 here too).
    toRecords(gxs, gys, gzs, records, n);
    for (std::uint32_t c = 0; c < n;) {
      const std::uint32_t end = std::min(start[row + 1] - q0, n);
      for (; c < end; ++c) {
        const Quad g = loadQuad(records[c]);
        Force& fj = f[js[c]];
        sum = addQuad(sum, g);
        storeQuad(fj, subQuad(loadQuad(fj), g));
      }
      if (start[row + 1] - q0 <= n) {
        storeQuad(f[base + row], addQuad(loadQuad(f[base + row]), sum));
        sum = zeroQuad();
        ++row;
      }
    }
  }
  // Slots after the last pair (no partners, or the last row ending on a chunk boundary).
  for (; row < rows; ++row) {
    storeQuad(f[base + row], addQuad(loadQuad(f[base + row]), sum));
    sum = zeroQuad();
  }
}

// The instance of layerPairForces for this table and this list encoding.
template <class Index>
void layerForces(const PairList::Layer& layer, const Index* list, std::uint32_t jBase,
                 const forces::InteractionTable& table, ParticleStore& s) {
  using enum VelocityTerms;
  const VelocityTerms terms = table.hasRelativeVelocity() ? Full : table.hasVelocityTerms() ? Damping : None;
  const bool one = table.materials() == 1;
  switch (terms) {
    case None:
      return one ? layerPairForces<None, true>(layer, list, jBase, table, s)
                 : layerPairForces<None, false>(layer, list, jBase, table, s);
    case Damping:
      return one ? layerPairForces<Damping, true>(layer, list, jBase, table, s)
                 : layerPairForces<Damping, false>(layer, list, jBase, table, s);
    case Full:
      return one ? layerPairForces<Full, true>(layer, list, jBase, table, s)
                 : layerPairForces<Full, false>(layer, list, jBase, table, s);
  }
}

// The closed-form kernel's vectors, in GCC's vector extension: 8 lanes in the AVX2
// copy, 4 in the baseline one, which takes a group of 8 slots in two parts. The same
// IEEE operations per lane in both, so the same bits.
#if SOFTSUB_KERNEL_AVX || defined(__AVX__)
inline constexpr std::uint32_t kLanes = 8;
typedef float Vf __attribute__((vector_size(32)));
typedef std::int32_t Vi __attribute__((vector_size(32)));
#else
inline constexpr std::uint32_t kLanes = 4;
typedef float Vf __attribute__((vector_size(16)));
typedef std::int32_t Vi __attribute__((vector_size(16)));
#endif
inline constexpr std::uint32_t kParts = 8 / kLanes;

inline Vf loadV(const float* p) {
  Vf v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline void storeV(float* p, Vf v) { std::memcpy(p, &v, sizeof v); }
// x in every lane (one broadcast from memory; Vf{} + x would add 0 first).
inline Vf splat(float x) {
#if SOFTSUB_KERNEL_AVX || defined(__AVX__)
  return _mm256_set1_ps(x);
#else
  return Vf{x, x, x, x};
#endif
}
// b < a ? a : b per lane (b where either is NaN): one instruction (maxps) where the
// compiler would otherwise compare and blend.
inline Vf atLeast(Vf a, Vf b) {
#if SOFTSUB_KERNEL_AVX || defined(__AVX__)
  return _mm256_max_ps(a, b);
#elif defined(__SSE2__)
  return _mm_max_ps(a, b);
#else
  const Vi less = b < a;
  return reinterpret_cast<Vf>((reinterpret_cast<Vi>(a) & less) | (reinterpret_cast<Vi>(b) & ~less));
#endif
}

// a * b + c rounded once (IEEE 754 fusedMultiplyAdd) in every lane: one instruction in
// the AVX2 copy (which is built only for CPUs with FMA), std::fma lane by lane in the
// baseline one (a library call where the target has no FMA: slow, but the same bits).
// Used only where the source asks for it; the file is built with -ffp-contract=off, so
// the compiler contracts none of our operations and the copies agree bit for bit.
inline Vf fused(Vf a, Vf b, Vf c) {
#if SOFTSUB_KERNEL_AVX || (defined(__AVX__) && defined(__FMA__))
  return _mm256_fmadd_ps(a, b, c);
#else
  Vf r;
  for (std::uint32_t l = 0; l < kLanes; ++l) r[l] = std::fma(a[l], b[l], c[l]);
  return r;
#endif
}

// For each 8-bit lane mask of a group entry, the lanes as all-ones or zero (8 KB): one
// load instead of a broadcast, an AND and two comparisons per group.
struct LaneMasks {
  alignas(32) std::int32_t lanes[256][8];
  constexpr LaneMasks() : lanes() {
    for (std::uint32_t m = 0; m < 256; ++m)
      for (std::uint32_t c = 0; c < 8; ++c) lanes[m][c] = (m >> c) & 1u ? -1 : 0;
  }
};
inline constexpr LaneMasks kLaneMasks{};
// For each 7-bit lane field of a packed window code, the window's lanes (lane 0 always
// a partner: PairList::Layer::windowLanes) as all-ones or zero (4 KB).
struct WindowMasks {
  alignas(32) std::int32_t lanes[128][8];
  constexpr WindowMasks() : lanes() {
    for (std::uint32_t m = 0; m < 128; ++m)
      for (std::uint32_t c = 0; c < 8; ++c) lanes[m][c] = (PairList::Layer::windowLanes(m) >> c) & 1u ? -1 : 0;
  }
};
inline constexpr WindowMasks kWindowMasks{};
// The 8 lanes of each of three sums (x, y, z), each added in one fixed order whatever
// the parts: ((0 + 1) + (2 + 3)) + ((4 + 5) + (6 + 7)); horizontal additions in the
// AVX2 copy (a third of the instructions of lane-by-lane sums).
inline void sumLanes(const Vf* x, const Vf* y, const Vf* z, float out[3]) {
#if SOFTSUB_KERNEL_AVX || defined(__AVX__)
  const __m256 xy = _mm256_hadd_ps(x[0], y[0]);            // x01 x23 y01 y23 | x45 x67 y45 y67
  const __m256 zz = _mm256_hadd_ps(z[0], z[0]);            // z01 z23 z01 z23 | z45 z67 z45 z67
  const __m256 xyz = _mm256_hadd_ps(xy, zz);               // x0123 y0123 z0123 . | x4567 ...
  const __m128 sum = _mm_add_ps(_mm256_castps256_ps128(xyz), _mm256_extractf128_ps(xyz, 1));
  out[0] = sum[0];
  out[1] = sum[1];
  out[2] = sum[2];
#else
  const auto tree = [](const Vf* v) {
    return ((v[0][0] + v[0][1]) + (v[0][2] + v[0][3])) + ((v[1][0] + v[1][1]) + (v[1][2] + v[1][3]));
  };
  out[0] = tree(x);
  out[1] = tree(y);
  out[2] = tree(z);
#endif
}

// The Lennard-Jones force over r of 8 lanes (kParts parts) at offsets (dx, dy, dz) from
// i, exactly 0 in the lanes that are not partners (partnerLanes: all-ones or zero) or
// lie beyond the cutoff. The one copy of the arithmetic both grouped kernels use.
struct LjLanes {
  Vf a, minusB, sigma2, cutoff2, minR2;
  explicit LjLanes(const forces::ClosedFormLj& lj)
      : a(splat(lj.a)), minusB(splat(-lj.b)), sigma2(splat(lj.sigma2)), cutoff2(splat(lj.cutoff2)),
        minR2(splat(lj.minR2)) {}
  [[nodiscard]] Vf forceOverR(Vf dx, Vf dy, Vf dz, const std::int32_t* partnerLanes) const {
    const Vf r2 = fused(dz, dz, fused(dy, dy, dx * dx));
    Vi partner;
    std::memcpy(&partner, partnerLanes, sizeof partner);
    const Vi in = partner & (r2 < cutoff2);
    const Vf u = sigma2 / atLeast(minR2, r2);
    // a u³ as (a u) u², so that a u and u² run side by side: one multiplication fewer
    // on the chain that bounds this loop (docs/benchmarks.md).
    const Vf au = a * u, u2 = u * u;
    const Vf u4 = reinterpret_cast<Vf>(reinterpret_cast<Vi>(u2 * u2) & in);
    return fused(au, u2, minusB) * u4;  // F(r) / r
  }
  // Whether a partner lane lies within the cutoff: the r² and test of forceOverR.
  [[nodiscard]] bool anyWithin(Vf dx, Vf dy, Vf dz, const std::int32_t* partnerLanes) const {
    const Vf r2 = fused(dz, dz, fused(dy, dy, dx * dx));
    Vi partner;
    std::memcpy(&partner, partnerLanes, sizeof partner);
    const Vi in = partner & (r2 < cutoff2);
#if SOFTSUB_KERNEL_AVX || defined(__AVX__)
    return _mm256_movemask_ps(reinterpret_cast<__m256>(in)) != 0;
#elif defined(__SSE2__)
    return _mm_movemask_ps(reinterpret_cast<__m128>(in)) != 0;
#else
    bool any = false;
    for (std::uint32_t l = 0; l < kLanes; ++l) any = any || in[l] != 0;
    return any;
#endif
  }
};

// How many consecutive slots' own sums packedPairForces adds up together.
inline constexpr std::uint32_t kBatch = 8;

// The own sums of `count` (at most kBatch) consecutive slots, from slot - lo `first` on:
// held[b] the 8 lanes of slot first + b's x, y and z sums, each added up in sumLanes'
// order, ((0 + 1) + (2 + 3)) + ((4 + 5) + (6 + 7)), and subtracted from its sums. Why
// batched: per slot, the horizontal sums and three scalar read-modify-writes were about
// 20 instructions; for 8 slots in the AVX2 copy they are 12 horizontal additions, a few
// permutations, and one 8-wide subtraction per axis. A slot's own sum is then subtracted
// after the windows of the batch's later slots, which reach only slots after theirs
// (the forward ranges), so it still comes after the slot's last pair.
inline void subtractOwnSums(const Vf (&held)[kBatch][3][kParts], std::uint32_t count, std::ptrdiff_t first,
                            float* __restrict sx, float* __restrict sy, float* __restrict sz) {
  float* const sums[3] = {sx + first, sy + first, sz + first};
#if SOFTSUB_KERNEL_AVX || defined(__AVX__)
  for (std::uint32_t axis = 0; axis < 3; ++axis) {
    // hadd(a, b): a01 a23 b01 b23 | a45 a67 b45 b67, as sumLanes pairs the lanes.
    const __m256 h01 = _mm256_hadd_ps(held[0][axis][0], held[1][axis][0]);
    const __m256 h23 = _mm256_hadd_ps(held[2][axis][0], held[3][axis][0]);
    const __m256 h45 = _mm256_hadd_ps(held[4][axis][0], held[5][axis][0]);
    const __m256 h67 = _mm256_hadd_ps(held[6][axis][0], held[7][axis][0]);
    const __m256 q0 = _mm256_hadd_ps(h01, h23);  // slots 0-3's lanes 0123 | their lanes 4567
    const __m256 q1 = _mm256_hadd_ps(h45, h67);
    const __m256 own = _mm256_add_ps(_mm256_permute2f128_ps(q0, q1, 0x20), _mm256_permute2f128_ps(q0, q1, 0x31));
    if (count == kBatch) {
      float* const at = sums[axis];
      _mm256_storeu_ps(at, _mm256_sub_ps(_mm256_loadu_ps(at), own));
    } else {
      alignas(32) float lane[kBatch];
      _mm256_store_ps(lane, own);
      for (std::uint32_t b = 0; b < count; ++b) sums[axis][b] -= lane[b];
    }
  }
#else
  for (std::uint32_t b = 0; b < count; ++b) {
    float own[3];
    sumLanes(held[b][0], held[b][1], held[b][2], own);
    for (std::uint32_t axis = 0; axis < 3; ++axis) sums[axis][b] -= own[axis];
  }
#endif
}

// Adds n slots' sums, three arrays x, y, z, to their force records f[0, n): the same
// IEEE addition per component as a scalar loop, so the same bits. Four slots at a time
// as one 4 x 4 transposition (the records' fourth component gets + 0 and stays 0):
// GCC's own vectorisation of the scalar loop read every sum on its own and wrote every
// component on its own: this made the closed-form kernel 4% faster at cutoff 2.5 and 7%
// at 2.0 (docs/benchmarks.md, twentieth session; each slot is added back about twice,
// from its own layer's span and from the layer before).
inline void addSums(Force* __restrict f, const float* __restrict x, const float* __restrict y,
                    const float* __restrict z, std::uint32_t n) {
  std::uint32_t t = 0;
#if defined(__SSE2__)
  for (; t + 4 <= n; t += 4) {
    __m128 a = _mm_loadu_ps(x + t), b = _mm_loadu_ps(y + t), c = _mm_loadu_ps(z + t), d = _mm_setzero_ps();
    _MM_TRANSPOSE4_PS(a, b, c, d);
    storeQuad(f[t], addQuad(loadQuad(f[t]), a));
    storeQuad(f[t + 1], addQuad(loadQuad(f[t + 1]), b));
    storeQuad(f[t + 2], addQuad(loadQuad(f[t + 2]), c));
    storeQuad(f[t + 3], addQuad(loadQuad(f[t + 3]), d));
  }
#endif
  for (; t < n; ++t) {
    f[t].x += x[t];
    f[t].y += y[t];
    f[t].z += z[t];
  }
}

// The pairs of one packed layer (PairList::Layer::isPacked) with the true Lennard-Jones
// force in closed form (InteractionTable::closedFormLj): per slot i, each listed window
// of 8 slots is evaluated in 8-lane arithmetic straight from position arrays (no
// gather, no table), the lanes that are not partners or lie beyond the cutoff masked to
// exactly 0. Why: the table kernel spends most of its instructions gathering a
// partner's position and scattering its force (docs/benchmarks.md); here a window costs
// three loads and three read-modify-writes of a buffer in the same layout, whatever its
// number of partners (about 3 of 8 in a dense liquid).
// Every array is indexed by slot - lo (lo: the layer's first span slot rounded down to
// 8), so that a window's address is one register plus the walk's slot count: qx, qy, qz
// the positions and sums the forces (3 arrays x, y, z of `stride` floats), each
// readable over [0, stride), which reaches at least 7 slots past the span's end (a
// window from its last slot). The forces are added to the store after the layer, in
// slot order. Each slot's sum runs in a fixed order: pair by pair in list order, i's
// own sum (its 8 lanes added in a fixed order) after its last pair; the same whatever
// the number of threads.
// The sums are added to the store holding `locks` (setPairForces: this layer's and the
// next one's; empty in the phases, which need none).
// Outer windows (PairList::Layer::outer) come in passes of their own, each after a batch
// of kBatch slots once over a thousand are waiting, and after the layer's last: each
// slot's end code gives their count, and the slot is written that many times into
// outerSlots (one vector store of kLanes copies, and a loop only for a slot with more
// outer windows than that), so that their pass walks one flat array (a pass after every
// batch of 8 slots was 4% slower at cutoff 2.0: a loop exit a batch); an outer window
// with no partner within the cutoff costs its loads and distances and a branch (the
// same r² and test as forceOverR: exactly the zeros its evaluation would add, for
// finite positions; a NaN position, which the evaluation would spread to its window's
// lanes, is left to the blow-up check, which stops the run on it anyway).
void packedPairForces(const PairList::Layer& layer, const forces::ClosedFormLj& lj, ParticleStore& s,
                      const float* __restrict qx, const float* __restrict qy, const float* __restrict qz,
                      float* __restrict sums, std::size_t stride, std::span<std::atomic<bool>> locks) {
  const std::uint32_t lo = layer.span.begin & ~7u;
  Force* __restrict f = s.f.data();
  const std::uint16_t* __restrict code = layer.packed.data();
  float* __restrict sx = sums;
  float* __restrict sy = sums + stride;
  float* __restrict sz = sums + 2 * stride;
  for (std::size_t t = 0; t < 3 * stride; ++t) sums[t] = 0.0f;
  const LjLanes ljv(lj);
  // The 8 lanes of i's sums, kept for a batch of consecutive slots (subtractOwnSums).
  Vf held[kBatch][3][kParts] = {};
  // The slots of the outer windows waiting for their pass: room for a batch's most
  // (each slot writes kLanes entries at least) over the 1,024 that start a pass.
  constexpr std::uint32_t kOuterPass = 1024;
  std::int32_t outerSlots[kOuterPass + kBatch * PairList::Layer::kOuterMost + kLanes];
  std::uint32_t outers = 0;
  const std::uint16_t* __restrict outer = layer.outer.data();
  const std::uint8_t* __restrict outerLanes = layer.outerLanes.data();
  const std::uint32_t rows = layer.slots.end - layer.slots.begin;
  for (std::uint32_t k = 0; k < rows; ++k) {
    const std::ptrdiff_t iv = static_cast<std::ptrdiff_t>(layer.slots.begin + k) - lo;
    const Vf xi = splat(qx[iv]), yi = splat(qy[iv]), zi = splat(qz[iv]);
    Vf ax[kParts] = {}, ay[kParts] = {}, az[kParts] = {};
    // The window's first slot - lo; starts at i - 7, as PairList::Layer::packed counts
    // (which is modulo 2^32: here signed, the same slots).
    std::ptrdiff_t v = iv - 7;
    std::uint32_t e = *code++;
    for (; !PairList::Layer::isEnd(e); e = *code++) {
      if (!PairList::Layer::isWindow(e)) [[unlikely]] {  // a jump
        v += static_cast<std::int32_t>(PairList::Layer::jumpOf(e));
        continue;
      }
      v += e >> PairList::Layer::kStepShift;
      const std::int32_t* partnerLanes = kWindowMasks.lanes[e & 127u];
      for (std::uint32_t h = 0; h < kParts; ++h) {
        const std::ptrdiff_t at = v + h * kLanes;
        const Vf dx = loadV(qx + at) - xi, dy = loadV(qy + at) - yi, dz = loadV(qz + at) - zi;
        const Vf fr = ljv.forceOverR(dx, dy, dz, partnerLanes + h * kLanes);
        // The force on j is fr * (dx, dy, dz): added to i's sums and to j's, each
        // rounded once.
        ax[h] = fused(fr, dx, ax[h]);
        ay[h] = fused(fr, dy, ay[h]);
        az[h] = fused(fr, dz, az[h]);
        storeV(sx + at, fused(fr, dx, loadV(sx + at)));
        storeV(sy + at, fused(fr, dy, loadV(sy + at)));
        storeV(sz + at, fused(fr, dz, loadV(sz + at)));
      }
    }
    // e: the slot's outer windows (at most kOuterMost).
    const Vi slot = Vi{} + static_cast<std::int32_t>(iv);
    std::memcpy(outerSlots + outers, &slot, sizeof slot);
    if (e > kLanes) [[unlikely]]
      for (std::uint32_t t = kLanes; t < e; ++t) outerSlots[outers + t] = static_cast<std::int32_t>(iv);
    outers += e;
    const std::uint32_t b = k % kBatch;
    for (std::uint32_t h = 0; h < kParts; ++h) {
      held[b][0][h] = ax[h];
      held[b][1][h] = ay[h];
      held[b][2][h] = az[h];
    }
    if (b != kBatch - 1 && k + 1 != rows) continue;
    subtractOwnSums(held, b + 1, iv - b, sx, sy, sz);
    if (outers <= kOuterPass && k + 1 != rows) continue;
    for (std::uint32_t o = 0; o < outers; ++o) {
      const std::ptrdiff_t ov = outerSlots[o];
      const std::ptrdiff_t w = ov + 1 + outer[o];
      const std::int32_t* partnerLanes = kWindowMasks.lanes[outerLanes[o]];
      const Vf oxi = splat(qx[ov]), oyi = splat(qy[ov]), ozi = splat(qz[ov]);
      Vf dx[kParts], dy[kParts], dz[kParts];
      bool within = false;
      for (std::uint32_t h = 0; h < kParts; ++h) {
        const std::ptrdiff_t at = w + h * kLanes;
        dx[h] = loadV(qx + at) - oxi;
        dy[h] = loadV(qy + at) - oyi;
        dz[h] = loadV(qz + at) - ozi;
        within = within || ljv.anyWithin(dx[h], dy[h], dz[h], partnerLanes + h * kLanes);
      }
      if (!within) [[likely]]
        continue;
      Vf fx[kParts], fy[kParts], fz[kParts];
      for (std::uint32_t h = 0; h < kParts; ++h) {
        const std::ptrdiff_t at = w + h * kLanes;
        const Vf fr = ljv.forceOverR(dx[h], dy[h], dz[h], partnerLanes + h * kLanes);
        fx[h] = fr * dx[h];
        fy[h] = fr * dy[h];
        fz[h] = fr * dz[h];
        storeV(sx + at, fused(fr, dx[h], loadV(sx + at)));
        storeV(sy + at, fused(fr, dy[h], loadV(sy + at)));
        storeV(sz + at, fused(fr, dz[h], loadV(sz + at)));
      }
      float own[3];
      sumLanes(fx, fy, fz, own);
      sx[ov] -= own[0];
      sy[ov] -= own[1];
      sz[ov] -= own[2];
    }
    outer += outers;
    outerLanes += outers;
    outers = 0;
  }
  const std::uint32_t from = layer.span.begin - lo;
  const LayerLocks owned(locks);
  addSums(f + layer.span.begin, sx + from, sy + from, sz + from, layer.span.end - layer.span.begin);
}

// The pairs of one wide grouped layer (grouped, not narrow: very large layers, some
// across the grid's wrap) in closed form: per slot i, each listed aligned group of 8
// evaluated as packedPairForces does a window, the forces added straight to the store,
// partner by partner, in list order, i's own sum after its last pair.
void widePairForces(const PairList::Layer& layer, const forces::ClosedFormLj& lj, ParticleStore& s) {
  const auto n = static_cast<std::uint32_t>(s.size());
  const std::uint32_t lo = layer.span.begin & ~7u;
  Force* __restrict f = s.f.data();
  const std::uint32_t* __restrict start = layer.start.data();
  const std::uint32_t* __restrict groups = layer.groups.data();
  const LjLanes ljv(lj);
  float tx[8], ty[8], tz[8];  // the store's last slots, padded
  const std::uint32_t rows = layer.slots.end - layer.slots.begin;
  for (std::uint32_t k = 0; k < rows; ++k) {
    const std::uint32_t i = layer.slots.begin + k;
    const Vf xi = splat(s.px[i]), yi = splat(s.py[i]), zi = splat(s.pz[i]);
    Vf ax[kParts] = {}, ay[kParts] = {}, az[kParts] = {};
    for (std::uint32_t q = start[k]; q < start[k + 1]; ++q) {
      const std::uint32_t e = groups[q];
      const std::uint32_t bits = e & 255u, w = lo + (e >> 8) * 8;
      const float *xs = s.px.data() + w, *ys = s.py.data() + w, *zs = s.pz.data() + w;
      if (w + 8 > n) [[unlikely]] {
        paddedGroup(s, w, tx, ty, tz);
        xs = tx;
        ys = ty;
        zs = tz;
      }
      for (std::uint32_t h = 0; h < kParts; ++h) {
        const std::uint32_t o = h * kLanes;
        const Vf dx = loadV(xs + o) - xi, dy = loadV(ys + o) - yi, dz = loadV(zs + o) - zi;
        const Vf fr = ljv.forceOverR(dx, dy, dz, kLaneMasks.lanes[bits] + o);
        ax[h] = fused(fr, dx, ax[h]);
        ay[h] = fused(fr, dy, ay[h]);
        az[h] = fused(fr, dz, az[h]);
        const Vf gx = fr * dx, gy = fr * dy, gz = fr * dz;
        for (std::uint32_t c = 0; c < kLanes; ++c)
          if ((bits >> (o + c)) & 1u) {
            f[w + o + c].x += gx[c];
            f[w + o + c].y += gy[c];
            f[w + o + c].z += gz[c];
          }
      }
    }
    float own[3];
    sumLanes(ax, ay, az, own);
    f[i].x -= own[0];
    f[i].y -= own[1];
    f[i].z -= own[2];
  }
}

// The kernel for one layer, in its list encoding. scratch: the thread's buffer for the
// closed-form kernel, grown here as needed; locks: see packedPairForces (packed
// layers only).
inline void layerForcesOf(const PairList::Layer& layer, const forces::InteractionTable& table, ParticleStore& s,
                          std::vector<float>& scratch, std::span<std::atomic<bool>> locks) {
  if (layer.grouped) {
    if (!table.closedFormLj()) throw std::logic_error("a grouped pair list used with a table that has no closed form");
    const forces::ClosedFormLj& lj = *table.closedFormLj();
    if (!layer.narrow) return widePairForces(layer, lj, s);
    // Each of x, y, z: the span from its first slot rounded down to 8, and the 7 slots
    // a window starting at its last slot reaches past it, rounded up to 8.
    const std::uint32_t lo = layer.span.begin & ~7u;
    const std::size_t stride = (layer.span.end - lo + 7 + 7) / 8 * 8;
    // Windows read the store's arrays where it has those slots; a layer whose windows
    // could reach past the store's end (the last, usually the one before it too, whose
    // forward ranges end there) reads a copy of them padded with zeros (lanes that are
    // never partners), so that the kernel has no test per window.
    const std::size_t n = s.size();
    const bool copy = lo + stride > n;
    const std::size_t need = (copy ? 6 : 3) * stride;
    if (scratch.size() < need) {
      scratch.reserve(need);  // exactly: resize alone could double it (2 bytes an atom a thread)
      scratch.resize(need);
    }
    if (!copy) return packedPairForces(layer, lj, s, s.px.data() + lo, s.py.data() + lo, s.pz.data() + lo,
                                       scratch.data(), stride, locks);
    float* q = scratch.data() + 3 * stride;
    const float* from[3] = {s.px.data(), s.py.data(), s.pz.data()};
    for (int axis = 0; axis < 3; ++axis)
      for (std::size_t t = 0; t < stride; ++t) q[axis * stride + t] = lo + t < n ? from[axis][lo + t] : 0.0f;
    return packedPairForces(layer, lj, s, q, q + stride, q + 2 * stride, scratch.data(), stride, locks);
  }
  if (layer.narrow)
    layerForces(layer, layer.near.data(), layer.slots.begin, table, s);
  else
    layerForces(layer, layer.far.data(), 0u, table, s);
}
