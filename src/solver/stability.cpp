#include "solver/stability.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <variant>

namespace softsub::solver {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// A mode that grows by more than this factor per second of simulated time is a blow-up.
constexpr double kGrowthLimit = 2;
/// Pieces the Lennard-Jones kinds are sampled into for their slope (the solver's table
/// has 2048; finer here so the kink at a clamp costs under 1% of the slope).
constexpr int kSlopeSamples = 8192;
/// Where LennardJonesForce's slope is measured from, in sigma.
constexpr double kLennardJonesForceInner = 0.9;

/// The distance the slope and the force are measured from.
double innerRadius(const forces::PairFunction& f) {
  if (const auto* lj = std::get_if<forces::LennardJonesForce>(&f)) return kLennardJonesForceInner * lj->sigma;
  return 0;
}

/// Visits F at kSlopeSamples + 1 points of [innerRadius, cutoff), the last just below
/// the cutoff (the table keeps a function's value up to it).
template <class Visit>
void sampleFunction(const forces::PairFunction& f, Visit&& visit) {
  const double lo = innerRadius(f);
  const double hi = forces::cutoff(f);
  if (!(hi > lo)) return;
  const double h = (hi - lo) / kSlopeSamples;
  for (int k = 0; k <= kSlopeSamples; ++k) {
    const double r = k == kSlopeSamples ? hi - 1e-9 * hi : lo + k * h;
    visit(r, forces::evaluate(f, r));
  }
}

/// The fastest mode's growth per second at time step dt (amplification^(1/dt)).
double growthPerSecond(Integrator integrator, double omegaDt, double dampingNumber, double dt) {
  const double rho = amplificationPerStep(integrator, omegaDt, dampingNumber);
  if (!(rho > 1)) return rho >= 0 ? std::min(1.0, std::pow(rho, 1 / dt)) : 1.0;
  return std::exp(std::min(std::log(rho) / dt, 700.0));
}

/// The numbers of a pair at `substeps`, without minimumSubsteps.
struct Numbers {
  double omegaDt = 0, damping = 0, travel = 0, growth = 1;
  StabilityVerdict verdict = StabilityVerdict::Stable;
};

/// Everything about an interaction that does not depend on the time step.
struct PairConstants {
  double omega = 0;     ///< sqrt(kLatticeSpringFactor k / mu), 1/s
  double gamma = 0;     ///< damping rate, 1/s
  double push = 0;      ///< max |F| / mu / cutoff, 1/s^2
};

Numbers numbersAt(const PairConstants& c, double framesPerSecond, int substeps, Integrator integrator) {
  Numbers n;
  const double dt = 1.0 / (framesPerSecond * substeps);
  n.omegaDt = c.omega * dt;
  n.damping = c.gamma * dt;
  n.travel = c.push * dt * dt;
  n.growth = growthPerSecond(integrator, n.omegaDt, n.damping, dt);
  if (n.growth > kGrowthLimit || n.travel > 1) {
    n.verdict = StabilityVerdict::Unstable;
    return n;
  }
  // Twice the time step: the same criteria with a factor 2 to spare.
  const double growth2 = growthPerSecond(integrator, 2 * n.omegaDt, 2 * n.damping, 2 * dt);
  n.verdict = growth2 > kGrowthLimit || 4 * n.travel > 1 ? StabilityVerdict::Marginal : StabilityVerdict::Stable;
  return n;
}

/// The smallest substep count in [1, kMaxStableSubsteps] that is Stable (0 if none).
/// Every criterion only improves as the time step shrinks, so a bisection finds it.
int minimumStableSubsteps(const PairConstants& c, double framesPerSecond, Integrator integrator) {
  auto stable = [&](int s) { return numbersAt(c, framesPerSecond, s, integrator).verdict == StabilityVerdict::Stable; };
  if (!stable(kMaxStableSubsteps)) return 0;
  int lo = 0, hi = kMaxStableSubsteps;  // lo is not stable (or 0), hi is
  while (hi - lo > 1) {
    const int mid = lo + (hi - lo) / 2;
    (stable(mid) ? hi : lo) = mid;
  }
  return hi;
}

double reducedMass(double a, double b) {
  if (std::isinf(a)) return b;
  if (std::isinf(b)) return a;
  return a * b / (a + b);
}

/// The objects of each body row (indexed by row - fluids), named, and their lightest
/// dynamic mass (infinity when all are static).
struct BodyRow {
  std::string names;
  double mass = kInfinity;
  bool used = false;
};

std::vector<BodyRow> bodyRows(const Model& model, const State* state) {
  const std::size_t nf = model.fluids.size();
  const std::size_t rows = model.materials.size() > nf ? model.materials.size() - nf : 0;
  std::vector<BodyRow> out(rows);
  const auto& bodies = model.bodies.bodies;
  // Each body's row, from one of its particles in the state.
  std::vector<std::size_t> rowOf(bodies.size(), rows);
  if (state != nullptr) {
    const ParticleStore& s = state->particles;
    const std::uint32_t first = model.bodies.firstEntity;
    for (std::size_t i = 0; i < s.size(); ++i) {
      if (s.owner[i] < first) continue;
      const std::size_t b = s.owner[i] - first;
      if (b < bodies.size() && s.material[i] >= nf) rowOf[b] = s.material[i] - nf;
    }
  }
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    for (std::size_t r = 0; r < rows; ++r) {
      if (rowOf[b] != rows && rowOf[b] != r) continue;
      BodyRow& row = out[r];
      if (row.used) row.names += ", ";
      row.names += bodies[b].name;
      row.used = true;
      if (bodies[b].dynamic) row.mass = std::min(row.mass, bodies[b].mass);
    }
  }
  return out;
}

}  // namespace

std::string_view verdictName(StabilityVerdict verdict) {
  switch (verdict) {
    case StabilityVerdict::Stable: return "stable";
    case StabilityVerdict::Marginal: return "marginal";
    case StabilityVerdict::Unstable: return "unstable";
  }
  return "unknown";
}

double maximumSlope(const forces::PairFunction& f) {
  if (const auto* l = std::get_if<forces::Linear>(&f)) {
    // The line is steep wherever it is not clamped; clamped everywhere it is flat.
    if (!(l->cutoff > 0) || l->atZero == 0) return 0;
    const double lo = std::max(std::min(l->atZero, 0.0), l->min);
    const double hi = std::min(std::max(l->atZero, 0.0), l->max);
    return hi > lo ? std::abs(l->atZero) / l->cutoff : 0;
  }
  if (const auto* c = std::get_if<forces::Curve>(&f)) {
    double k = 0;
    for (std::size_t i = 2; i + 1 < c->points.size(); i += 2) {
      const double dr = c->points[i] - c->points[i - 2];
      if (dr > 0) k = std::max(k, std::abs(c->points[i + 1] - c->points[i - 1]) / dr);
    }
    return k;
  }
  double k = 0, lastR = 0, lastF = 0;
  bool first = true;
  sampleFunction(f, [&](double r, double v) {
    if (!first && r > lastR) k = std::max(k, std::abs(v - lastF) / (r - lastR));
    first = false;
    lastR = r;
    lastF = v;
  });
  return k;
}

double maximumForce(const forces::PairFunction& f) {
  if (const auto* c = std::get_if<forces::Curve>(&f)) {
    double m = 0;
    for (std::size_t i = 1; i < c->points.size(); i += 2) m = std::max(m, std::abs(c->points[i]));
    return m;
  }
  double m = 0;
  sampleFunction(f, [&](double, double v) { m = std::max(m, std::abs(v)); });
  return m;
}

double amplificationPerStep(Integrator integrator, double omegaDt, double dampingNumber) {
  // State (x, u = v dt) or, for velocity Verlet, (x, u, phi = a dt^2 of the last force
  // evaluation): one substep is a linear map, and its spectral radius is the growth.
  const double w2 = omegaDt * omegaDt;
  const double d = dampingNumber;
  switch (integrator) {
    case Integrator::ExplicitEuler: {
      Eigen::Matrix2d a;
      a << 1, 1, -w2, 1 - d;
      return a.eigenvalues().cwiseAbs().maxCoeff();
    }
    case Integrator::SymplecticEuler: {
      Eigen::Matrix2d a;
      a << 1 - w2, 1 - d, -w2, 1 - d;
      return a.eigenvalues().cwiseAbs().maxCoeff();
    }
    case Integrator::VelocityVerlet: {
      // u_h = u + phi/2; x' = x + u_h; phi' = -w2 x' - d u_h; u' = u_h + phi'/2.
      Eigen::Matrix3d a;
      a << 1, 1, 0.5,                                            // x'
          -w2 / 2, 1 - w2 / 2 - d / 2, 0.5 - w2 / 4 - d / 4,     // u'
          -w2, -w2 - d, -w2 / 2 - d / 2;                         // phi'
      return a.eigenvalues().cwiseAbs().maxCoeff();
    }
  }
  return kInfinity;
}

PairStability assessInteraction(const forces::Interaction& interaction, double massA, double massB,
                                double framesPerSecond, int substeps, Integrator integrator) {
  PairStability p;
  p.stiffness = maximumSlope(interaction.function);
  p.reducedMass = reducedMass(massA, massB);
  PairConstants c;
  c.omega = std::sqrt(kLatticeSpringFactor * p.stiffness / p.reducedMass);
  c.gamma = (kLatticeViscosityFactor * std::abs(interaction.damping) +
             kLatticeSpringFactor * std::abs(interaction.relativeVelocity)) /
            p.reducedMass;
  const double range = forces::cutoff(interaction.function);
  c.push = range > 0 ? maximumForce(interaction.function) / p.reducedMass / range : 0;
  const Numbers n = numbersAt(c, framesPerSecond, substeps, integrator);
  p.omegaDt = n.omegaDt;
  p.dampingNumber = n.damping;
  p.travelNumber = n.travel;
  p.growthPerSecond = n.growth;
  p.verdict = n.verdict;
  p.minimumSubsteps = minimumStableSubsteps(c, framesPerSecond, integrator);
  return p;
}

StabilityReport assessStability(const Model& model, const State* state) {
  StabilityReport report;
  report.substeps = model.substeps;
  report.dt = model.dt();
  const std::size_t nf = std::min(model.fluids.size(), model.table.materials());
  auto add = [&](std::size_t a, std::size_t b, double massB, std::string second) {
    PairStability p = assessInteraction(model.table.interaction(a, b), model.fluids[a].particleMass, massB,
                                        model.framesPerSecond, model.substeps, model.integrator);
    p.first = model.fluids[a].name;
    p.second = std::move(second);
    p.materialA = a;
    p.materialB = b;
    report.pairs.push_back(std::move(p));
  };
  for (std::size_t a = 0; a < nf; ++a) {
    if (model.fluids[a].count == 0) continue;
    for (std::size_t b = a; b < nf; ++b)
      if (model.fluids[b].count > 0) add(a, b, model.fluids[b].particleMass, model.fluids[b].name);
  }
  const std::vector<BodyRow> rows = bodyRows(model, state);
  for (std::size_t r = 0; r < rows.size(); ++r) {
    if (!rows[r].used || nf + r >= model.table.materials()) continue;
    for (std::size_t a = 0; a < nf; ++a)
      if (model.fluids[a].count > 0) add(a, nf + r, rows[r].mass, rows[r].names);
  }

  report.worst = report.pairs.size();
  report.minimumSubsteps = 1;
  // The worst pair needs the most substeps; "none suffices" (0) is worst of all.
  auto need = [](const PairStability& p) {
    return p.minimumSubsteps == 0 ? kMaxStableSubsteps + 1 : p.minimumSubsteps;
  };
  for (std::size_t i = 0; i < report.pairs.size(); ++i) {
    const PairStability& p = report.pairs[i];
    report.verdict = std::max(report.verdict, p.verdict);
    if (report.worst == report.pairs.size() || need(p) > need(report.pairs[report.worst]) ||
        (need(p) == need(report.pairs[report.worst]) && p.verdict > report.pairs[report.worst].verdict))
      report.worst = i;
  }
  if (report.worst < report.pairs.size()) report.minimumSubsteps = report.pairs[report.worst].minimumSubsteps;
  return report;
}

}  // namespace softsub::solver
