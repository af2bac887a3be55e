// The solver's two hot stages on their own, with no integration around them, so that a
// change to either can be measured in isolation (docs/benchmarks.md, issue #6):
// - BM_PairKernel: one evaluation of the pair forces from a built list
//   (fluid::setPairForces, as the solver evaluates between list rebuilds);
// - BM_ListBuild: re-sorting an already sorted store into the grid and building the pair
//   list (what every list rebuild costs when the order did not change);
// - BM_GridResort: the grid rebuild alone on a store whose particles moved since it was
//   sorted (each by its velocity times `substeps` substeps of 1/192 s, the seed's step):
//   the sort and the permutation a rebuild during motion pays. The store is copied back
//   before each rebuild (the copy is part of the time, the same for every version).
// Cases: 0 = the seed pool of 200,000 particles after one simulated second (viscous goo,
// velocity terms), 1 = the Lennard-Jones liquid of `softsub bench lammps` (32,000 atoms,
// fcc at density 0.8442, cutoff 2.5, no velocity terms), 2 = the same liquid with cutoff 2.0
// (the bench's other cutoff: fewer partners a window, so the per-window and per-slot costs
// weigh more).
// Second argument of BM_PairKernel and BM_ListBuild: 0 = the copy the CPU selects
// (fluid::simdInUse, AVX2 where there is one), 1 = the baseline copy (SSE2).
// Third argument of BM_PairKernel: 0 = the closed-form kernel on a grouped list where
// the table has one (the LJ liquid: InteractionTable::closedFormLj), 1 = the table
// kernel whatever the table (ListOptions::closedForm off).
// Counters: pairs/s is listed pairs processed per second.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>

#include "fluid/pair_forces.h"
#include "neighbors/cell_grid.h"
#include "solver/simulation.h"
#include "support/scenarios.h"

namespace {

using namespace softsub;

struct Case {
  forces::InteractionTable table;
  ParticleStore store;
  float cell = 0, skin = 0;
};

// An fcc lattice of 4 cells^3 atoms at reduced density 0.8442 (LAMMPS's bench/in.lj),
// each moved by a fixed-seed jitter of up to +-0.02, with the true LJ force cut at `cutoff`.
Case ljLiquid(int cells, double cutoff) {
  Case c;
  c.table = forces::InteractionTable(1);
  c.table.set(0, 0, {forces::LennardJonesForce{1, 1, cutoff}, 0, 0});
  const double a = std::cbrt(4.0 / 0.8442);
  const double basis[4][3] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
  std::uint64_t seed = 12345;
  const auto jitter = [&seed] {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<float>((static_cast<double>(seed >> 11) / 9007199254740992.0 - 0.5) * 0.04);
  };
  for (int i = 0; i < cells; ++i)
    for (int j = 0; j < cells; ++j)
      for (int k = 0; k < cells; ++k)
        for (const auto& b : basis)
          c.store.add(static_cast<float>((i + b[0]) * a) + jitter(), static_cast<float>((j + b[1]) * a) + jitter(),
                      static_cast<float>((k + b[2]) * a) + jitter(), 0, 0, 0, 0, 0);
  c.cell = static_cast<float>(cutoff);
  c.skin = 0.1f * c.cell;  // the solver's default: a tenth of the cutoff
  return c;
}

// The seed pool after one simulated second (fluid in motion, viscous).
Case seedPool(std::size_t n) {
  solver::Model model;
  solver::State state;
  scenarios::fluidPool(n, 1.0, 10, model, state);
  solver::Simulation sim(model, std::move(state));
  for (int f = 0; f < 24; ++f) sim.advanceFrame();
  Case c;
  c.table = model.table;
  c.store = sim.state().particles;
  c.cell = static_cast<float>(model.table.maxCutoff());
  c.skin = static_cast<float>(model.pairListSkin) * c.cell;
  return c;
}

// Selects the copy of the hot loops for one benchmark (see the header comment), and
// restores the default after it.
struct SimdFor {
  fluid::Simd was = fluid::simdInUse();
  explicit SimdFor(std::int64_t arg) {
    if (arg == 1) fluid::useSimd(fluid::Simd::Baseline);
  }
  ~SimdFor() { fluid::useSimd(was); }
  SimdFor(const SimdFor&) = delete;
  SimdFor& operator=(const SimdFor&) = delete;
};

Case& caseOf(std::int64_t which) {
  if (which == 0) {
    static Case pool = seedPool(200000);
    return pool;
  }
  if (which == 1) {
    static Case lj = ljLiquid(20, 2.5);  // made only when asked for: the pool takes a while
    return lj;
  }
  static Case lj2 = ljLiquid(20, 2.0);
  return lj2;
}

void BM_PairKernel(benchmark::State& st) {
  Case& c = caseOf(st.range(0));
  const SimdFor simd(st.range(1));
  neighbors::CellGrid grid;
  grid.rebuild(c.store, c.cell + c.skin);
  fluid::PairList list;
  fluid::ListOptions options;
  options.closedForm = st.range(2) == 0;
  list.build(grid, c.table, c.store, c.skin, options);
  ParticleStore& s = c.store;
  for (auto _ : st) {
    fluid::setPairForces(list, c.table, s);
    benchmark::DoNotOptimize(s.f.data());
  }
  st.counters["pairs/s"] = benchmark::Counter(static_cast<double>(list.pairCount()) * static_cast<double>(st.iterations()),
                                              benchmark::Counter::kIsRate);
  st.counters["pairs/particle"] = static_cast<double>(list.pairCount()) / static_cast<double>(s.size());
  std::size_t entries = 0;  // pairs; groups of 8 slots in a wide grouped layer; codes in a packed one
  std::size_t wide = 0;  // layers with 32-bit entries, or whose sums go straight to the store
  for (const fluid::PairList::Layer& l : list.layers()) {
    entries += l.size();
    wide += l.narrow ? 0 : 1;
  }
  st.counters["entries/particle"] = static_cast<double>(entries) / static_cast<double>(s.size());
  st.counters["wide layers"] = static_cast<double>(wide);
  st.counters["layers"] = static_cast<double>(list.layers().size());
  st.counters["list bytes/particle"] = static_cast<double>(list.memoryBytes()) / static_cast<double>(s.size());
}
BENCHMARK(BM_PairKernel)
    ->ArgsProduct({{0, 1, 2}, {0, 1}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);

void BM_ListBuild(benchmark::State& st) {
  Case& c = caseOf(st.range(0));
  const SimdFor simd(st.range(1));
  neighbors::CellGrid grid;
  grid.rebuild(c.store, c.cell + c.skin);  // sorted once: the timed rebuilds find it sorted
  fluid::PairList list;
  for (auto _ : st) {
    grid.rebuild(c.store, c.cell + c.skin);
    list.build(grid, c.table, c.store, c.skin);
    benchmark::DoNotOptimize(list.layers().data());
    benchmark::ClobberMemory();
  }
  st.counters["pairs/s"] = benchmark::Counter(static_cast<double>(list.pairCount()) * static_cast<double>(st.iterations()),
                                              benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ListBuild)->ArgsProduct({{0, 1, 2}, {0, 1}})->Unit(benchmark::kMillisecond)->MinTime(1.0);

void BM_GridResort(benchmark::State& st) {
  Case& c = caseOf(0);
  ParticleStore moved = c.store;
  neighbors::CellGrid grid;
  grid.rebuild(moved, c.cell + c.skin);
  const float dt = static_cast<float>(st.range(0)) / 192.0f;
  for (std::size_t i = 0; i < moved.size(); ++i) {
    moved.px[i] += moved.vx[i] * dt;
    moved.py[i] += moved.vy[i] * dt;
    moved.pz[i] += moved.vz[i] * dt;
  }
  ParticleStore s = moved;
  for (auto _ : st) {
    s = moved;
    grid.rebuild(s, c.cell + c.skin);
    benchmark::DoNotOptimize(s.px.data());
  }
}
BENCHMARK(BM_GridResort)->Arg(2)->Arg(8)->Unit(benchmark::kMillisecond)->MinTime(1.0);

}  // namespace
