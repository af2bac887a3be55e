#include "core/particle_store.h"

#include <cassert>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace softsub {

void ParticleStore::reserve(std::size_t n) {
  for (auto* a : {&px, &py, &pz, &vx, &vy, &vz, &fx, &fy, &fz}) a->reserve(n);
  material.reserve(n);
  owner.reserve(n);
  id.reserve(n);
}

std::size_t ParticleStore::add(float x, float y, float z, float vxi, float vyi, float vzi,
                               std::uint16_t materialIndex, std::uint32_t ownerIndex) {
  const std::size_t slot = size();
  px.push_back(x); py.push_back(y); pz.push_back(z);
  vx.push_back(vxi); vy.push_back(vyi); vz.push_back(vzi);
  fx.push_back(0); fy.push_back(0); fz.push_back(0);
  material.push_back(materialIndex);
  owner.push_back(ownerIndex);
  id.push_back(static_cast<std::uint32_t>(slot));
  return slot;
}

namespace {
template <class T>
void gather(std::vector<T>& a, std::span<const std::uint32_t> order, std::vector<T>& scratch) {
  const std::size_t n = order.size();
  scratch.resize(n);
  // In parallel over fixed blocks: each element is written once, whatever the split.
  using Range = tbb::blocked_range<std::size_t>;
  tbb::parallel_for(Range(0, n, 16384), [&](const Range& r) {
    for (std::size_t k = r.begin(); k != r.end(); ++k) scratch[k] = a[order[k]];
  });
  a.swap(scratch);
}
}  // namespace

void ParticleStore::permute(std::span<const std::uint32_t> order) {
  assert(order.size() == size());
  for (auto* a : {&px, &py, &pz, &vx, &vy, &vz, &fx, &fy, &fz}) gather(*a, order, scratchF_);
  gather(material, order, scratchS_);
  gather(owner, order, scratchU_);
  gather(id, order, scratchU_);
}

void ParticleStore::slotsById(std::vector<std::uint32_t>& out) const {
  out.resize(size());
  for (std::size_t s = 0; s < size(); ++s) out[id[s]] = static_cast<std::uint32_t>(s);
}

}  // namespace softsub
