// The seed's table (report 3.4.1): time per frame of 8 substeps for one fluid of
// 1,000 .. 200,000 particles in a container (the Time column, ms per frame), plus
// particle-steps per second and bytes per particle.
// Run: build-bench/bench/softsub-bench --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include "solver/simulation.h"
#include "support/scenarios.h"

namespace {

using namespace softsub;

// The block first settles for a few frames so the benchmark measures a fluid in
// motion at rest density, not the first lattice frames.
void BM_SeedFrame(benchmark::State& st) {
  const auto n = static_cast<std::size_t>(st.range(0));
  solver::Model model;
  solver::State state;
  scenarios::fluidBlock(n, 1.0, model, state);
  solver::Simulation sim(model, std::move(state));
  for (int f = 0; f < 4; ++f) sim.advanceFrame();
  for (auto _ : st) sim.advanceFrame();
  const double steps = static_cast<double>(st.iterations()) * model.substeps;
  st.counters["particle-steps/s"] =
      benchmark::Counter(steps * static_cast<double>(n), benchmark::Counter::kIsRate);
  st.counters["bytes/particle"] = static_cast<double>(sim.memoryBytes()) / static_cast<double>(n);
}
BENCHMARK(BM_SeedFrame)->Arg(1000)->Arg(5000)->Arg(10000)->Arg(20000)->Arg(50000)->Arg(100000)->Arg(200000)
    ->Unit(benchmark::kMillisecond)->MinTime(1.0);

}  // namespace

BENCHMARK_MAIN();
