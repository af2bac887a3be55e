#pragma once
/// SceneDesc -> Model (read-only) + State (mutable).
#include <optional>
#include <string>
#include <vector>

#include "geometry/triangle_mesh.h"
#include "scene/scene_desc.h"
#include "solver/model.h"

namespace softsub::scene {

/// A compiled scene. Keep it alive while a Simulation refers to its model.
struct Compiled {
  solver::Model model;
  solver::State state;
  /// Each object's geometry in its own coordinates before UniformScale (scene order):
  /// what the `.sim` transforms place, written once beside the frames.
  std::vector<geometry::TriangleMesh> objectMeshes;
  /// What the initial particles have that a user most likely did not mean, one line
  /// each (`<element>: <text>`): a fluid's or an object's particles outside the
  /// container (the walls put a fluid's and a dynamic object's back inside, with a jolt;
  /// a static object stays where it is), and fluid particles at exactly the same place
  /// as another (a pair at distance 0 has no direction: they never push apart).
  std::vector<std::string> warnings;
  /// Per fluid: the points of its fills with OutsideObjects left out because they lie
  /// inside an object (`softsub info` shows them).
  std::vector<std::size_t> leftOutInsideObjects;
};

/// Builds the model (materials, interaction table, container, options) and the initial
/// state (every fluid's explicit particles then its fills, in scene order; stable ids in
/// that order; then every object's particles, see addBodies) from a validated description. Mesh fills load their mesh from
/// desc.baseDir / Geometry again (IoError or InputError if it changed since reading).
Compiled compile(const SceneDesc& desc);

/// The spacing at which a simple cubic lattice (what every fill makes) of particles
/// interacting through `f` is at rest, gravity aside: where the sum of r F(r) over a
/// particle's neighbours goes from pushing apart to pulling together as the spacing
/// grows; of several, the nearest to `near`. None where there is none between a quarter
/// of f's cutoff and the cutoff (a function that only pushes or only pulls).
std::optional<double> cubicRestSpacing(const forces::PairFunction& f, double near);

/// The solver's integrator for a scene's.
solver::Integrator toSolver(Integrator i);

}  // namespace softsub::scene
