#include "fluid/pair_forces.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace softsub::fluid {

namespace {

// Why a pair list: most candidates of a cell stencil are out of range, and sorting
// plus filtering them costs as much as the forces. The list keeps the pairs within
// cutoff + skin and serves several substeps. To build it, per cell the candidates (own
// cell first, then the forward neighbour cells) are copied into a contiguous buffer;
// per particle one loop computes squared distances over it (vectorised) and a
// branch-free compaction keeps the partners.
struct Buffers {
  const float* __restrict x;
  const float* __restrict y;
  const float* __restrict z;
  float* __restrict r2;
  const std::uint32_t* __restrict slot;
  std::uint32_t* __restrict kept;
  const std::uint32_t* __restrict owner;  // filled only when the list excludes owners
};

// Squared distances from (xi, yi, zi) to buffer entries [from, len), into b.r2.
inline void squaredDistances(const Buffers& b, std::uint32_t from, std::uint32_t len, float xi, float yi, float zi) {
  for (std::uint32_t k = from; k < len; ++k) {
    const float dx = b.x[k] - xi, dy = b.y[k] - yi, dz = b.z[k] - zi;
    b.r2[k] = dx * dx + dy * dy + dz * dz;
  }
}

// The slots of buffer entries [from, len) closer than sqrt(cut2) to (xi, yi, zi) go to
// b.kept. Returns how many.
inline std::uint32_t filter(const Buffers& b, std::uint32_t from, std::uint32_t len, float xi, float yi,
                            float zi, float cut2) {
  squaredDistances(b, from, len, xi, yi, zi);
  std::uint32_t n = 0;
  for (std::uint32_t k = from; k < len; ++k) {
    b.kept[n] = b.slot[k];
    n += b.r2[k] < cut2 ? 1u : 0u;
  }
  return n;
}

// filter() for a particle whose owner's particles never pair with each other (a rigid
// body): candidates of the same owner are dropped too.
inline std::uint32_t filterOthers(const Buffers& b, std::uint32_t from, std::uint32_t len, float xi, float yi,
                                  float zi, float cut2, std::uint32_t own) {
  squaredDistances(b, from, len, xi, yi, zi);
  std::uint32_t n = 0;
  for (std::uint32_t k = from; k < len; ++k) {
    b.kept[n] = b.slot[k];
    n += (b.r2[k] < cut2 && b.owner[k] != own) ? 1u : 0u;
  }
  return n;
}

}  // namespace

void PairList::build(const neighbors::CellGrid& grid, const forces::InteractionTable& table,
                     const ParticleStore& s, float skin, const ListOptions& options) {
  const std::size_t n = s.size();
  offsets_.resize(n + 1);
  partners_.clear();
  rowCut2_.resize(table.materials());
  for (std::size_t a = 0; a < rowCut2_.size(); ++a) {
    const float radius = options.rowRadius.empty() ? std::sqrt(table.rowCutoff2(a)) : options.rowRadius[a];
    const float rc = radius + skin;
    rowCut2_[a] = rc * rc;
  }
  const std::size_t cells = grid.cellCount();
  for (std::size_t c = 0; c < cells; ++c) {
    const neighbors::SlotRange own = grid.cell(c);
    const auto forward = grid.forwardRanges(c);
    std::uint32_t len = own.end - own.begin;
    for (const neighbors::SlotRange& r : forward) len += r.end - r.begin;
    if (bx_.size() < len) {  // grows to the densest neighbourhood seen, then stays
      for (auto* v : {&bx_, &by_, &bz_, &r2_}) v->resize(len);
      slot_.resize(len);
      kept_.resize(len);
      owner_.resize(len);
    }
    std::uint32_t k = 0;
    auto append = [&](std::uint32_t b, std::uint32_t e) {
      for (std::uint32_t j = b; j < e; ++j, ++k) {
        bx_[k] = s.px[j]; by_[k] = s.py[j]; bz_[k] = s.pz[j]; slot_[k] = j;
      }
    };
    const bool exclusive = options.exclusiveOwnersFrom != UINT32_MAX;
    append(own.begin, own.end);
    for (const neighbors::SlotRange& r : forward) append(r.begin, r.end);
    if (exclusive)
      for (std::uint32_t q = 0; q < len; ++q) owner_[q] = s.owner[slot_[q]];
    const Buffers b{bx_.data(), by_.data(), bz_.data(), r2_.data(), slot_.data(), kept_.data(), owner_.data()};
    // Cells come in slot order, so offsets fill in order too.
    for (std::uint32_t i = own.begin; i < own.end; ++i) {
      offsets_[i] = static_cast<std::uint32_t>(partners_.size());
      const std::uint32_t from = i - own.begin + 1;
      const float cut2 = rowCut2_[s.material[i]];
      const std::uint32_t kept =
          exclusive && s.owner[i] >= options.exclusiveOwnersFrom
              ? filterOthers(b, from, len, s.px[i], s.py[i], s.pz[i], cut2, s.owner[i])
              : filter(b, from, len, s.px[i], s.py[i], s.pz[i], cut2);
      partners_.insert(partners_.end(), kept_.begin(), kept_.begin() + kept);
    }
  }
  offsets_[n] = static_cast<std::uint32_t>(partners_.size());
}

void accumulatePairForces(const PairList& list, const forces::InteractionTable& table, ParticleStore& s) {
  const std::size_t m = table.materials();
  const forces::PairEntry* entries = table.entries().data();
  const float* __restrict samples = table.samples().data();
  const float* __restrict px = s.px.data();
  const float* __restrict py = s.py.data();
  const float* __restrict pz = s.pz.data();
  const float* __restrict vx = s.vx.data();
  const float* __restrict vy = s.vy.data();
  const float* __restrict vz = s.vz.data();
  float* __restrict fx = s.fx.data();
  float* __restrict fy = s.fy.data();
  float* __restrict fz = s.fz.data();
  const std::uint16_t* __restrict mat = s.material.data();
  const std::size_t n = s.size();
  for (std::size_t i = 0; i < n; ++i) {
    const forces::PairEntry* row = entries + mat[i] * m;
    const float xi = px[i], yi = py[i], zi = pz[i];
    const float uxi = vx[i], uyi = vy[i], uzi = vz[i];
    float ax = 0, ay = 0, az = 0;
    // The whole interaction model, one formula for every pair kind.
    for (const std::uint32_t j : list.partners(i)) {
      const float dx = px[j] - xi, dy = py[j] - yi, dz = pz[j] - zi;
      const float r2 = dx * dx + dy * dy + dz * dz;
      const forces::PairEntry& e = row[mat[j]];
      if (!(r2 < e.cutoff2)) continue;  // listed within the skin, not in range now
      const float r = std::sqrt(r2);
      // Coincident particles have no direction: only the damping term acts.
      const float inv = r > 0 ? 1.0f / r : 0.0f;
      const float t = r * e.invDr;
      const std::uint32_t k = std::min(static_cast<std::uint32_t>(t), e.lastPiece);
      const float* piece = samples + e.offset + 2 * k;
      const float f = piece[0] + piece[1] * (t - static_cast<float>(k));
      const float nx = dx * inv, ny = dy * inv, nz = dz * inv;
      const float dvx = vx[j] - uxi, dvy = vy[j] - uyi, dvz = vz[j] - uzi;
      const float vn = dvx * nx + dvy * ny + dvz * nz;
      const float along = -f + e.relativeVelocity * vn;
      const float gx = along * nx + e.damping * dvx;
      const float gy = along * ny + e.damping * dvy;
      const float gz = along * nz + e.damping * dvz;
      ax += gx; ay += gy; az += gz;
      fx[j] -= gx; fy[j] -= gy; fz[j] -= gz;
    }
    fx[i] += ax; fy[i] += ay; fz[i] += az;
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
