#pragma once
/// The parameters of one substance, with the seed's names.
#include "forces/function.h"

namespace softsub::fluid {

/// A fluid's own interaction: the seed's clamped Lennard-Jones-shaped force and its
/// viscosity. Units: lengths in scene units, forces in mass*units/s^2.
struct FluidParams {
  double interactionDistance = 1.5;  ///< cutoff of the fluid's own function, > 0
  double amplitude = 30;             ///< A in 4A((s/r)^12-(s/r)^6)
  double finiteDistance = 1;         ///< s: distance where the force is zero
  double minimumForce = -20;         ///< clamp: strongest attraction (<= 0 usually)
  double maximumForce = 400;         ///< clamp: strongest repulsion
  double viscosity = 1;              ///< damping of relative velocity, mass/s
  double particleSize = 1;           ///< particle diameter (display, walls, surfaces)
  double particleMass = 1;           ///< mass of one particle
  bool operator==(const FluidParams&) const = default;
};

/// The seed's same-fluid function as a pair function.
inline forces::PairFunction ownFunction(const FluidParams& p) {
  return forces::LennardJones{p.amplitude, p.finiteDistance, p.minimumForce, p.maximumForce,
                              p.interactionDistance};
}

}  // namespace softsub::fluid
