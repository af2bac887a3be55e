#pragma once
/// Energy of a state under its model, for `run --stats` and the LAMMPS comparison: the
/// numbers a user checks conservation with (no viscosity, no walls losing energy: the
/// total stays constant up to the integrator's error).
#include "solver/model.h"

namespace softsub::solver {

/// Energies in the scene's units (mass x length^2 / s^2).
struct EnergyReport {
  double kinetic = 0;    ///< fluid particles: sum of m v^2 / 2
  double pair = 0;       ///< sum over pairs within their cutoff of U(r), U the integral of
                         ///< the sampled force the solver uses, zero at the cutoff
  double gravity = 0;    ///< -sum of m g . x over fluid particles and dynamic bodies
  double bodies = 0;     ///< dynamic bodies: M v^2 / 2 + omega . L / 2
  [[nodiscard]] double total() const { return kinetic + pair + gravity + bodies; }
};

/// Measures `state` (does not change it: pairs are found on a copy of the positions).
/// Pairs of two particles of rigid bodies (contacts by impulse, not a potential) are left
/// out of `pair`.
[[nodiscard]] EnergyReport measureEnergy(const Model& model, const State& state);

}  // namespace softsub::solver
