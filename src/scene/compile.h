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

/// The push of a simple cubic lattice (what every fill makes) of spacing `a` whose
/// particles interact through `f`: the sum of r F(r) over a particle's neighbours within
/// f's cutoff. Positive: the lattice pushes itself apart; negative: it pulls together.
double cubicVirial(const forces::PairFunction& f, double a);
/// The spacings from `from` up to f's cutoff where such a lattice is at rest, gravity
/// aside, ascending: where cubicVirial goes from pushing apart to not (pulling, or no
/// force at all: a function without attraction swells to where it stops pushing).
std::vector<double> cubicRests(const forces::PairFunction& f, double from);
/// The rest a lattice of spacing `near` settles at, of `rests` (cubicRests): the first
/// above when it pushes itself apart, the last below when it pulls together; none when
/// it does neither or has no rest that way.
std::optional<double> cubicRestFrom(const std::vector<double>& rests, const forces::PairFunction& f,
                                    double near);
/// cubicRestFrom for a lattice of spacing `near`, the rests searched from a quarter of
/// the cutoff or of `near` if less (not below a 64th of the cutoff); none when `near` is
/// at or beyond the cutoff (its particles out of each other's reach).
std::optional<double> cubicRestSpacing(const forces::PairFunction& f, double near);

/// The solver's integrator for a scene's.
solver::Integrator toSolver(Integrator i);

}  // namespace softsub::scene
