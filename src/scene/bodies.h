#pragma once
/// `<Object>` → rigid bodies: geometry (loaded or primitive), mass properties, particles
/// and initial state. Used by compile() and, for the particle bound, by the reader.
#include <memory>
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

/// Every object's geometry, worked out before anything is placed: its mesh, its particles
/// and initial state, and for a closed mesh its volume fill at the initial pose, which
/// fills with OutsideObjects ask of (inside()) before the fluids are placed.
class ObjectShapes {
 public:
  /// Loads and fills every object of `desc` (throws InputError as objectMesh does).
  explicit ObjectShapes(const SceneDesc& desc);
  ~ObjectShapes();
  ObjectShapes(ObjectShapes&&) noexcept;
  ObjectShapes(const ObjectShapes&) = delete;
  ObjectShapes& operator=(const ObjectShapes&) = delete;
  ObjectShapes& operator=(ObjectShapes&&) = delete;

  /// Whether a particle of `radius` at p starts inside an object or overlapping it, at
  /// the object's initial pose: in one of the voxels of a closed object's volume fill
  /// (its particles' lattice, each voxel a particle wide), or closer to one of any
  /// object's particles than their two radii (open meshes included).
  [[nodiscard]] bool inside(const Vec3& p, double radius) const;

 private:
  struct Prepared;
  struct Particles;
  [[nodiscard]] const Particles& particles() const;  // built at the first call
  std::vector<Prepared> objects_;
  mutable std::unique_ptr<Particles> particles_;
  friend void addBodies(const SceneDesc&, ObjectShapes&&, solver::Model&, solver::State&,
                        std::vector<geometry::TriangleMesh>&, std::vector<std::string>*);
};

/// The extents of the primitive that stands in for an object's inertia (radius | radius
/// height | width height depth, scaled): its Size times UniformScale, or, without a
/// Size, fitted to `scaledBox`, the bounding box of its mesh after UniformScale. Empty
/// for Shape mesh.
[[nodiscard]] std::vector<double> inertiaPrimitiveSize(const ObjectDesc& o, const Aabb& scaledBox);

/// Appends every object of `desc` as a rigid body to the model (after the fluids:
/// materials, interaction rows with every fluid) and its particles and state to `state`,
/// from `shapes` (built from the same `desc`). `meshes` receives each object's
/// objectMesh, in scene order. `warnings` (if given) receives one sentence for each
/// fluid with particles that start inside a closed object's volume (a body keeps only
/// its two outer layers of particles, so nothing pushes fluid out of its hollow middle)
/// and for each pair of objects that start inside each other.
void addBodies(const SceneDesc& desc, ObjectShapes&& shapes, solver::Model& model, solver::State& state,
               std::vector<geometry::TriangleMesh>& meshes, std::vector<std::string>* warnings = nullptr);

}  // namespace softsub::scene
