#pragma once
/// `<Object>` → rigid bodies: geometry (loaded or primitive), mass properties, particles
/// and initial state. Used by compile() and, for the particle bound, by the reader.
#include <string>
#include <vector>

#include "geometry/triangle_mesh.h"
#include "scene/scene_desc.h"
#include "solver/model.h"

namespace softsub::scene {

/// The object's surface in its geometry's own coordinates, before UniformScale: the mesh
/// file (loaded from baseDir / Geometry), or the primitive of Shape and Size centred on
/// its centre of mass (a cone's base at y = -height/4). This is the mesh written beside
/// the frames, which the `.sim` transform places.
[[nodiscard]] geometry::TriangleMesh objectMesh(const ObjectDesc& object, const std::string& baseDir);

/// The particle diameter of an object: ParticleSize, or 1/20 of the largest extent of
/// its scaled mesh.
[[nodiscard]] double objectParticleSize(const ObjectDesc& object, const geometry::TriangleMesh& mesh);

/// The `<Pair>` of names a and b (either order), or null.
[[nodiscard]] const PairDesc* findPair(const InteractionsDesc& interactions, const std::string& a,
                                       const std::string& b);

/// Appends every object of `desc` as a rigid body to the model (after the fluids:
/// materials, interaction rows with every fluid) and its particles and state to `state`.
/// `meshes` receives each object's objectMesh, in scene order. `warnings` (if given)
/// receives one sentence for each fluid with particles that start inside a closed
/// object's volume: a body keeps only its two outer layers of particles, so nothing
/// pushes fluid out of its hollow middle.
void addBodies(const SceneDesc& desc, solver::Model& model, solver::State& state,
               std::vector<geometry::TriangleMesh>& meshes, std::vector<std::string>* warnings = nullptr);

}  // namespace softsub::scene
