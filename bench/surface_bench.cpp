// Surfaces (issue #5): seconds per frame to turn a fluid of 10,000 .. 1,000,000 particles
// into a level set and a closed mesh. The fluid is a lattice ball (spacing = particle size
// = 1) with every particle jittered by up to 0.2 in each axis, a dense blob like a settled
// pool's interior. BM_SurfaceFrame is a whole frame (field, threshold, level-set rebuild,
// meshing with normals); BM_SurfaceVdbLevelSet is the .vdb path (field, threshold and
// the rebuild into a narrow-band signed-distance level set, no mesh). See docs/benchmarks.md.
// Run: build-bench/bench/softsub-surface-bench --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "surface/surface.h"

namespace {

namespace ss = softsub::surface;

// About n particles: a lattice ball of the radius that holds n, each point moved by a
// deterministic jitter in [-0.2, 0.2] per axis (a fixed-seed LCG: the same blob every run).
std::vector<float> jitteredBall(std::size_t n) {
  const double r = std::cbrt(3.0 * static_cast<double>(n) / (4.0 * std::numbers::pi));
  const int m = static_cast<int>(std::ceil(r));
  std::uint64_t state = 0x9E3779B97F4A7C15ull;
  const auto jitter = [&state] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<float>((static_cast<double>(state >> 11) / 9007199254740992.0 - 0.5) * 0.4);
  };
  std::vector<float> xyz;
  xyz.reserve(3 * n + 3 * 1024);
  for (int i = -m; i <= m; ++i)
    for (int j = -m; j <= m; ++j)
      for (int k = -m; k <= m; ++k)
        if (double(i) * i + double(j) * j + double(k) * k <= r * r) {
          xyz.push_back(static_cast<float>(i) + jitter());
          xyz.push_back(static_cast<float>(j) + jitter());
          xyz.push_back(static_cast<float>(k) + jitter());
        }
  return xyz;
}

void BM_SurfaceFrame(benchmark::State& st) {
  const auto xyz = jitteredBall(static_cast<std::size_t>(st.range(0)));
  ss::SurfaceMesh m;
  for (auto _ : st) {
    m = ss::meshParticles(xyz, 1.0);
    benchmark::DoNotOptimize(m.vertices.data());
  }
  const double rest = static_cast<double>(xyz.size() / 3);
  st.counters["particles"] = rest;
  st.counters["triangles"] = static_cast<double>(m.triangles.size());
  st.counters["volume/rest"] = ss::enclosedVolume(m) / rest;
}
BENCHMARK(BM_SurfaceFrame)->Arg(10000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->MinTime(1.0);

void BM_SurfaceVdbLevelSet(benchmark::State& st) {
  const auto xyz = jitteredBall(static_cast<std::size_t>(st.range(0)));
  std::size_t band = 0;
  for (auto _ : st) {
    const auto ls = ss::LevelSet::fromParticles(xyz, 1.0);
    band = ls.activeVoxelCount();
  }
  st.counters["band voxels"] = static_cast<double>(band);
}
BENCHMARK(BM_SurfaceVdbLevelSet)->Arg(10000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->MinTime(1.0);

}  // namespace

BENCHMARK_MAIN();
