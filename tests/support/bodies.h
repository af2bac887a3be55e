#pragma once
// Scenes with rigid bodies, built as descriptions and compiled like a scene file: shared
// by the rigid-body tests, the examples' checks and the benchmarks.
#include <memory>
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
