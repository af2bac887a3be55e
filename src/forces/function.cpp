#include "forces/function.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace softsub::forces {

namespace {

template <class... Ts>
struct Overload : Ts... {
  using Ts::operator()...;
};
template <class... Ts>
Overload(Ts...) -> Overload<Ts...>;

// Largest magnitude any function returns: keeps r -> 0 limits finite (the sampled
// tables are float) while far beyond any force a stable scene can hold.
constexpr double kForceLimit = 1e12;

double clampForce(double v) { return std::clamp(v, -kForceLimit, kForceLimit); }

}  // namespace

std::string_view kindName(const PairFunction& f) {
  return std::visit(Overload{[](const Linear&) { return std::string_view("Linear"); },
                             [](const LennardJones&) { return std::string_view("LennardJones"); },
                             [](const LennardJonesForce&) {
                               return std::string_view("LennardJonesForce");
                             },
                             [](const Curve&) { return std::string_view("Curve"); }},
                    f);
}

double evaluate(const PairFunction& f, double r) {
  return std::visit(
      Overload{
          [r](const Linear& l) {
            if (r >= l.cutoff) return 0.0;
            const double v = l.atZero * (1.0 - r / l.cutoff);
            return std::clamp(v, l.min, l.max);
          },
          [r](const LennardJones& l) {
            if (r >= l.cutoff) return 0.0;
            if (r <= 0) return l.amplitude > 0 ? l.max : (l.amplitude < 0 ? l.min : 0.0);
            const double s6 = std::pow(l.finiteDistance / r, 6);
            const double v = 4.0 * l.amplitude * (s6 * s6 - s6);
            return std::clamp(clampForce(v), l.min, l.max);
          },
          [r](const LennardJonesForce& l) {
            if (r >= l.cutoff) return 0.0;
            if (r <= 0) return l.epsilon > 0 ? kForceLimit : 0.0;
            const double s6 = std::pow(l.sigma / r, 6);
            return clampForce(24.0 * l.epsilon / r * (2.0 * s6 * s6 - s6));
          },
          [r](const Curve& c) {
            const auto& p = c.points;
            const std::size_t n = p.size() / 2;
            if (n == 0 || r >= p[2 * (n - 1)]) return 0.0;
            if (r <= p[0]) return p[1];
            for (std::size_t k = 1; k < n; ++k) {
              const double r1 = p[2 * k];
              if (r < r1) {
                const double r0 = p[2 * (k - 1)], f0 = p[2 * (k - 1) + 1], f1 = p[2 * k + 1];
                return f0 + (f1 - f0) * (r - r0) / (r1 - r0);
              }
            }
            return 0.0;
          }},
      f);
}

double cutoff(const PairFunction& f) {
  return std::visit(Overload{[](const Linear& l) { return l.cutoff; },
                             [](const LennardJones& l) { return l.cutoff; },
                             [](const LennardJonesForce& l) { return l.cutoff; },
                             [](const Curve& c) {
                               return c.points.size() >= 2 ? c.points[c.points.size() - 2] : 0.0;
                             }},
                    f);
}

double potential(const PairFunction& f, double r) {
  const double rc = cutoff(f);
  if (r >= rc) return 0.0;
  if (const auto* lj = std::get_if<LennardJonesForce>(&f)) {
    auto u = [lj](double x) {
      const double s6 = std::pow(lj->sigma / x, 6);
      return 4.0 * lj->epsilon * (s6 * s6 - s6);
    };
    // Unshifted, as LAMMPS's lj/cut reports it: U(r) itself inside the cutoff.
    return r <= 0 ? std::numeric_limits<double>::infinity() : u(r);
  }
  // U(r) = integral from r to rc of F(x) dx (Simpson, fine steps: reports only).
  const int n = 2000;
  const double h = (rc - r) / n;
  double sum = evaluate(f, r) + evaluate(f, rc - 1e-12 * rc);
  for (int k = 1; k < n; ++k) sum += evaluate(f, r + k * h) * (k % 2 ? 4.0 : 2.0);
  return sum * h / 3.0;
}

}  // namespace softsub::forces
