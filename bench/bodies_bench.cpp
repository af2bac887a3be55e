// Rigid bodies in a fluid (issue #3): 50 bodies falling into a pool of 50,000 goo
// particles (BM_BodiesInPool), against the same pool with as many more fluid particles
// as the bodies have (BM_BodiesAsFluid): bodies must not cost more than their particle
// count would as fluid. Time column: ms per frame of 8 substeps. See docs/benchmarks.md.
#include <benchmark/benchmark.h>

#include <algorithm>

#include "solver/simulation.h"
#include "support/bodies.h"

namespace {

using namespace softsub;

void BM_BodiesInPool(benchmark::State& st) {
  const auto fluid = static_cast<std::size_t>(st.range(0));
  const auto bodies = static_cast<std::size_t>(st.range(1));
  scenarios::BodyRun run(scenarios::bodiesInPool(fluid, bodies));
  for (int f = 0; f < 12; ++f) run.sim->advanceFrame();  // the bodies reach the fluid
  const std::int64_t builds = run.sim->listBuilds();
  for (auto _ : st) run.sim->advanceFrame();
  st.counters["substeps/list"] = static_cast<double>(st.iterations()) * run.compiled.model.substeps /
                                 static_cast<double>(std::max<std::int64_t>(1, run.sim->listBuilds() - builds));
  st.counters["particles"] = static_cast<double>(run.compiled.model.particleCount());
  st.counters["body particles"] = static_cast<double>(run.compiled.model.bodies.particleCount());
  st.counters["contacts"] = static_cast<double>(run.sim->rigidSolver().contacts().size());
}
BENCHMARK(BM_BodiesInPool)->Args({50000, 50})->Args({50000, 0})->Unit(benchmark::kMillisecond)->MinTime(2.0);

void BM_BodiesAsFluid(benchmark::State& st) {
  const auto fluid = static_cast<std::size_t>(st.range(0));
  const auto bodies = static_cast<std::size_t>(st.range(1));
  const scene::Compiled probe = scene::compile(scenarios::bodiesInPool(fluid, bodies));
  // The same scene without bodies, its pool widened to as many particles as both had.
  scenarios::BodyRun run(scenarios::bodiesInPool(probe.model.particleCount(), 0));
  for (int f = 0; f < 12; ++f) run.sim->advanceFrame();
  const std::int64_t builds = run.sim->listBuilds();
  for (auto _ : st) run.sim->advanceFrame();
  st.counters["particles"] = static_cast<double>(run.compiled.model.particleCount());
  st.counters["substeps/list"] = static_cast<double>(st.iterations()) * run.compiled.model.substeps /
                                 static_cast<double>(std::max<std::int64_t>(1, run.sim->listBuilds() - builds));
}
BENCHMARK(BM_BodiesAsFluid)->Args({50000, 50})->Unit(benchmark::kMillisecond)->MinTime(2.0);

}  // namespace
