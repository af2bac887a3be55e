#pragma once
/// The closed set of pair-force functions F(r) (positive = repulsion), as described
/// by a scene. Evaluated exactly here; the solver only ever uses their sampled tables.
#include <string_view>
#include <variant>
#include <vector>

namespace softsub::forces {

/// Straight line from AtZero at r = 0 to 0 at Cutoff, clamped to [Min, Max]; zero
/// from Cutoff on. The seed's global fluid/fluid default.
struct Linear {
  double atZero = 5;  ///< force at r = 0
  double cutoff = 1;  ///< distance where the line reaches 0 and the force ends
  double min = 0;     ///< lower clamp
  double max = 5;     ///< upper clamp
  bool operator==(const Linear&) const = default;
};

/// The seed's Lennard-Jones-shaped function
/// F(r) = 4 A ((s/r)^12 - (s/r)^6), clamped to [Min, Max], zero from Cutoff on.
struct LennardJones {
  double amplitude = 1;       ///< A, force units
  double finiteDistance = 1;  ///< s, where F = 0
  double min = -1;            ///< lower clamp (strongest attraction)
  double max = 10;            ///< upper clamp (strongest repulsion)
  double cutoff = 1.5;        ///< interaction distance
  bool operator==(const LennardJones&) const = default;
};

/// The true 12-6 force -dU/dr, U = 4 eps ((sigma/r)^12 - (sigma/r)^6), zero from Cutoff
/// on (unshifted, as LAMMPS's lj/cut).
struct LennardJonesForce {
  double epsilon = 1;  ///< well depth, energy units
  double sigma = 1;    ///< distance where U = 0
  double cutoff = 2.5; ///< interaction distance
  bool operator==(const LennardJonesForce&) const = default;
};

/// Piecewise linear through (r0, f0), (r1, f1), ...; f0 below r0; zero past the last r.
struct Curve {
  std::vector<double> points;  ///< r0 f0 r1 f1 ... with r strictly increasing, r0 >= 0
  bool operator==(const Curve&) const = default;
};

/// One pair function of any kind.
using PairFunction = std::variant<Linear, LennardJones, LennardJonesForce, Curve>;

/// The scene-file element name of a function's kind ("Linear", "LennardJones", ...).
std::string_view kindName(const PairFunction& f);

/// F(r) from the formula, r >= 0. Never NaN: at r = 0 the limit (clamped or huge).
double evaluate(const PairFunction& f, double r);

/// Distance from which F is zero.
double cutoff(const PairFunction& f);

/// The potential energy U(r) with F = -dU/dr and U(cutoff) = 0 (only for true
/// Lennard-Jones force this is the physical potential; for other kinds it is the
/// integral of F, used for energy reports). Computed numerically for sampled kinds.
double potential(const PairFunction& f, double r);

}  // namespace softsub::forces
