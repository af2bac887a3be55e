#include "core/particle_store.h"

#include <algorithm>
#include <cassert>
#include <cstring>
#include <type_traits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace softsub {

void ParticleStore::reserve(std::size_t n) {
  for (auto* a : {&px, &py, &pz, &vx, &vy, &vz}) a->reserve(n);
  f.reserve(n);
  material.reserve(n);
  owner.reserve(n);
  id.reserve(n);
}

std::size_t ParticleStore::add(float x, float y, float z, float vxi, float vyi, float vzi,
                               std::uint16_t materialIndex, std::uint32_t ownerIndex) {
  const std::size_t slot = size();
  px.push_back(x); py.push_back(y); pz.push_back(z);
  vx.push_back(vxi); vy.push_back(vyi); vz.push_back(vzi);
  f.push_back({});
  material.push_back(materialIndex);
  owner.push_back(ownerIndex);
  id.push_back(static_cast<std::uint32_t>(slot));
  return slot;
}

namespace {
using Range = tbb::blocked_range<std::size_t>;
constexpr std::size_t kBlock = 16384;

// to[k] = from[order[k]], in parallel over fixed blocks: each element is written once,
// whatever the split. Eight at a time: where the eight come from eight consecutive slots
// (most of a re-sort in which few particles changed cell: the rest keep their order and
// shift in runs), one contiguous copy that vectorises instead of eight indexed loads.
template <class From, class To>
void gather(const From* __restrict from, std::span<const std::uint32_t> order, To* __restrict to) {
  constexpr std::size_t kRun = 8;
  const std::uint32_t* __restrict o = order.data();
  tbb::parallel_for(Range(0, order.size(), kBlock), [&](const Range& r) {
    std::size_t k = r.begin();
    for (; k + kRun <= r.end(); k += kRun) {
      const std::uint32_t first = o[k];
      // Whether the eight are first, first + 1, ...: two 4-wide comparisons (GCC's vector
      // extension; it left the plain loop scalar).
      using U4 = std::uint32_t __attribute__((vector_size(16)));
      U4 lo, hi;
      std::memcpy(&lo, o + k, sizeof lo);
      std::memcpy(&hi, o + k + 4, sizeof hi);
      const U4 step = {0, 1, 2, 3};
      const U4 apart = (lo - (first + step)) | (hi - (first + 4 + step));
      if ((apart[0] | apart[1] | apart[2] | apart[3]) == 0) {
        if constexpr (std::is_same_v<From, To>)
          std::memcpy(to + k, from + first, kRun * sizeof(To));  // fixed size: inline moves
        else
          for (std::size_t t = 0; t < kRun; ++t) to[k + t] = static_cast<To>((from + first)[t]);
      } else
        for (std::size_t t = 0; t < kRun; ++t) to[k + t] = static_cast<To>(from[o[k + t]]);
    }
    for (; k != r.end(); ++k) to[k] = static_cast<To>(from[o[k]]);
  });
}

template <class T>
void copyBack(std::span<const std::uint32_t> scratch, std::vector<T>& to) {
  tbb::parallel_for(Range(0, to.size(), kBlock), [&](const Range& r) {
    for (std::size_t k = r.begin(); k != r.end(); ++k) to[k] = static_cast<T>(scratch[k]);
  });
}
}  // namespace

void ParticleStore::permute(std::span<const std::uint32_t> order, std::span<std::uint32_t> scratch) {
  const std::size_t n = size();
  assert(order.size() == n && scratch.size() >= n && f.size() == n);
  // The float arrays pass their memory along a chain: the first is gathered into the
  // force records' memory (4n floats, whose values are dropped), each next one into the
  // buffer the previous one left free (the two vectors swap), and the first array's
  // values are copied back into the last free buffer: one copy instead of six.
  float* held = reinterpret_cast<float*>(f.data());  // the first array's new values
  std::vector<float>* const arrays[6] = {&px, &py, &pz, &vx, &vy, &vz};
  gather(px.data(), order, held);
  for (int a = 1; a < 6; ++a) {  // arrays[0]'s buffer is free
    gather(arrays[a]->data(), order, arrays[0]->data());
    arrays[a]->swap(*arrays[0]);
  }
  tbb::parallel_for(Range(0, n, kBlock), [&](const Range& r) {
    std::copy(held + r.begin(), held + r.end(), px.data() + r.begin());
  });
  tbb::parallel_for(Range(0, n, kBlock), [&](const Range& r) {
    for (std::size_t k = r.begin(); k != r.end(); ++k) f[k] = Force{};
  });
  gather(material.data(), order, scratch.data());
  copyBack(scratch, material);
  gather(owner.data(), order, scratch.data());
  copyBack(scratch, owner);
  gather(id.data(), order, scratch.data());
  copyBack(scratch, id);
}

void ParticleStore::slotsById(std::vector<std::uint32_t>& out) const {
  out.resize(size());
  for (std::size_t s = 0; s < size(); ++s) out[id[s]] = static_cast<std::uint32_t>(s);
}

}  // namespace softsub
