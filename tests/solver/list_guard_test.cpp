// The pair list's second validity test (solver/list_guard.h): whenever it keeps a list,
// every pair in reach at the new positions is listed (checked against all pairs), and
// it keeps lists that particles carried along together, which the displacement test
// alone would rebuild.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include <tbb/global_control.h>

#include "fluid/pair_forces.h"
#include "neighbors/cell_grid.h"
#include "solver/list_guard.h"
#include "solver/simulation.h"
#include "support/force_check.h"
#include "support/scenarios.h"

namespace softsub::solver {
namespace {

constexpr float kReach = 1.0f, kSkin = 0.1f;

forces::InteractionTable linearTable() {
  forces::InteractionTable t(1);
  t.set(0, 0, {forces::Linear{3, kReach, 0, 3}, 0, 0});
  return t;
}

// A list built on a cloud, its reference positions, and the guard holding it.
struct Built {
  ParticleStore store;
  neighbors::CellGrid grid;
  fluid::PairList list;
  std::vector<float> ref;  // x of every slot, then y, then z
  ListGuard guard;
  std::set<std::pair<std::uint32_t, std::uint32_t>> listed;

  Built(ParticleStore s, const forces::InteractionTable& table) : store(std::move(s)) {
    grid.rebuild(store, kReach + kSkin);
    list.build(grid, table, store, kSkin);
    const std::size_t n = store.size();
    ref.resize(3 * n);
    for (std::size_t i = 0; i < n; ++i) {
      ref[i] = store.px[i];
      ref[n + i] = store.py[i];
      ref[2 * n + i] = store.pz[i];
    }
    list.forEachPair([&](std::uint32_t i, std::uint32_t j) {
      listed.insert({std::min(i, j), std::max(i, j)});
    });
    guard.hold(kReach, kSkin);
  }
  // Moves every particle to f(reference position, slot).
  template <class F>
  void moveTo(F&& f) {
    const std::size_t n = store.size();
    for (std::size_t i = 0; i < n; ++i) {
      const std::array<float, 3> p = f(std::array<float, 3>{ref[i], ref[n + i], ref[2 * n + i]}, i);
      store.px[i] = p[0];
      store.py[i] = p[1];
      store.pz[i] = p[2];
    }
  }
  // Pairs now within reach that the list lacks.
  std::size_t missing() const {
    std::size_t count = 0;
    for (std::uint32_t i = 0; i < store.size(); ++i)
      for (std::uint32_t j = i + 1; j < store.size(); ++j) {
        const float dx = store.px[j] - store.px[i], dy = store.py[j] - store.py[i],
                    dz = store.pz[j] - store.pz[i];
        if (dx * dx + dy * dy + dz * dz < kReach * kReach && !listed.count({i, j})) ++count;
      }
    return count;
  }
};

// A liquid-like lump: a jittered lattice of spacing 0.55 (about 5 partners within reach).
ParticleStore lump(int side, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> jitter(-0.1f, 0.1f);
  ParticleStore s;
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j)
      for (int k = 0; k < side; ++k)
        s.add(0.55f * static_cast<float>(i) + jitter(rng), 0.55f * static_cast<float>(j) + jitter(rng),
              0.55f * static_cast<float>(k) + jitter(rng), 0, 0, 0, 0, 0);
  return s;
}

std::array<float, 3> turn(const std::array<float, 3>& p, const std::array<float, 3>& centre, float angle) {
  const float c = std::cos(angle), s = std::sin(angle);
  const float x = p[0] - centre[0], z = p[2] - centre[2];
  return {centre[0] + c * x - s * z, p[1], centre[2] + s * x + c * z};
}

TEST(ListGuard, KeepsAListTheWholeCloudWasCarriedAlongByManyCells) {
  Built b(lump(10, 1), linearTable());
  b.moveTo([](std::array<float, 3> p, std::size_t) {
    return std::array<float, 3>{p[0] + 7.3f, p[1] - 12.1f, p[2] + 3.7f};
  });
  EXPECT_TRUE(b.guard.proves(b.grid, b.store, b.ref.data()));
  EXPECT_GT(b.guard.blocks(), 1u);
  EXPECT_EQ(b.missing(), 0u);
}

TEST(ListGuard, KeepsAListThroughASlowTurnAndRefusesAFastOne) {
  Built b(lump(10, 2), linearTable());
  const std::array<float, 3> centre{2.5f, 2.5f, 2.5f};
  b.moveTo([&](std::array<float, 3> p, std::size_t) {
    p = turn(p, centre, 0.005f);
    return std::array<float, 3>{p[0], p[1] + 30.0f, p[2]};  // and falling far
  });
  EXPECT_TRUE(b.guard.proves(b.grid, b.store, b.ref.data()));
  EXPECT_EQ(b.missing(), 0u);
  // Turned by 0.3 rad, particles 2.5 apart have closed by 0.75: far beyond the skin.
  b.moveTo([&](std::array<float, 3> p, std::size_t) { return turn(p, centre, 0.3f); });
  EXPECT_FALSE(b.guard.proves(b.grid, b.store, b.ref.data()));
}

TEST(ListGuard, OneParticleMovedAgainstItsNeighboursByTheSkinMakesItStale) {
  Built b(lump(8, 3), linearTable());
  b.moveTo([](std::array<float, 3> p, std::size_t i) {
    if (i == 77) p[0] += 1.5f * kSkin;
    return std::array<float, 3>{p[0] + 4.0f, p[1], p[2]};
  });
  EXPECT_FALSE(b.guard.proves(b.grid, b.store, b.ref.data()));
  b.moveTo([](std::array<float, 3> p, std::size_t i) {
    if (i == 77) p[1] = NAN;
    return p;
  });
  EXPECT_FALSE(b.guard.proves(b.grid, b.store, b.ref.data()));
}

TEST(ListGuard, ANotFiniteDisplacementInABlockOfItsOwnMakesItStale) {
  // A particle alone in its block, far from the lump: NaN in x leaves that block's x
  // box empty (min and max skip NaN); it must still count as not finite.
  for (int axis = 0; axis < 3; ++axis) {
    ParticleStore s = lump(4, 11);
    s.add(30, 0, 0, 0, 0, 0, 0, 0);
    Built b(std::move(s), linearTable());
    std::size_t lone = 0;
    for (std::size_t i = 0; i < b.store.size(); ++i)
      if (b.store.px[i] == 30.0f) lone = i;
    b.moveTo([&](std::array<float, 3> p, std::size_t i) {
      if (i == lone) p[static_cast<std::size_t>(axis)] = NAN;
      return p;
    });
    EXPECT_FALSE(b.guard.proves(b.grid, b.store, b.ref.data())) << "axis " << axis;
    EXPECT_FALSE(b.guard.proves(b.grid, b.store, b.ref.data(), lone)) << "axis " << axis;
  }
}

TEST(ListGuard, TheRoundingOfLongDisplacementsIsCovered) {
  // Two particles 1.1000023 apart (not listed: reach 1 + skin 0.1), both carried about
  // 64 units past the origin, the second 0.1000025 further: now 0.99999976 apart, in
  // reach. x - ref rounds to 7.6e-6 there, so the computed closing is below the skin.
  ParticleStore s;
  s.add(60.5797462f, 0, 0, 0, 0, 0, 0, 0);
  s.add(61.6797485f, 0, 0, 0, 0, 0, 0, 0);
  Built b(std::move(s), linearTable());
  ASSERT_TRUE(b.listed.empty());
  b.moveTo([](std::array<float, 3> p, std::size_t) {
    p[0] = p[0] < 61.0f ? -3.36857057f : -2.3685708f;
    return p;
  });
  ASSERT_EQ(b.missing(), 1u);
  EXPECT_FALSE(b.guard.proves(b.grid, b.store, b.ref.data()));
}

TEST(ListGuard, WhereItLooksFirstAndHowManyThreadsRunItChangeNothing) {
  // The same answer for every hinted slot and on 1, 2 and 3 threads, over motions
  // that are kept and motions that are refused.
  int kept = 0, refused = 0;
  for (std::uint32_t trial = 0; trial < 12; ++trial) {
    Built b(lump(10, 50 + trial), linearTable());
    std::mt19937 rng(trial);
    std::uniform_real_distribution<float> u(-1, 1);
    const float jitter = 0.05f * kSkin * static_cast<float>(trial);
    b.moveTo([&](std::array<float, 3> p, std::size_t) {
      return std::array<float, 3>{p[0] + 5 + jitter * u(rng), p[1] - 3 + jitter * u(rng),
                                  p[2] + jitter * u(rng)};
    });
    const bool expected = b.guard.proves(b.grid, b.store, b.ref.data());
    expected ? ++kept : ++refused;
    for (int threads = 1; threads <= 3; ++threads) {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                static_cast<std::size_t>(threads));
      for (std::size_t hint = 0; hint < b.store.size(); hint += 37)
        ASSERT_EQ(b.guard.proves(b.grid, b.store, b.ref.data(), hint), expected)
            << "trial " << trial << " threads " << threads << " hint " << hint;
    }
  }
  EXPECT_GT(kept, 2);
  EXPECT_GT(refused, 2);
}

TEST(ListGuard, WheneverItKeepsAListNoPairInReachIsMissing) {
  // Random motions: a carry of up to 20 cells, a turn, a stretch, a jitter up to past
  // the skin and now and then one particle flung. Every trial whose list lacks a pair
  // must be refused; the trials include lists kept, lists refused, and lists that lack
  // pairs.
  int kept = 0, refused = 0, incomplete = 0;
  for (std::uint32_t trial = 0; trial < 80; ++trial) {
    // Every third trial a sparse cloud (wider blocks), the others a lump.
    Built b(trial % 3 == 2 ? scenarios::randomCloud(700, -40, 40, 0, 1, trial) : lump(9, trial),
            linearTable());
    std::mt19937 rng(1000 + trial);
    std::uniform_real_distribution<float> u(-1, 1), unit(0, 1);
    const std::array<float, 3> carry{20 * u(rng), 20 * u(rng), 20 * u(rng)};
    const float angle = 0.02f * unit(rng), stretch = 0.02f * u(rng),
                jitter = (trial % 2 == 0 ? 0.1f : 1.5f) * kSkin * unit(rng);
    const bool fling = trial % 5 == 0;
    b.moveTo([&](std::array<float, 3> p, std::size_t i) {
      p = turn(p, {2, 2, 2}, angle);
      for (int a = 0; a < 3; ++a) p[a] += carry[a] + stretch * p[a] + jitter * u(rng);
      if (fling && i == 100) p[1] += 3.0f;
      return p;
    });
    const bool keeps = b.guard.proves(b.grid, b.store, b.ref.data());
    const std::size_t missing = b.missing();
    keeps ? ++kept : ++refused;
    if (missing > 0) ++incomplete;
    ASSERT_FALSE(keeps && missing > 0)
        << "trial " << trial << ": kept a list that lacks " << missing << " pairs";
  }
  EXPECT_GT(kept, 10);
  EXPECT_GT(refused, 10);
  EXPECT_GT(incomplete, 5);
}

TEST(ListGuard, BlocksEachMovedAsOneButAgainstTheirNeighboursAreRefused) {
  // Each block of 2 x 2 x 2 grid cells carried along by its own random step (up to
  // 0.3 a coordinate): no block moved within itself and the whole spread is below the
  // reach, so only the comparison of touching blocks sees that pairs across their
  // faces closed by more than the skin.
  Built b(lump(12, 9), linearTable());
  std::vector<std::array<float, 3>> step(b.store.size());
  for (std::size_t c = 0; c < b.grid.cellCount(); ++c) {
    const std::array<std::uint32_t, 3> k = b.grid.cellFields(c);
    std::mt19937 rng(((k[2] / 2) * 1000 + k[1] / 2) * 1000 + k[0] / 2);
    std::uniform_real_distribution<float> u(-0.3f, 0.3f);
    const std::array<float, 3> d{u(rng), u(rng), u(rng)};
    for (std::uint32_t i = b.grid.cell(c).begin; i < b.grid.cell(c).end; ++i) step[i] = d;
  }
  b.moveTo([&](std::array<float, 3> p, std::size_t i) {
    return std::array<float, 3>{p[0] + step[i][0], p[1] + step[i][1], p[2] + step[i][2]};
  });
  EXPECT_GT(b.missing(), 0u);
  EXPECT_FALSE(b.guard.proves(b.grid, b.store, b.ref.data()));
  // The same steps a hundredth as long: every pair closed by less than the skin.
  b.moveTo([&](std::array<float, 3> p, std::size_t i) {
    return std::array<float, 3>{p[0] + 0.01f * step[i][0], p[1] + 0.01f * step[i][1],
                                p[2] + 0.01f * step[i][2]};
  });
  EXPECT_TRUE(b.guard.proves(b.grid, b.store, b.ref.data()));
}

TEST(ListGuard, TwoLumpsClosingOnEachOtherAreRefusedThoughEachMovedAsOne) {
  // Two lumps five block widths apart, each carried along as one: every block agrees
  // with its neighbours, only the whole spread tells that the lumps met.
  ParticleStore s = lump(6, 7);
  const std::size_t half = s.size();
  const float gap = 5 * 2 * (kReach + kSkin) + 0.55f * 5;
  for (std::size_t i = 0; i < half; ++i) s.add(s.px[i] + gap, s.py[i], s.pz[i], 0, 0, 0, 0, 0);
  Built b(std::move(s), linearTable());
  const auto closeBy = [&](float d) {
    b.moveTo([&](std::array<float, 3> p, std::size_t) {
      p[0] += p[0] < 0.5f * gap ? d : -d;
      return p;
    });
  };
  closeBy(0.2f * kReach);  // still far apart
  EXPECT_TRUE(b.guard.proves(b.grid, b.store, b.ref.data()));
  EXPECT_EQ(b.missing(), 0u);
  closeBy(0.5f * (gap - 0.55f * 5));  // now touching
  EXPECT_GT(b.missing(), 0u);
  EXPECT_FALSE(b.guard.proves(b.grid, b.store, b.ref.data()));
}

TEST(ListGuard, AFallingTurningLumpKeepsItsListAndItsForcesExact) {
  // Position-only forces and velocity Verlet: after each step the store holds the
  // forces of the current positions. A lump falls fast and turns slowly: the
  // displacements call the list stale every few substeps, the guard keeps it, and the
  // forces still equal a brute-force sum over all pairs.
  Model m = scenarios::ljModel(2.5);
  m.integrator = Integrator::VelocityVerlet;
  m.table = linearTable();
  m.gravity = Vec3(0, -9.8, 0);
  m.substeps = 8;
  State s;
  s.particles = lump(9, 5);
  m.fluids[0].count = static_cast<std::uint32_t>(s.particles.size());
  for (std::size_t i = 0; i < s.particles.size(); ++i) {
    s.particles.vy[i] = -40.0f;
    s.particles.vx[i] = 0.3f * (s.particles.pz[i] - 2.2f);  // a slow turn about y
    s.particles.vz[i] = -0.3f * (s.particles.px[i] - 2.2f);
  }
  std::int64_t builds[2] = {0, 0};
  for (int guard = 0; guard < 2; ++guard) {
    m.listGuard = guard == 1;
    Simulation sim(m, s);
    for (int k = 0; k < 60; ++k) {
      sim.step();
      ASSERT_LT(testing::relativeForceError(m.table, sim.state().particles), 1e-3)
          << "guard " << guard << " step " << k;
    }
    builds[guard] = sim.listBuilds();
  }
  EXPECT_GT(builds[0], 20) << "the displacement test alone rebuilds often";
  EXPECT_LT(3 * builds[1], builds[0]) << "the guard keeps most of those lists";
}

}  // namespace
}  // namespace softsub::solver
