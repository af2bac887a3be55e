// Sampled tables: error bounded by linear-interpolation theory and tested; the
// table's entries are what the pair kernel reads.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "forces/interaction_table.h"

namespace softsub::forces {
namespace {

// A priori bound of linear interpolation with pieces of width h: h^2/8 max|F''| on
// smooth pieces; a piece with a clamp corner inside errs at most h/2 * max|F'| there.
// Derivatives estimated from the formula on a fine grid; plus float rounding.
double errorBound(const PairFunction& f, int intervals, double from) {
  const double rc = cutoff(f), h = rc / intervals;
  double bound = 0;
  for (int k = 0; k < intervals; ++k) {
    const double a = k * h;
    if (a + h < from) continue;
    double m1 = 0, m2 = 0, vmax = 0;
    for (int s = 0; s <= 8; ++s) {
      const double r = std::min(a + s * h / 8, rc * (1 - 1e-9));
      const double e = h / 64;
      const double fm = evaluate(f, std::max(r - e, 0.0)), f0 = evaluate(f, r), fp = evaluate(f, r + e);
      m1 = std::max(m1, std::abs(fp - fm) / (2 * e));
      m2 = std::max(m2, std::abs(fp - 2 * f0 + fm) / (e * e));
      vmax = std::max(vmax, std::abs(f0));
    }
    bound = std::max(bound, std::min(h * h / 8 * m2, h / 2 * m1) + 4e-7 * vmax + 1e-12);
  }
  return bound;
}

// Largest |table - formula| over [from, cutoff).
double maxError(const PairFunction& f, const SampledFunction& s, double from) {
  double err = 0;
  const double rc = cutoff(f);
  for (int k = 0; k < 200000; ++k) {
    const double r = from + (rc - from) * k / 200000.0;
    err = std::max(err, std::abs(s.at(r) - evaluate(f, r)));
  }
  return err;
}

TEST(SampledFunction, ErrorWithinInterpolationBoundForEveryKind) {
  const PairFunction fns[] = {
      Linear{5, 1, 0, 5}, Linear{5, 1.5, 0, 5}, LennardJones{30, 1, -20, 400, 1.5},
      LennardJones{2, 0.5, -1, 40, 1.2}, LennardJonesForce{1, 1, 2.5}, Curve{{0.1, 3, 0.6, -1, 1.1, 0.5}}};
  for (const PairFunction& f : fns) {
    // The true LJ force is unbounded at r -> 0; it is checked where particles can be.
    const double from = std::holds_alternative<LennardJonesForce>(f) ? 0.8 : 0.0;
    const SampledFunction s = sample(f, kDefaultIntervals);
    const double bound = errorBound(f, kDefaultIntervals, from);
    const double err = maxError(f, s, from);
    EXPECT_LE(err, bound) << kindName(f);
  }
}

TEST(SampledFunction, ErrorConvergesQuadraticallyOnSmoothFunctions) {
  // Doubling the samples divides the error of a smooth function by ~4.
  const PairFunction f = LennardJonesForce{1, 1, 2.5};
  const double coarse = maxError(f, sample(f, 512), 0.85);
  const double fine = maxError(f, sample(f, 1024), 0.85);
  EXPECT_GT(coarse / fine, 3.5);
  EXPECT_LT(coarse / fine, 4.5);
}

TEST(SampledFunction, RelativeErrorOfTheDefaultTablesIsSmall) {
  // Over the range particles actually sit (r >= 0.85 sigma), the true LJ force table
  // is within 1e-3 of the largest force there.
  const PairFunction f = LennardJonesForce{1, 1, 2.5};
  const SampledFunction s = sample(f);
  double err = 0, fmax = 0;
  for (double r = 0.85; r < 2.5; r += 1e-5) {
    err = std::max(err, std::abs(s.at(r) - evaluate(f, r)));
    fmax = std::max(fmax, std::abs(evaluate(f, r)));
  }
  EXPECT_LT(err / fmax, 1e-3);
}

TEST(SampledFunction, KeepsValueUpToAJumpAtTheCutoff) {
  const LennardJones f{10, 1, -100, 100, 1.3};  // F(1.3-) is about -7.5: a jump to 0
  const SampledFunction s = sample(f);
  EXPECT_NEAR(s.at(1.3 - 1e-6), evaluate(f, 1.3 - 1e-6), 1e-3);
  EXPECT_EQ(s.at(1.3), 0.0);
  EXPECT_EQ(s.at(5.0), 0.0);
}

TEST(InteractionTable, SymmetricEntriesSharedSamplesAndMaxCutoff) {
  InteractionTable t(3);
  const Interaction global{Linear{5, 1, 0, 5}, 0, 0};
  t.set(0, 1, global);
  t.set(0, 2, global);
  t.set(1, 2, {Linear{8, 1.5, 0, 8}, 0.5, 2});
  t.set(0, 0, {LennardJones{30, 1, -20, 400, 1.5}, 1, 0});
  EXPECT_EQ(t.entry(0, 1).offset, t.entry(1, 0).offset);
  EXPECT_EQ(t.entry(0, 1).offset, t.entry(0, 2).offset) << "identical functions share samples";
  // Three distinct functions, after the zero piece every table starts with.
  EXPECT_EQ(t.samples().size(), 2u + 3u * 2 * kDefaultIntervals);
  EXPECT_FLOAT_EQ(t.entry(2, 1).damping, 0.5f);
  EXPECT_FLOAT_EQ(t.entry(2, 1).relativeVelocity, 2.0f);
  EXPECT_FLOAT_EQ(t.entry(1, 2).cutoff2, 2.25f);
  EXPECT_EQ(t.entry(1, 1).cutoff2, 0.0f) << "unset pairs do nothing";
  EXPECT_DOUBLE_EQ(t.maxCutoff(), 1.5);
  for (double r = 0; r < 1.6; r += 0.01) {
    EXPECT_NEAR(t.sampledAt(0, 0, r), sample(t.interaction(0, 0).function).at(r),
                1e-4 * (1 + std::abs(sample(t.interaction(0, 0).function).at(r))));
    EXPECT_NEAR(t.sampledAt(1, 2, r), evaluate(Linear{8, 1.5, 0, 8}, r), 1e-4);
  }
}

// rowCutoff2 (the kernel's pre-filter) is the largest cutoff of each row however the
// pairs were set: grown (kept in O(1)), shrunk, replaced by nothing, set again; and a
// function found again (the last one or an older one) shares its samples.
TEST(InteractionTable, RowCutoffsFollowEverySet) {
  InteractionTable t(5);
  auto check = [&](const char* when) {
    for (std::size_t a = 0; a < t.materials(); ++a) {
      float expected = 0;
      for (std::size_t b = 0; b < t.materials(); ++b) expected = std::max(expected, t.entry(a, b).cutoff2);
      EXPECT_EQ(t.rowCutoff2(a), expected) << when << ", row " << a;
    }
  };
  const Interaction short1{Linear{5, 1, 0, 5}, 0, 0}, long2{Linear{5, 2, 0, 5}, 0, 0},
      none{Linear{0, 0, 0, 0}, 0, 0};
  for (std::size_t a = 0; a < 5; ++a)
    for (std::size_t b = a; b < 5; ++b) t.set(a, b, short1);
  check("all short");
  t.set(1, 3, long2);
  check("one long");
  EXPECT_EQ(t.rowCutoff2(1), 4.0f);
  const std::uint32_t longOffset = t.entry(1, 3).offset;
  t.set(1, 3, short1);  // shrinks: rows 1 and 3 back to 1
  check("long one shortened");
  EXPECT_EQ(t.rowCutoff2(3), 1.0f);
  t.set(2, 2, long2);
  t.set(2, 2, none);
  check("one cleared");
  for (std::size_t b = 0; b < 5; ++b) t.set(4, b, none);
  check("a row cleared");
  EXPECT_EQ(t.rowCutoff2(4), 0.0f);
  t.set(0, 4, long2);
  check("set again");
  EXPECT_EQ(t.entry(0, 4).offset, longOffset) << "found again, not sampled again";
  EXPECT_EQ(t.entry(1, 3).offset, t.entry(0, 1).offset);
  EXPECT_EQ(t.samples().size(), 2u + 3u * 2 * kDefaultIntervals) << "three distinct functions";
}

TEST(InteractionTable, PairsThatDoNothingPointAtAZeroPiece) {
  // The pair kernel reads every listed pair's table whatever the distance (branch-free):
  // an entry never set must point at readable zeros, even in a table with no function.
  const InteractionTable t(3);
  ASSERT_GE(t.samples().size(), 2u);
  for (std::size_t a = 0; a < 3; ++a)
    for (std::size_t b = 0; b < 3; ++b) {
      const PairEntry& e = t.entry(a, b);
      EXPECT_EQ(e.cutoff2, 0.0f);
      ASSERT_LT(e.offset + 2 * std::size_t{e.lastPiece} + 1, t.samples().size());
      EXPECT_EQ(t.samples()[e.offset], 0.0f);
      EXPECT_EQ(t.samples()[e.offset + 1], 0.0f);
    }
}

}  // namespace
// A cutoff far beyond the function's own length scale: the 12-6 core used to fall in a
// few of the 2048 pieces (a force of 11 at r = FiniteDistance, where the formula gives
// 0). Now each length scale gets at least half the default's pieces; cutoffs up to twice
// the length scale (every example) keep exactly the default table.
TEST(InteractionTable, LongCutoffsGetPiecesEnoughForTheirLengthScale) {
  EXPECT_EQ(intervalsFor(LennardJones{20, 1, -20, 400, 1.5}), kDefaultIntervals);
  EXPECT_EQ(intervalsFor(LennardJones{20, 1, -20, 400, 2}), kDefaultIntervals);
  EXPECT_EQ(intervalsFor(LennardJonesForce{1, 1, 2.5}), 2560);
  EXPECT_EQ(intervalsFor(LennardJones{20, 1, -20, 400, 200}), 1024 * 200);
  EXPECT_EQ(intervalsFor(LennardJones{20, 1, -20, 400, 1000}), kMaxIntervals);
  EXPECT_EQ(intervalsFor(Linear{5, 100, 0, 5}), kDefaultIntervals) << "a line is sampled exactly";
  EXPECT_EQ(intervalsFor(Curve{{0, 5, 0.1, 1, 10, 0}}), 1024 * 100) << "its closest points set its scale";
  EXPECT_EQ(intervalsFor(LennardJones{20, 1, -20, 400, 200}, 64), 32 * 200) << "scales with the base count";

  for (const double rc : {50.0, 200.0}) {
    const LennardJones f{20, 1, -20, 400, rc};
    InteractionTable t(1);
    t.set(0, 0, {f, 0, 0});
    EXPECT_EQ(std::size_t{t.entry(0, 0).lastPiece} + 1, static_cast<std::size_t>(intervalsFor(f)));
    double err = 0;
    for (double r = 0.9; r < 3; r += 1e-4)
      err = std::max(err, std::abs(t.sampledAt(0, 0, r) - evaluate(f, r)));
    EXPECT_LT(err, 1e-3 * 20) << "cutoff " << rc << ": within 1e-3 of the clamp";
  }
}

// samplingError against a brute-force check: the largest |sampled - exact| over
// [0.9, 4] length scales (a finer grid than the function's own), over the largest |exact|
// there. Small within the table's cap, growing once the cap makes each piece longer
// than the length scale allows; 0 for a straight line (no length scale).
TEST(InteractionTable, SamplingErrorGrowsOnceTheCapIsReached) {
  double last = 0;
  for (const double rc : {2.5, 100.0, 1e3, 1e4, 1e6}) {
    const LennardJones f{30, 1, -20, 400, rc};
    const int n = intervalsFor(f);
    const double error = samplingError(f, n);
    const SampledFunction s = sample(f, n);
    double worst = 0, largest = 0;
    for (int k = 0; k < 20000; ++k) {
      const double r = 0.9 + 3.1 * (k + 0.25) / 20000;
      worst = std::max(worst, std::abs(s.at(r) - evaluate(f, r)));
      largest = std::max(largest, std::abs(evaluate(f, r)));
    }
    EXPECT_NEAR(error, worst / largest, 0.2 * worst / largest + 1e-4) << rc;
    if (rc <= 100) {
      EXPECT_LT(error, 0.005) << rc;
    }
    if (rc >= 1e6) {
      EXPECT_GT(error, 0.5) << rc;
    }
    EXPECT_GE(error, 0.9 * last) << rc;
    last = error;
  }
  EXPECT_EQ(samplingError(Linear{5, 1e6, 0, 5}, kMaxIntervals), 0.0);
}

// Distinct functions each take their own samples; past kMaxTableFloats the table
// refuses (the scene compiler names the scene's line) instead of exhausting memory.
TEST(InteractionTable, AFunctionPastTheTablesSizeCapIsRefused) {
  const std::size_t each = 2 * static_cast<std::size_t>(kMaxIntervals);
  const std::size_t fit = (kMaxTableFloats - 2) / each;
  InteractionTable t(fit + 1);
  for (std::size_t a = 0; a < fit; ++a)
    t.set(a, a, {LennardJones{1.0 + static_cast<double>(a), 1, -20, 400, 600}, 0, 0});
  EXPECT_EQ(t.samples().size(), 2 + fit * each);
  t.set(fit, fit, {LennardJones{1, 1, -20, 400, 600}, 0, 0});  // shares the first's samples
  EXPECT_THROW(t.set(fit, fit, {LennardJones{0.5, 1, -20, 400, 600}, 0, 0}), std::length_error);
}

}  // namespace softsub::forces
