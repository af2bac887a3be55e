#include "solver/energy.h"

#include <cmath>
#include <vector>

#include "neighbors/cell_grid.h"
#include "rigid/body.h"

namespace softsub::solver {

namespace {

// U(r) = integral from r to the cutoff of the sampled force (pieces of the table, linear
// in r), so that F = -dU/dr holds exactly for the force the kernel applies.
class PotentialTable {
 public:
  PotentialTable(const forces::InteractionTable& table) : table_(table), tail_(table.entries().size()) {
    const auto samples = table.samples();
    for (std::size_t e = 0; e < tail_.size(); ++e) {
      const forces::PairEntry& entry = table.entries()[e];
      if (entry.cutoff2 <= 0 || entry.invDr <= 0) continue;
      const std::size_t pieces = std::size_t{entry.lastPiece} + 1;
      const double h = 1.0 / entry.invDr;
      // tail[k]: the integral over pieces k .. last.
      std::vector<double>& tail = tail_[e];
      tail.assign(pieces + 1, 0.0);
      for (std::size_t k = pieces; k-- > 0;) {
        const double v = samples[entry.offset + 2 * k], d = samples[entry.offset + 2 * k + 1];
        tail[k] = tail[k + 1] + h * (v + 0.5 * d);
      }
    }
  }

  // U for the pair (a, b) at distance r (< its cutoff).
  double at(std::size_t a, std::size_t b, double r) const {
    const std::size_t e = a * table_.materials() + b;
    const forces::PairEntry& entry = table_.entries()[e];
    const std::vector<double>& tail = tail_[e];
    if (tail.empty()) return 0.0;
    const double t = r * entry.invDr;
    const auto k = std::min(static_cast<std::size_t>(t), std::size_t{entry.lastPiece});
    const double u = t - static_cast<double>(k);  // position inside piece k, 0..1
    const auto samples = table_.samples();
    const double v = samples[entry.offset + 2 * k], d = samples[entry.offset + 2 * k + 1];
    const double h = 1.0 / entry.invDr;
    // Integral over [u, 1] of (v + d s) h ds.
    return tail[k + 1] + h * (v * (1.0 - u) + 0.5 * d * (1.0 - u * u));
  }

 private:
  const forces::InteractionTable& table_;
  std::vector<std::vector<double>> tail_;
};

}  // namespace

EnergyReport measureEnergy(const Model& model, const State& state) {
  EnergyReport out;
  ParticleStore s = state.particles;  // the grid sorts its store: work on a copy
  const std::uint32_t firstBody = model.bodies.empty() ? UINT32_MAX : model.bodies.firstEntity;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s.owner[i] >= firstBody) continue;
    const double im = model.materials[s.material[i]].inverseMass;
    if (im <= 0) continue;
    const double m = 1.0 / im;
    out.kinetic += 0.5 * m * (double(s.vx[i]) * s.vx[i] + double(s.vy[i]) * s.vy[i] + double(s.vz[i]) * s.vz[i]);
    out.gravity -= m * (model.gravity.x() * s.px[i] + model.gravity.y() * s.py[i] + model.gravity.z() * s.pz[i]);
  }
  const double cutoff = model.table.maxCutoff();
  if (cutoff > 0 && s.size() > 1) {
    const PotentialTable potential(model.table);
    neighbors::CellGrid grid;
    grid.rebuild(s, static_cast<float>(cutoff));
    grid.forEachCandidatePair([&](std::uint32_t i, std::uint32_t j) {
      if (s.owner[i] >= firstBody && s.owner[j] >= firstBody) return;
      const forces::PairEntry& e = model.table.entry(s.material[i], s.material[j]);
      const double dx = double(s.px[j]) - s.px[i], dy = double(s.py[j]) - s.py[i], dz = double(s.pz[j]) - s.pz[i];
      const double r2 = dx * dx + dy * dy + dz * dz;
      if (!(r2 < e.cutoff2)) return;
      out.pair += potential.at(s.material[i], s.material[j], std::sqrt(r2));
    });
  }
  for (std::size_t b = 0; b < model.bodies.bodies.size() && b < state.bodies.size(); ++b) {
    const rigid::BodyInfo& info = model.bodies.bodies[b];
    if (!info.dynamic) continue;
    const rigid::BodyState& st = state.bodies[b];
    out.bodies += 0.5 * info.mass * st.velocity.squaredNorm() + 0.5 * rigid::angularVelocity(info, st).dot(st.angularMomentum);
    out.gravity -= info.mass * model.gravity.dot(st.position);
  }
  return out;
}

}  // namespace softsub::solver
