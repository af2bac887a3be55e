// Every function kind against its formula, written out independently here.
#include <gtest/gtest.h>

#include <cmath>

#include "forces/function.h"

namespace softsub::forces {
namespace {

double seedLj(double a, double s, double lo, double hi, double rc, double r) {
  if (r >= rc) return 0;
  const double q = s / r;
  const double v = 4 * a * (std::pow(q, 12) - std::pow(q, 6));
  return std::min(hi, std::max(lo, v));
}

TEST(Function, LinearIsTheSeedLine) {
  const Linear l{5, 1, 0, 5};  // the seed's fluid/fluid default
  EXPECT_DOUBLE_EQ(evaluate(l, 0.0), 5.0);
  EXPECT_DOUBLE_EQ(evaluate(l, 0.5), 2.5);
  EXPECT_DOUBLE_EQ(evaluate(l, 0.9), 5.0 * 0.1);
  EXPECT_EQ(evaluate(l, 1.0), 0.0);
  EXPECT_EQ(evaluate(l, 3.0), 0.0);
  const Linear clamped{10, 2, -1, 4};
  EXPECT_DOUBLE_EQ(evaluate(clamped, 0.2), 4.0);   // 9 clamped to Max
  EXPECT_DOUBLE_EQ(evaluate(clamped, 1.5), 2.5);
  EXPECT_DOUBLE_EQ(cutoff(clamped), 2.0);
}

TEST(Function, SeedLennardJonesMatchesFormulaAndClamps) {
  const LennardJones f{3, 1.2, -2, 50, 2.0};
  for (double r = 0.05; r < 2.5; r += 0.0137)
    EXPECT_NEAR(evaluate(f, r), seedLj(3, 1.2, -2, 50, 2.0, r), 1e-12 * (1 + std::abs(seedLj(3, 1.2, -2, 50, 2.0, r))))
        << "r=" << r;
  EXPECT_DOUBLE_EQ(evaluate(f, 1.2), 0.0);  // zero at the finite distance
  EXPECT_DOUBLE_EQ(evaluate(f, 0.0), 50.0); // limit at r = 0 is the clamp, never NaN
  EXPECT_DOUBLE_EQ(evaluate(f, 0.3), 50.0);
  EXPECT_EQ(evaluate(f, 2.0), 0.0);
  // Unclamped minimum of 4A(q^12 - q^6) is -A at r = 2^(1/6) s.
  const LennardJones wide{3, 1.2, -1e9, 1e9, 5};
  EXPECT_NEAR(evaluate(wide, std::pow(2.0, 1.0 / 6.0) * 1.2), -3.0 * 4 * 0.25, 1e-12);
}

TEST(Function, TrueLennardJonesForceIsMinusDerivativeOfPotential) {
  const LennardJonesForce f{1.5, 0.9, 2.5 * 0.9};
  for (double r = 0.8; r < 2.2; r += 0.01) {
    const double h = 1e-6;
    const double dudr = (potential(f, r + h) - potential(f, r - h)) / (2 * h);
    EXPECT_NEAR(evaluate(f, r), -dudr, 1e-5 * (1 + std::abs(dudr))) << "r=" << r;
    const double q6 = std::pow(0.9 / r, 6);
    EXPECT_NEAR(potential(f, r), 4 * 1.5 * (q6 * q6 - q6), 1e-12);
  }
  EXPECT_NEAR(evaluate(f, 0.9 * std::pow(2.0, 1.0 / 6.0)), 0.0, 1e-12);  // potential minimum
  EXPECT_EQ(evaluate(f, 2.25), 0.0);
  EXPECT_TRUE(std::isfinite(evaluate(f, 0.0)));
  EXPECT_TRUE(std::isfinite(evaluate(f, 1e-30)));
}

TEST(Function, CurveIsPiecewiseLinear) {
  const Curve c{{0.2, 8, 0.5, 2, 1.0, -1, 1.4, 0}};
  EXPECT_DOUBLE_EQ(evaluate(c, 0.0), 8.0);  // f0 below r0
  EXPECT_DOUBLE_EQ(evaluate(c, 0.2), 8.0);
  EXPECT_DOUBLE_EQ(evaluate(c, 0.35), 5.0);
  EXPECT_DOUBLE_EQ(evaluate(c, 0.75), 0.5);
  EXPECT_DOUBLE_EQ(evaluate(c, 1.2), -0.5);
  EXPECT_EQ(evaluate(c, 1.4), 0.0);  // zero past the last point
  EXPECT_DOUBLE_EQ(cutoff(c), 1.4);
}

TEST(Function, PotentialIntegratesTheForce) {
  // For a linear function the potential is a quadratic: U(r) = integral_r^rc F.
  const Linear l{4, 2, 0, 4};  // F = 4 (1 - r/2)
  for (double r = 0; r < 2; r += 0.25) {
    const double exact = 4 * ((2 - r) - (4 - r * r) / 4);
    EXPECT_NEAR(potential(l, r), exact, 1e-6);
  }
  EXPECT_EQ(kindName(l), "Linear");
  EXPECT_EQ(kindName(PairFunction{Curve{}}), "Curve");
}

}  // namespace
}  // namespace softsub::forces
