// The seed's table (report 3.4.1): time per frame of 8 substeps for one fluid of
// 1,000 .. 1,000,000 particles in a container (BM_SeedFrame; the Time column is ms per
// frame), and a slumping cube in full motion (BM_SlumpingCube); plus particle-steps per
// second, bytes per particle and substeps per pair list. See docs/benchmarks.md.
// Run: build-bench/bench/softsub-bench --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>

#include "solver/simulation.h"
#include "support/scenarios.h"

namespace {

using namespace softsub;

// Each case first runs `settle` frames so that it is measured in a steady regime, not
// in the first lattice frames (whose pair-list rebuild rate differs with size).
void run(benchmark::State& st, solver::Model& model, solver::State& state, std::size_t n, int settle) {
  solver::Simulation sim(model, std::move(state));
  for (int f = 0; f < settle; ++f) sim.advanceFrame();
  const std::int64_t builds0 = sim.listBuilds();
  for (auto _ : st) sim.advanceFrame();
  const double steps = static_cast<double>(st.iterations()) * model.substeps;
  st.counters["particle-steps/s"] =
      benchmark::Counter(steps * static_cast<double>(n), benchmark::Counter::kIsRate);
  st.counters["bytes/particle"] = static_cast<double>(sim.memoryBytes()) / static_cast<double>(n);
  st.counters["substeps/list"] = steps / static_cast<double>(std::max<std::int64_t>(1, sim.listBuilds() - builds0));
}

// The seed's table: a pool of goo 10 layers deep in a container, after it has settled
// (the scaling check).
void BM_SeedFrame(benchmark::State& st) {
  const auto n = static_cast<std::size_t>(st.range(0));
  solver::Model model;
  solver::State state;
  scenarios::fluidPool(n, 1.0, 10, model, state);
  run(st, model, state, n, n >= 1000000 ? 12 : 24);  // half a second to one second
}
BENCHMARK(BM_SeedFrame)->Arg(1000)->Arg(5000)->Arg(10000)->Arg(50000)->Arg(100000)->Arg(200000)
    ->Arg(1000000)->Unit(benchmark::kMillisecond)->MinTime(1.0);

// The scaling check on the same simulated frames: BM_SeedFrame runs as many frames as
// fit in its time, so a small pool is measured hundreds of frames later than a large
// one, settled and rebuilding its list a quarter as often (docs/benchmarks.md). Here
// every size is timed over frames 24 to 39 of the same pool, from a fresh start in
// each repetition (the simulation is deterministic: the same work every time).
void BM_SeedScaling(benchmark::State& st) {
  const auto n = static_cast<std::size_t>(st.range(0));
  solver::Model model;
  solver::State state;
  scenarios::fluidPool(n, 1.0, 10, model, state);
  run(st, model, state, n, 24);
}
BENCHMARK(BM_SeedScaling)->Arg(10000)->Arg(100000)->Arg(1000000)->Iterations(16)->Repetitions(3)
    ->Unit(benchmark::kMillisecond);

// A cube of goo slumping on the floor (more surface for small n, more motion).
void BM_SlumpingCube(benchmark::State& st) {
  const auto n = static_cast<std::size_t>(st.range(0));
  solver::Model model;
  solver::State state;
  scenarios::fluidBlock(n, 1.0, model, state);
  run(st, model, state, n, 4);  // measured while it slumps
}
BENCHMARK(BM_SlumpingCube)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond)->MinTime(1.0);

// A ball of goo falling onto the floor of a container from a quarter of its radius
// above it, timed over its first 36 frames (it lands at about frame 19 and splashes): the case of the pair
// list's second validity test (solver/list_guard.h), which keeps the lists the ball's
// fall alone would make stale. Second argument: the test on (1) or off (0). Every
// repetition starts afresh, so both time the same frames.
void BM_FallingBall(benchmark::State& st) {
  const auto n = static_cast<std::size_t>(st.range(0));
  solver::Model model = scenarios::oneFluidModel(n);
  model.listGuard = st.range(1) != 0;
  const double radius = std::cbrt(3.0 * static_cast<double>(n) / (4.0 * 3.14159265358979));
  solver::Container c;
  c.lo = {-3 * radius, 0, -3 * radius};
  c.hi = {3 * radius, 8 * radius, 3 * radius};
  model.container = c;
  solver::State state;
  state.particles.reserve(n);
  const auto side = static_cast<int>(std::ceil(2 * radius)) + 2;
  for (int i = -side; i <= side && state.particles.size() < n; ++i)
    for (int j = -side; j <= side && state.particles.size() < n; ++j)
      for (int k = -side; k <= side && state.particles.size() < n; ++k)
        if (i * i + j * j + k * k <= radius * radius + 1e-9)
          state.particles.add(static_cast<float>(i), static_cast<float>(1.25 * radius + j),
                              static_cast<float>(k), 0, -2, 0, 0, 0);
  model.fluids[0].count = static_cast<std::uint32_t>(state.particles.size());
  const double count = static_cast<double>(state.particles.size());
  solver::Simulation sim(model, std::move(state));
  for (auto _ : st) sim.advanceFrame();
  const double steps = static_cast<double>(st.iterations()) * model.substeps;
  st.counters["particle-steps/s"] = benchmark::Counter(steps * count, benchmark::Counter::kIsRate);
  st.counters["substeps/list"] = steps / static_cast<double>(std::max<std::int64_t>(1, sim.listBuilds()));
}
BENCHMARK(BM_FallingBall)
    ->Args({25000, 0})
    ->Args({25000, 1})
    ->Iterations(36)
    ->Repetitions(3)
    ->Unit(benchmark::kMillisecond);

// A dam of goo flat in z (two lattice layers deep, twice as long in x as high in y)
// collapsing in a container just as deep: the grid must cut it into layers along x, or
// both cores share one or two layers (thread scaling, docs/benchmarks.md).
void BM_FlatDam(benchmark::State& st) {
  const auto n = static_cast<std::size_t>(st.range(0));
  solver::Model model = scenarios::oneFluidModel(n);
  const auto high = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(n) / 4.0)));
  const std::size_t wide = 2 * high;
  solver::Container c;
  c.lo = {-1.0, 0, -1.2};
  c.hi = {4.0 * static_cast<double>(wide), 2.0 * static_cast<double>(high), 1.2};
  model.container = c;
  solver::State state;
  state.particles.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = k % wide, j = (k / wide) % high, l = k / (wide * high);
    state.particles.add(static_cast<float>(i), static_cast<float>(0.5 + static_cast<double>(j)),
                        static_cast<float>(l % 2) - 0.5f, 0, 0, 0, 0, 0);
  }
  run(st, model, state, n, 4);  // measured while it collapses
}
BENCHMARK(BM_FlatDam)->Arg(20000)->Unit(benchmark::kMillisecond)->MinTime(1.0);

}  // namespace

BENCHMARK_MAIN();
