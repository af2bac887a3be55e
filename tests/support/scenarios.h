#pragma once
// Scenario builders shared by tests and benchmarks: the same particle sets and models
// everywhere (Box2D's "shared/" idea).
#include <cmath>
#include <cstdint>

#include "support/clouds.h"
#include "fluid/fluid_params.h"
#include "solver/model.h"

namespace softsub::scenarios {

/// The seed's benchmark situation: one fluid of `n` particles as a cubic lattice block
/// (spacing `spacing`) resting above the floor of a container, symplectic Euler, 8
/// substeps at 24 fps. Model parameters are the scene defaults (fluid::FluidParams).
inline void fluidBlock(std::size_t n, double spacing, solver::Model& model, solver::State& state) {
  const auto side = static_cast<std::size_t>(std::ceil(std::cbrt(static_cast<double>(n))));
  fluid::FluidParams p;
  model = solver::Model{};
  model.fluids.push_back({"goo", {0.8f, 0.5f, 0.2f}, p.particleSize, p.particleMass, 0,
                          static_cast<std::uint32_t>(n)});
  model.materials.push_back({static_cast<float>(1 / p.particleMass), static_cast<float>(p.particleSize / 2)});
  model.table = forces::InteractionTable(1);
  model.table.set(0, 0, {fluid::ownFunction(p), p.viscosity, 0});
  const double width = static_cast<double>(side) * spacing + 4;
  solver::Container c;
  c.lo = {-width, 0, -width};
  c.hi = {width, 10 * width, width};
  model.container = c;
  state = solver::State{};
  state.particles.reserve(n);
  const double x0 = -0.5 * static_cast<double>(side) * spacing;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = k % side, j = (k / side) % side, l = k / (side * side);
    state.particles.add(static_cast<float>(x0 + static_cast<double>(i) * spacing),
                        static_cast<float>(0.5 + static_cast<double>(l) * spacing),
                        static_cast<float>(x0 + static_cast<double>(j) * spacing), 0, 0, 0, 0, 0);
  }
}

}  // namespace softsub::scenarios
