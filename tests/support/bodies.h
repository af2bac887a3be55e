#pragma once
// Scenes with rigid bodies, built as descriptions and compiled like a scene file: shared
// by the rigid-body tests, the examples' checks and the benchmarks.
#include <memory>
#include <cmath>
#include <string>

#include "scene/compile.h"
#include "solver/simulation.h"

namespace softsub::scenarios {

/// A primitive object (no mesh file).
inline scene::ObjectDesc primitiveObject(std::string name, scene::ObjectShape shape, std::vector<double> size,
                                         double particleSize, const Vec3& position) {
  scene::ObjectDesc o;
  o.name = std::move(name);
  o.shape = shape;
  o.size = std::move(size);
  o.particleSize = particleSize;
  o.initialPosition = position;
  return o;
}

/// A compiled scene and a simulation of it (the model lives as long as the simulation).
struct BodyRun {
  explicit BodyRun(const scene::SceneDesc& desc) : compiled(scene::compile(desc)) {
    sim = std::make_unique<solver::Simulation>(compiled.model, std::move(compiled.state));
  }
  scene::Compiled compiled;
  std::unique_ptr<solver::Simulation> sim;

  [[nodiscard]] const rigid::BodyState& body(std::size_t b) const { return sim->state().bodies.at(b); }
  [[nodiscard]] const rigid::BodyInfo& info(std::size_t b) const { return compiled.model.bodies.bodies.at(b); }
};

}  // namespace softsub::scenarios

namespace softsub::scenarios {

/// The rigid-body benchmark scene: a pool of `fluidParticles` goo particles (lattice
/// spacing 1, 10 layers deep, filling the floor of a closely fitting container) with
/// `bodies` dynamic bodies (boxes of 2 and balls of radius 1.2, particle size 0.5, a
/// little turned) in a grid just above it, falling in.
inline scene::SceneDesc bodiesInPool(std::size_t fluidParticles, std::size_t bodies) {
  scene::SceneDesc d;
  const double side = std::ceil(std::sqrt(static_cast<double>(fluidParticles) / 10.0));
  scene::EnvironmentDesc env;
  env.width = env.depth = side + 1;
  env.height = 40;
  d.environment = env;
  scene::FluidDesc goo;
  goo.name = "goo";
  scene::FillDesc fill;
  fill.shape = scene::FillShape::Box;
  fill.min = Vec3(-side / 2, 0, -side / 2);
  fill.max = Vec3(side / 2, 10, side / 2);
  fill.spacing = 1;
  goo.fills.push_back(fill);
  d.fluids.push_back(goo);
  const auto perRow = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(bodies))));
  const double step = side / static_cast<double>(perRow);
  for (std::size_t b = 0; b < bodies; ++b) {
    const double x = -side / 2 + step * (static_cast<double>(b % perRow) + 0.5);
    const double z = -side / 2 + step * (static_cast<double>(b / perRow) + 0.5);
    scene::ObjectDesc o = b % 2 == 0 ? primitiveObject("box" + std::to_string(b), scene::ObjectShape::Box, {2, 2, 2}, 0.5, Vec3(x, 13, z))
                                     : primitiveObject("ball" + std::to_string(b), scene::ObjectShape::Sphere, {1.2}, 0.5, Vec3(x, 13, z));
    o.initialRotation = Vec3(10.0 * static_cast<double>(b % 7), 15.0 * static_cast<double>(b % 5), 0);
    o.mass = 8;
    d.objects.push_back(o);
  }
  return d;
}

}  // namespace softsub::scenarios
