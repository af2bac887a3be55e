#include "fluid/pair_forces.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace softsub::fluid {

namespace {

// Why this shape: most candidates of a cell stencil are out of range, and the ranges
// of one cell's neighbours are short. So per cell the candidate particles (own cell
// first, then the forward neighbour cells) are copied once into a contiguous buffer;
// per particle, one long loop computes squared distances over it (vectorised), a
// compaction keeps the in-range ones, and only those pay for the sqrt, the table
// lookup and the scatter to j.
struct CellScratch {
  std::vector<float> x, y, z, r2, r2Kept;
  std::vector<std::uint32_t> slot, kept;
  void resize(std::size_t n) {
    if (x.size() >= n) return;
    for (auto* v : {&x, &y, &z, &r2, &r2Kept}) v->resize(n);
    slot.resize(n);
    kept.resize(n);
  }
};

struct Arrays {
  const float* __restrict px;
  const float* __restrict py;
  const float* __restrict pz;
  const float* __restrict vx;
  const float* __restrict vy;
  const float* __restrict vz;
  float* __restrict fx;
  float* __restrict fy;
  float* __restrict fz;
  const std::uint16_t* __restrict mat;
  const float* __restrict samples;
};

// Squared distances from (xi, yi, zi) to buffer entries [from, len), kept if < cut2.
inline std::uint32_t filter(CellScratch& sc, std::uint32_t from, std::uint32_t len, float xi, float yi,
                            float zi, float cut2) {
  const float* __restrict bx = sc.x.data();
  const float* __restrict by = sc.y.data();
  const float* __restrict bz = sc.z.data();
  float* __restrict r2 = sc.r2.data();
  for (std::uint32_t k = from; k < len; ++k) {
    const float dx = bx[k] - xi, dy = by[k] - yi, dz = bz[k] - zi;
    r2[k] = dx * dx + dy * dy + dz * dz;
  }
  std::uint32_t* __restrict kept = sc.kept.data();
  float* __restrict r2Kept = sc.r2Kept.data();
  const std::uint32_t* __restrict slot = sc.slot.data();
  std::uint32_t n = 0;
  for (std::uint32_t k = from; k < len; ++k) {
    kept[n] = slot[k];
    r2Kept[n] = r2[k];
    n += r2[k] < cut2 ? 1u : 0u;
  }
  return n;
}

// The whole interaction model, one formula for every pair kind.
inline void interact(const Arrays& a, const CellScratch& sc, std::uint32_t n, const forces::PairEntry* row,
                     float xi, float yi, float zi, float uxi, float uyi, float uzi, float& ax, float& ay,
                     float& az) {
  const std::uint32_t* __restrict kept = sc.kept.data();
  const float* __restrict r2Kept = sc.r2Kept.data();
  for (std::uint32_t q = 0; q < n; ++q) {
    const std::uint32_t j = kept[q];
    const float r2 = r2Kept[q];
    const forces::PairEntry& e = row[a.mat[j]];
    if (!(r2 < e.cutoff2)) continue;  // only with mixed cutoffs in one row
    const float r = std::sqrt(r2);
    // Coincident particles have no direction: only the velocity terms act.
    const float inv = r > 0 ? 1.0f / r : 0.0f;
    const float t = r * e.invDr;
    const std::uint32_t k = std::min(static_cast<std::uint32_t>(t), e.lastPiece);
    const float* piece = a.samples + e.offset + 2 * k;
    const float f = piece[0] + piece[1] * (t - static_cast<float>(k));
    const float nx = (a.px[j] - xi) * inv, ny = (a.py[j] - yi) * inv, nz = (a.pz[j] - zi) * inv;
    const float dvx = a.vx[j] - uxi, dvy = a.vy[j] - uyi, dvz = a.vz[j] - uzi;
    const float vn = dvx * nx + dvy * ny + dvz * nz;
    const float along = -f + e.relativeVelocity * vn;
    const float gx = along * nx + e.damping * dvx;
    const float gy = along * ny + e.damping * dvy;
    const float gz = along * nz + e.damping * dvz;
    ax += gx; ay += gy; az += gz;
    a.fx[j] -= gx; a.fy[j] -= gy; a.fz[j] -= gz;
  }
}

}  // namespace

void accumulatePairForces(const neighbors::CellGrid& grid, const forces::InteractionTable& table,
                          ParticleStore& s) {
  const std::size_t m = table.materials();
  const forces::PairEntry* entries = table.entries().data();
  const Arrays a{s.px.data(), s.py.data(), s.pz.data(), s.vx.data(), s.vy.data(), s.vz.data(),
                 s.fx.data(), s.fy.data(), s.fz.data(), s.material.data(), table.samples().data()};
  // Reused across calls (and grown only when a denser cell neighbourhood appears).
  static thread_local CellScratch sc;

  const std::size_t cells = grid.cellCount();
  for (std::size_t c = 0; c < cells; ++c) {
    const neighbors::SlotRange own = grid.cell(c);
    const auto forward = grid.forwardRanges(c);
    std::uint32_t len = own.end - own.begin;
    for (const neighbors::SlotRange& r : forward) len += r.end - r.begin;
    sc.resize(len);
    std::uint32_t k = 0;
    auto append = [&](std::uint32_t b, std::uint32_t e) {
      for (std::uint32_t j = b; j < e; ++j, ++k) {
        sc.x[k] = a.px[j]; sc.y[k] = a.py[j]; sc.z[k] = a.pz[j]; sc.slot[k] = j;
      }
    };
    append(own.begin, own.end);
    for (const neighbors::SlotRange& r : forward) append(r.begin, r.end);

    for (std::uint32_t i = own.begin; i < own.end; ++i) {
      const forces::PairEntry* row = entries + a.mat[i] * m;
      const float xi = a.px[i], yi = a.py[i], zi = a.pz[i];
      // Own-cell partners after i, then every forward cell: each pair once.
      const std::uint32_t n = filter(sc, i - own.begin + 1, len, xi, yi, zi, table.rowCutoff2(a.mat[i]));
      float ax = 0, ay = 0, az = 0;
      interact(a, sc, n, row, xi, yi, zi, a.vx[i], a.vy[i], a.vz[i], ax, ay, az);
      a.fx[i] += ax; a.fy[i] += ay; a.fz[i] += az;
    }
  }
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
