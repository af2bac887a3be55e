#pragma once
// Particle clouds shared by tests and benchmarks (needs only core).
#include <cstdint>
#include <random>

#include "core/particle_store.h"

namespace softsub::scenarios {

/// n particles uniformly in [lo, hi]^3 with random velocities in [-vmax, vmax] and
/// materials cycling over `materials`. Deterministic for a seed.
inline ParticleStore randomCloud(std::size_t n, float lo, float hi, float vmax, std::uint16_t materials,
                                 std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(lo, hi), w(-vmax, vmax);
  ParticleStore s;
  s.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto m = static_cast<std::uint16_t>(i % materials);
    s.add(u(rng), u(rng), u(rng), w(rng), w(rng), w(rng), m, m);
  }
  return s;
}

}  // namespace softsub::scenarios
