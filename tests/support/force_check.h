#pragma once
// The forces a store holds against a brute-force sum over all its pairs (double
// precision, fluid::referencePairForces): for tests that step a simulation whose forces
// depend on positions only, so that a pair missing from a pair list shows.
#include <algorithm>
#include <cmath>
#include <vector>

#include "fluid/pair_forces.h"

namespace softsub::testing {

/// The largest |f - reference| (L1 over the three axes) over the particles, relative to
/// the largest |reference| (at least 1).
inline double relativeForceError(const forces::InteractionTable& table, const ParticleStore& p) {
  std::vector<double> rx, ry, rz;
  fluid::referencePairForces(table, p, rx, ry, rz);
  double worst = 0, scale = 1;
  for (std::size_t i = 0; i < p.size(); ++i) {
    worst =
        std::max(worst, std::abs(p.f[i].x - rx[i]) + std::abs(p.f[i].y - ry[i]) + std::abs(p.f[i].z - rz[i]));
    scale = std::max(scale, std::abs(rx[i]) + std::abs(ry[i]) + std::abs(rz[i]));
  }
  return worst / scale;
}

}  // namespace softsub::testing
