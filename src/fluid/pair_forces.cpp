#include "fluid/pair_forces.h"

#include <algorithm>
#include <cmath>

namespace softsub::fluid {

void accumulatePairForces(const neighbors::CellGrid& grid, const forces::InteractionTable& table,
                          ParticleStore& s) {
  const std::size_t m = table.materials();
  const forces::PairEntry* entries = table.entries().data();
  const float* samples = table.samples().data();
  const float* px = s.px.data();
  const float* py = s.py.data();
  const float* pz = s.pz.data();
  const float* vx = s.vx.data();
  const float* vy = s.vy.data();
  const float* vz = s.vz.data();
  float* fx = s.fx.data();
  float* fy = s.fy.data();
  float* fz = s.fz.data();
  const std::uint16_t* mat = s.material.data();

  // One pair: the whole interaction model in one place.
  auto pair = [&](std::uint32_t i, std::uint32_t j, const forces::PairEntry* row, float xi, float yi,
                  float zi, float uxi, float uyi, float uzi, float& ax, float& ay, float& az) {
    const float dx = px[j] - xi, dy = py[j] - yi, dz = pz[j] - zi;
    const float r2 = dx * dx + dy * dy + dz * dz;
    const forces::PairEntry& e = row[mat[j]];
    if (!(r2 < e.cutoff2)) return;
    const float r = std::sqrt(r2);
    // Coincident particles have no direction: only the velocity terms act.
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
    (void)i;
  };

  const std::size_t cells = grid.cellCount();
  for (std::size_t c = 0; c < cells; ++c) {
    const neighbors::SlotRange own = grid.cell(c);
    const auto forward = grid.forwardRanges(c);
    for (std::uint32_t i = own.begin; i < own.end; ++i) {
      const forces::PairEntry* row = entries + mat[i] * m;
      const float xi = px[i], yi = py[i], zi = pz[i];
      const float uxi = vx[i], uyi = vy[i], uzi = vz[i];
      float ax = 0, ay = 0, az = 0;
      for (std::uint32_t j = i + 1; j < own.end; ++j) pair(i, j, row, xi, yi, zi, uxi, uyi, uzi, ax, ay, az);
      for (const neighbors::SlotRange& r : forward)
        for (std::uint32_t j = r.begin; j < r.end; ++j)
          pair(i, j, row, xi, yi, zi, uxi, uyi, uzi, ax, ay, az);
      fx[i] += ax; fy[i] += ay; fz[i] += az;
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
