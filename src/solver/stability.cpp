#include "solver/stability.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <span>
#include <tuple>
#include <unordered_map>
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

/// Particles sampled for the most crowded neighbourhood (latticeDampingRate).
constexpr std::size_t kCrowdSamples = 64;
/// Particles of the patch whose damping operator is iterated, at most.
constexpr std::size_t kPatchParticles = 3000;
/// Lanczos steps on the patch.
constexpr int kLanczosSteps = 60;

/// The particles of each material, in store order (one pass for every pair to share).
std::vector<std::vector<std::uint32_t>> particlesByMaterial(const ParticleStore& s, std::size_t materials) {
  std::vector<std::vector<std::uint32_t>> out(materials);
  for (std::uint32_t i = 0; i < s.size(); ++i)
    if (s.material[i] < materials) out[s.material[i]].push_back(i);
  return out;
}

double distance2(const ParticleStore& s, std::uint32_t i, std::uint32_t j) {
  const double dx = double(s.px[j]) - s.px[i], dy = double(s.py[j]) - s.py[i], dz = double(s.pz[j]) - s.pz[i];
  return dx * dx + dy * dy + dz * dz;
}

/// latticeDampingRate on the particles `as` of material a and `bs` of b (the same list
/// when a == b).
double latticeRate(const ParticleStore& s, std::uint16_t a, std::uint16_t b,
                   std::span<const std::uint32_t> as, std::span<const std::uint32_t> bs, double damping,
                   double relativeVelocity, double cutoff, double inverseMassA, double inverseMassB) {
  if (!(cutoff > 0) || (damping == 0 && relativeVelocity == 0) || as.empty() || bs.empty()) return 0;
  const double c2 = cutoff * cutoff;
  // The most crowded of up to kCrowdSamples a particles, spread over the store: where
  // the fastest mode lives (the first of equals, so the same state gives the same answer).
  std::uint32_t centre = as.front();
  std::size_t most = 0;
  const std::size_t samples = std::min(as.size(), kCrowdSamples);
  for (std::size_t k = 0; k < samples; ++k) {
    const std::uint32_t i = as[k * as.size() / samples];
    std::size_t n = 0;
    for (const std::uint32_t j : bs) n += j != i && distance2(s, i, j) < c2;
    if (n > most) {
      most = n;
      centre = i;
    }
  }
  if (most == 0) return 0;
  // The patch: the kPatchParticles a and b particles nearest the centre.
  std::vector<std::pair<double, std::uint32_t>> near;
  auto gather = [&](std::span<const std::uint32_t> list) {
    for (const std::uint32_t j : list) near.emplace_back(distance2(s, centre, j), j);
  };
  gather(as);
  if (a != b) gather(bs);
  if (near.size() > kPatchParticles) {
    std::nth_element(near.begin(), near.begin() + kPatchParticles, near.end());
    near.resize(kPatchParticles);
  }
  std::sort(near.begin(), near.end(), [](const auto& x, const auto& y) { return x.second < y.second; });
  const std::size_t n = near.size();
  // Its a-b pairs within the cutoff, with their unit vectors.
  struct Edge {
    std::uint32_t i, j;
    double nx, ny, nz;
  };
  std::vector<Edge> edges;
  std::vector<double> weight(n);  // sqrt(1 / mass): the operator M^-1/2 D M^-1/2 is symmetric
  for (std::size_t p = 0; p < n; ++p) {
    const std::uint32_t i = near[p].second;
    weight[p] = std::sqrt(s.material[i] == a ? inverseMassA : inverseMassB);
    for (std::size_t q = p + 1; q < n; ++q) {
      const std::uint32_t j = near[q].second;
      const bool pair = (s.material[i] == a && s.material[j] == b) || (s.material[i] == b && s.material[j] == a);
      const double d2 = distance2(s, i, j);
      if (!pair || !(d2 < c2) || !(d2 > 0)) continue;
      const double r = std::sqrt(d2);
      edges.push_back({static_cast<std::uint32_t>(p), static_cast<std::uint32_t>(q), (double(s.px[j]) - s.px[i]) / r,
                       (double(s.py[j]) - s.py[i]) / r, (double(s.pz[j]) - s.pz[i]) / r});
    }
  }
  if (edges.empty()) return 0;
  // The largest eigenvalue of A = W D W, D the velocity terms' operator (per pair,
  // (c I + k_rel n n^T) on the difference of the two velocities), by Lanczos: its
  // tridiagonal matrix's largest eigenvalue approaches A's from below, much faster than
  // a power iteration does on a lattice's dense band of fast modes.
  auto apply = [&](const std::vector<double>& x, std::vector<double>& u, std::vector<double>& y) {
    for (std::size_t k = 0; k < x.size(); ++k) u[k] = weight[k / 3] * x[k];
    std::fill(y.begin(), y.end(), 0.0);
    for (const Edge& e : edges) {
      const double dx = u[3 * e.i] - u[3 * e.j], dy = u[3 * e.i + 1] - u[3 * e.j + 1],
                   dz = u[3 * e.i + 2] - u[3 * e.j + 2];
      const double along = relativeVelocity * (dx * e.nx + dy * e.ny + dz * e.nz);
      const double gx = damping * dx + along * e.nx, gy = damping * dy + along * e.ny, gz = damping * dz + along * e.nz;
      y[3 * e.i] += gx;
      y[3 * e.i + 1] += gy;
      y[3 * e.i + 2] += gz;
      y[3 * e.j] -= gx;
      y[3 * e.j + 1] -= gy;
      y[3 * e.j + 2] -= gz;
    }
    for (std::size_t k = 0; k < y.size(); ++k) y[k] *= weight[k / 3];
  };
  auto dot = [](const std::vector<double>& p, const std::vector<double>& q) {
    double sum = 0;
    for (std::size_t k = 0; k < p.size(); ++k) sum += p[k] * q[k];
    return sum;
  };
  std::vector<double> v(3 * n), previous(3 * n, 0.0), u(3 * n), w(3 * n);
  for (std::size_t k = 0; k < v.size(); ++k) v[k] = static_cast<double>(((k * 2654435761u) >> 7) % 2001) / 1000.0 - 1;
  double norm = std::sqrt(dot(v, v));
  for (double& e : v) e /= norm;
  std::vector<double> alpha, beta;  // the tridiagonal matrix: diagonal, off-diagonal
  for (int it = 0; it < kLanczosSteps; ++it) {
    apply(v, u, w);
    alpha.push_back(dot(w, v));
    const double last = beta.empty() ? 0.0 : beta.back();
    for (std::size_t k = 0; k < w.size(); ++k) w[k] -= alpha.back() * v[k] + last * previous[k];
    norm = std::sqrt(dot(w, w));
    if (!(norm > 1e-12 * std::abs(alpha.front()))) break;
    beta.push_back(norm);
    previous.swap(v);
    for (std::size_t k = 0; k < w.size(); ++k) v[k] = w[k] / norm;
  }
  const Eigen::Index m = static_cast<Eigen::Index>(alpha.size());
  Eigen::MatrixXd t = Eigen::MatrixXd::Zero(m, m);
  for (Eigen::Index k = 0; k < m; ++k) {
    t(k, k) = alpha[static_cast<std::size_t>(k)];
    if (k + 1 < m) t(k, k + 1) = t(k + 1, k) = beta[static_cast<std::size_t>(k)];
  }
  const double rate = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(t, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff();
  return std::max(rate, 0.0);
}

/// The fastest mode's growth per second at time step dt (amplification^(1/dt)).
double growthPerSecond(Integrator integrator, double omegaDt, double dampingNumber, double dt) {
  const double rho = amplificationPerStep(integrator, omegaDt, dampingNumber);
  if (!(rho > 1)) return rho >= 0 ? std::min(1.0, std::pow(rho, 1 / dt)) : 1.0;
  return std::exp(std::min(std::log(rho) / dt, 700.0));
}

/// The numbers of a pair at `substeps`, without minimumSubsteps.
struct Numbers {
  double omegaDt = 0, damping = 0, latticeDamping = 0, travel = 0, growth = 1;
  StabilityVerdict verdict = StabilityVerdict::Stable;
};

/// Everything about an interaction that does not depend on the time step.
struct PairConstants {
  double omega = 0;     ///< sqrt(kLatticeSpringFactor k / mu), 1/s
  double gamma = 0;     ///< damping rate, 1/s
  double push = 0;      ///< max |F| / mu / cutoff, 1/s^2
  double lattice = 0;   ///< the state's fastest damping rate (latticeDampingRate), 1/s
};

Numbers numbersAt(const PairConstants& c, double framesPerSecond, int substeps, Integrator integrator) {
  Numbers n;
  const double dt = 1.0 / (framesPerSecond * substeps);
  n.omegaDt = c.omega * dt;
  n.damping = c.gamma * dt;
  n.travel = c.push * dt * dt;
  n.latticeDamping = c.lattice * dt;
  // The fcc model mode, and the damping alone at the rate the particles' own
  // neighbourhood gives it (many neighbours within a wide cutoff).
  n.growth = std::max(growthPerSecond(integrator, n.omegaDt, n.damping, dt),
                      growthPerSecond(integrator, 0, n.latticeDamping, dt));
  if (n.growth > kGrowthLimit || n.travel > 1) {
    n.verdict = StabilityVerdict::Unstable;
    return n;
  }
  // Twice the time step: the same criteria with a factor 2 to spare.
  const double growth2 = std::max(growthPerSecond(integrator, 2 * n.omegaDt, 2 * n.damping, 2 * dt),
                                  growthPerSecond(integrator, 0, 2 * n.latticeDamping, 2 * dt));
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

double latticeDampingRate(const ParticleStore& s, std::uint16_t a, std::uint16_t b, double damping,
                          double relativeVelocity, double cutoff, double inverseMassA, double inverseMassB) {
  const std::vector<std::vector<std::uint32_t>> of = particlesByMaterial(s, std::size_t{std::max(a, b)} + 1);
  return latticeRate(s, a, b, of[a], of[b], damping, relativeVelocity, cutoff, inverseMassA, inverseMassB);
}

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

namespace {
/// The largest modulus of the eigenvalues of [[a, b], [c, d]], in closed form (a scene of
/// a thousand fluids asks for it some ten million times).
double spectralRadius2(double a, double b, double c, double d) {
  const double half = 0.5 * (a + d);
  const double det = a * d - b * c;
  const double disc = half * half - det;
  if (disc >= 0) return std::abs(half) + std::sqrt(disc);  // two real eigenvalues
  return std::sqrt(det);  // a complex pair: |lambda|^2 = det (> half^2 >= 0 here)
}
}  // namespace

double amplificationPerStep(Integrator integrator, double omegaDt, double dampingNumber) {
  // State (x, u = v dt) or, for velocity Verlet, (x, u, phi = a dt^2 of the last force
  // evaluation): one substep is a linear map, and its spectral radius is the growth.
  const double w2 = omegaDt * omegaDt;
  const double d = dampingNumber;
  switch (integrator) {
    case Integrator::ExplicitEuler: return spectralRadius2(1, 1, -w2, 1 - d);
    case Integrator::SymplecticEuler: return spectralRadius2(1 - w2, 1 - d, -w2, 1 - d);
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

namespace {

/// What assessInteraction needs of a function: its steepest slope and strongest force.
struct FunctionNumbers {
  double slope = 0;
  double force = 0;
};

PairStability assessWith(const forces::Interaction& interaction, FunctionNumbers f, double mu,
                         double framesPerSecond, int substeps, Integrator integrator, double latticeDamping) {
  PairStability p;
  p.stiffness = f.slope;
  p.reducedMass = mu;
  PairConstants c;
  c.omega = std::sqrt(kLatticeSpringFactor * p.stiffness / p.reducedMass);
  c.gamma = (kLatticeViscosityFactor * std::abs(interaction.damping) +
             kLatticeSpringFactor * std::abs(interaction.relativeVelocity)) /
            p.reducedMass;
  const double range = forces::cutoff(interaction.function);
  c.push = range > 0 ? f.force / p.reducedMass / range : 0;
  c.lattice = latticeDamping;
  const Numbers n = numbersAt(c, framesPerSecond, substeps, integrator);
  p.omegaDt = n.omegaDt;
  p.dampingNumber = n.damping;
  p.latticeDampingNumber = n.latticeDamping;
  p.travelNumber = n.travel;
  p.growthPerSecond = n.growth;
  p.verdict = n.verdict;
  p.minimumSubsteps = minimumStableSubsteps(c, framesPerSecond, integrator);
  return p;
}

/// Each material's particles and their bounding box, for latticeDampingRate on every
/// pair of a scene (a scene may have a thousand fluids: one pass over the store, and no
/// pair looked at closer whose boxes lie further apart than its cutoff).
class MaterialParticles {
 public:
  MaterialParticles(const ParticleStore& s, std::size_t materials)
      : store_(s), of_(particlesByMaterial(s, materials)), lo_(materials), hi_(materials) {
    for (std::size_t m = 0; m < materials; ++m) {
      lo_[m] = {kInfinity, kInfinity, kInfinity};
      hi_[m] = {-kInfinity, -kInfinity, -kInfinity};
      for (const std::uint32_t i : of_[m]) {
        const std::array<double, 3> p{s.px[i], s.py[i], s.pz[i]};
        for (int k = 0; k < 3; ++k) {
          lo_[m][k] = std::min(lo_[m][k], p[k]);
          hi_[m][k] = std::max(hi_[m][k], p[k]);
        }
      }
    }
  }

  double rate(std::size_t a, std::size_t b, double damping, double relativeVelocity, double cutoff,
              double inverseMassA, double inverseMassB) const {
    for (int k = 0; k < 3; ++k)  // no a particle within the cutoff of a b particle
      if (lo_[a][k] - hi_[b][k] >= cutoff || lo_[b][k] - hi_[a][k] >= cutoff) return 0;
    return latticeRate(store_, static_cast<std::uint16_t>(a), static_cast<std::uint16_t>(b), of_[a], of_[b],
                       damping, relativeVelocity, cutoff, inverseMassA, inverseMassB);
  }

 private:
  const ParticleStore& store_;
  std::vector<std::vector<std::uint32_t>> of_;
  std::vector<std::array<double, 3>> lo_, hi_;
};

}  // namespace

PairStability assessInteraction(const forces::Interaction& interaction, double massA, double massB,
                                double framesPerSecond, int substeps, Integrator integrator,
                                double latticeDamping) {
  return assessWith(interaction, {maximumSlope(interaction.function), maximumForce(interaction.function)},
                    reducedMass(massA, massB), framesPerSecond, substeps, integrator, latticeDamping);
}

StabilityReport assessStability(const Model& model, const State* state) {
  StabilityReport report;
  report.substeps = model.substeps;
  report.dt = model.dt();
  const std::size_t nf = std::min(model.fluids.size(), model.table.materials());
  std::optional<MaterialParticles> particles;
  if (state != nullptr) particles.emplace(state->particles, model.table.materials());
  // A scene of many fluids has about fluids^2 / 2 pairs, most of them alike (the one
  // FluidFluid function, the same masses): each function's slope and force (a few
  // thousand samples) and each distinct pair's estimate are worked out once. The table
  // keeps one sample offset per distinct function, which names it here.
  std::unordered_map<std::uint32_t, FunctionNumbers> byFunction;
  std::map<std::tuple<std::uint32_t, double, double, double, double>, PairStability> byPair;
  auto add = [&](std::size_t a, std::size_t b, double massB, std::string second) {
    // A fluid/object pair's velocity terms are taken implicitly on both sides
    // (rigid::RigidSolver::gatherDrag): they damp, and limit no time step. Only its
    // function counts.
    const forces::Interaction& entry = model.table.interaction(a, b);
    std::optional<forces::Interaction> withoutDrag;
    if (b >= nf && (entry.damping != 0 || entry.relativeVelocity != 0)) {
      withoutDrag = entry;
      withoutDrag->damping = withoutDrag->relativeVelocity = 0;
    }
    const forces::Interaction& interaction = withoutDrag ? *withoutDrag : entry;
    const std::uint32_t function = model.table.entry(a, b).offset;
    const double massA = model.fluids[a].particleMass;
    const double lattice = particles ? particles->rate(a, b, std::abs(interaction.damping),
                                                       std::abs(interaction.relativeVelocity),
                                                       forces::cutoff(interaction.function), 1 / massA,
                                                       std::isinf(massB) ? 0.0 : 1 / massB)
                                     : 0;
    const double mu = reducedMass(massA, massB);
    const auto key =
        std::make_tuple(function, interaction.damping, interaction.relativeVelocity, mu, lattice);
    auto known = byPair.find(key);
    if (known == byPair.end()) {
      auto numbers = byFunction.find(function);
      if (numbers == byFunction.end())
        numbers = byFunction
                      .emplace(function, FunctionNumbers{maximumSlope(interaction.function),
                                                         maximumForce(interaction.function)})
                      .first;
      known = byPair
                  .emplace(key, assessWith(interaction, numbers->second, mu, model.framesPerSecond,
                                           model.substeps, model.integrator, lattice))
                  .first;
    }
    PairStability p = known->second;
    p.first = model.fluids[a].name;
    p.second = std::move(second);
    p.materialA = a;
    p.materialB = b;
    report.pairs.push_back(std::move(p));
  };
  for (std::size_t a = 0; a < nf; ++a) {
    if (model.fluids[a].count == 0) continue;
    for (std::size_t b = a; b < nf; ++b)  // a fluid of one particle has no pair of its own
      if (model.fluids[b].count > (b == a ? 1u : 0u))
        add(a, b, model.fluids[b].particleMass, model.fluids[b].name);
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
