#pragma once
// Scenario builders shared by tests and benchmarks: the same particle sets and models
// everywhere (Box2D's "shared/" idea).
#include <cmath>
#include <cstdint>

#include "support/clouds.h"
#include "fluid/fluid_params.h"
#include "forces/function.h"
#include "solver/model.h"

namespace softsub::scenarios {

/// A model of one fluid "goo" of n particles with the scene-default parameters.
inline solver::Model oneFluidModel(std::size_t n) {
  fluid::FluidParams p;
  solver::Model model;
  model.fluids.push_back({"goo", {0.8f, 0.5f, 0.2f}, p.particleSize, p.particleMass, 0,
                          static_cast<std::uint32_t>(n)});
  model.materials.push_back({static_cast<float>(1 / p.particleMass), static_cast<float>(p.particleSize / 2)});
  model.table = forces::InteractionTable(1);
  model.table.set(0, 0, {fluid::ownFunction(p), p.viscosity, 0});
  return model;
}

/// A Lennard-Jones liquid's model: one fluid "argon" of unit-mass atoms with the true
/// force alone (LennardJonesForce, epsilon = sigma = 1, cutoff rc; the closed-form
/// kernel's case), no gravity, velocity Verlet; no container.
inline solver::Model ljModel(double rc) {
  solver::Model m;
  m.gravity = Vec3::Zero();
  m.integrator = solver::Integrator::VelocityVerlet;
  m.fluids.push_back({"argon", {1, 1, 1}, 1, 1, 0, 0});
  m.materials.push_back({1.0f, 0.5f});
  m.table = forces::InteractionTable(1);
  m.table.set(0, 0, {forces::LennardJonesForce{1, 1, rc}, 0, 0});
  return m;
}

/// The seed's benchmark situation: one fluid of `n` particles as a cubic lattice block
/// (spacing `spacing`) resting above the floor of a container, symplectic Euler, 8
/// substeps at 24 fps. Model parameters are the scene defaults (fluid::FluidParams).
inline void fluidBlock(std::size_t n, double spacing, solver::Model& model, solver::State& state) {
  const auto side = static_cast<std::size_t>(std::ceil(std::cbrt(static_cast<double>(n))));
  model = oneFluidModel(n);
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

/// One fluid of `n` particles filling the floor of a closely fitting container to a
/// fixed depth of `layers` lattice layers (spacing `spacing`): the seed's benchmark
/// situation, a fluid in a container. With the depth fixed, more particles means a
/// wider pool, so the neighbours per particle stay the same and the cost per particle
/// should too (the linear-scaling check). Scene-default fluid parameters.
inline void fluidPool(std::size_t n, double spacing, std::size_t layers, solver::Model& model,
                      solver::State& state) {
  const auto side = static_cast<std::size_t>(
      std::ceil(std::sqrt(static_cast<double>(n) / static_cast<double>(layers))));
  model = oneFluidModel(n);
  const double half = 0.5 * static_cast<double>(side) * spacing + 0.5;
  solver::Container c;
  c.lo = {-half, 0, -half};
  c.hi = {half, 4.0 * static_cast<double>(layers) * spacing, half};
  model.container = c;
  state = solver::State{};
  state.particles.reserve(n);
  const double x0 = -half + 0.5 + 0.5 * spacing;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = k % side, j = (k / side) % side, l = k / (side * side);
    state.particles.add(static_cast<float>(x0 + static_cast<double>(i) * spacing),
                        static_cast<float>(0.5 + static_cast<double>(l) * spacing),
                        static_cast<float>(x0 + static_cast<double>(j) * spacing), 0, 0, 0, 0, 0);
  }
}

}  // namespace softsub::scenarios
