#include "fluid/pair_forces.h"

#include <algorithm>
#include <cmath>

namespace softsub::fluid {

namespace {

// Why two passes: most candidates from a cell stencil are out of range. The first
// pass computes squared distances over a contiguous slot range (a plain loop the
// compiler vectorises), the second keeps the in-range ones, and only those pay for
// the sqrt, the table lookup and the scatter to j.
constexpr std::uint32_t kChunk = 256;

struct Scratch {
  float r2[kChunk];
  std::uint32_t j[kChunk];
  float r2Kept[kChunk];
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

// Pass 1 + 2 on slots [b, b + len), len <= kChunk: returns the kept count.
inline std::uint32_t filter(const Arrays& a, Scratch& sc, std::uint32_t b, std::uint32_t len, float xi,
                            float yi, float zi, float cut2) {
  const float* __restrict px = a.px + b;
  const float* __restrict py = a.py + b;
  const float* __restrict pz = a.pz + b;
  float* __restrict r2 = sc.r2;
  for (std::uint32_t k = 0; k < len; ++k) {
    const float dx = px[k] - xi, dy = py[k] - yi, dz = pz[k] - zi;
    r2[k] = dx * dx + dy * dy + dz * dz;
  }
  std::uint32_t n = 0;
  for (std::uint32_t k = 0; k < len; ++k) {
    sc.j[n] = b + k;
    sc.r2Kept[n] = r2[k];
    n += r2[k] < cut2 ? 1u : 0u;
  }
  return n;
}

// The whole interaction model, one formula for every pair kind.
inline void interact(const Arrays& a, const Scratch& sc, std::uint32_t n, const forces::PairEntry* row,
                     float xi, float yi, float zi, float uxi, float uyi, float uzi, float& ax, float& ay,
                     float& az) {
  for (std::uint32_t q = 0; q < n; ++q) {
    const std::uint32_t j = sc.j[q];
    const float r2 = sc.r2Kept[q];
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
  Scratch sc;

  const std::size_t cells = grid.cellCount();
  for (std::size_t c = 0; c < cells; ++c) {
    const neighbors::SlotRange own = grid.cell(c);
    const auto forward = grid.forwardRanges(c);
    for (std::uint32_t i = own.begin; i < own.end; ++i) {
      const forces::PairEntry* row = entries + a.mat[i] * m;
      const float cut2 = table.rowCutoff2(a.mat[i]);
      const float xi = a.px[i], yi = a.py[i], zi = a.pz[i];
      const float uxi = a.vx[i], uyi = a.vy[i], uzi = a.vz[i];
      float ax = 0, ay = 0, az = 0;
      auto range = [&](std::uint32_t b, std::uint32_t e) {
        for (; b < e; b += kChunk) {
          const std::uint32_t len = std::min(kChunk, e - b);
          const std::uint32_t n = filter(a, sc, b, len, xi, yi, zi, cut2);
          interact(a, sc, n, row, xi, yi, zi, uxi, uyi, uzi, ax, ay, az);
        }
      };
      range(i + 1, own.end);
      for (const neighbors::SlotRange& r : forward) range(r.begin, r.end);
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
