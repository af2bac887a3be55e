#pragma once
/// SceneDesc -> Model (read-only) + State (mutable).
#include "scene/scene_desc.h"
#include "solver/model.h"

namespace softsub::scene {

/// A compiled scene. Keep it alive while a Simulation refers to its model.
struct Compiled {
  solver::Model model;
  solver::State state;
};

/// Builds the model (materials, interaction table, container, options) and the initial
/// state (every fluid's explicit particles then its fills, in scene order; stable ids in
/// that order) from a validated description. Mesh fills load their mesh from
/// desc.baseDir / Geometry again (IoError or InputError if it changed since reading).
Compiled compile(const SceneDesc& desc);

/// The solver's integrator for a scene's.
solver::Integrator toSolver(Integrator i);

}  // namespace softsub::scene
