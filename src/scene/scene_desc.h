#pragma once
/// SceneDesc: what a .scene file says, as plain data with no behaviour. The reader
/// fills it (validated), the writer prints it, compile() turns it into Model + State.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/math.h"
#include "fluid/fluid_params.h"
#include "forces/function.h"

namespace softsub::scene {

/// Time integration scheme.
enum class Integrator : std::uint8_t { ExplicitEuler, SymplecticEuler, VelocityVerlet };

/// `<Simulation>`: timing and global forces.
struct SimulationDesc {
  double framesPerSecond = 24;            ///< output frames per second
  int substeps = 8;                       ///< updates per frame (seed -updateNum)
  int frames = 120;                       ///< frames to simulate
  Vec3 gravity{0, -9.81, 0};              ///< acceleration, units/s^2
  Integrator integrator = Integrator::SymplecticEuler;
  bool operator==(const SimulationDesc&) const = default;
};

/// `<Camera>`: viewer/renderer start pose; no effect on the simulation.
struct CameraDesc {
  Vec3 eye{0, 10, 40};         ///< camera position
  double verticalAngle = 0;    ///< pitch, degrees
  double horizontalAngle = 0;  ///< yaw, degrees
  bool operator==(const CameraDesc&) const = default;
};

/// `<Environment>`: the container box x in [-W/2,W/2], y in [0,H], z in [-D/2,D/2].
struct EnvironmentDesc {
  double width = 20;               ///< x extent
  double height = 20;              ///< y extent
  double depth = 20;               ///< z extent
  bool reflective = false;         ///< mirror floor (rendering only)
  double normalAttenuation = 0.5;  ///< restitution e in [0,1]
  double tangentAttenuation = 0.1; ///< friction in [0,1]
  bool closed = false;             ///< extension: a lid at y = H (a jar)
  bool operator==(const EnvironmentDesc&) const = default;
};

/// Shape of a `<Fill>` particle source.
enum class FillShape : std::uint8_t { Box, Sphere, Mesh };

/// `<Fill>`: a lattice of particles filling a shape.
struct FillDesc {
  FillShape shape = FillShape::Box;
  Vec3 min{0, 0, 0};     ///< box: lower corner
  Vec3 max{1, 1, 1};     ///< box: upper corner
  Vec3 center{0, 0, 0};  ///< sphere: centre
  double radius = 1;     ///< sphere: radius
  std::string geometry;  ///< mesh: file as written, relative to SceneDesc::baseDir
  bool surface = false;  ///< mesh: sample the surface only (thin shells, open meshes)
  double spacing = 1;    ///< lattice step, > 0
  /// Extension: leave out the points that lie inside a closed object at its initial pose
  /// (scene::ObjectShapes::inside), so that fluid can be filled around objects.
  bool outsideObjects = false;
  int line = 0;  ///< source line (for messages); not compared
  bool operator==(const FillDesc& o) const {
    return shape == o.shape && min == o.min && max == o.max && center == o.center && radius == o.radius &&
           geometry == o.geometry && surface == o.surface && spacing == o.spacing &&
           outsideObjects == o.outsideObjects;
  }
};

/// `<Fluid>`: one substance.
struct FluidDesc {
  std::string name;                  ///< unique, required
  fluid::FluidParams params;         ///< the seed's per-fluid parameters
  Vec3 initialSpeed{0, 0, 0};        ///< initial velocity of every particle
  Vec3 colour{0.8, 0.5, 0.2};        ///< display colour in [0,1]
  std::vector<Vec3> particles;       ///< explicit positions (NumberOfParticles of them)
  std::vector<FillDesc> fills;       ///< lattice sources
  int line = 0;                      ///< source line; not compared
  bool operator==(const FluidDesc& o) const {
    return name == o.name && params == o.params && initialSpeed == o.initialSpeed &&
           colour == o.colour && particles == o.particles && fills == o.fills;
  }
};

/// `<Object>` Shape: the primitive whose inertia tensor approximates the body, or the
/// exact inertia of the closed mesh.
enum class ObjectShape : std::uint8_t { Mesh, Sphere, Cone, Box, Cylinder };

/// `<Object>`: one rigid body made of particles.
struct ObjectDesc {
  std::string name;              ///< unique among objects and fluids; reader default "object<N>", N from 1
  std::string geometry;          ///< mesh file as written, relative to SceneDesc::baseDir; empty: primitive
  ObjectShape shape = ObjectShape::Mesh;  ///< the reader sets Mesh when Geometry is given and Shape is not
  std::vector<double> size;      ///< primitive extents: radius | radius height | width height depth; empty: from the mesh
  double particleSize = 0;       ///< particle diameter; 0: 1/20 of the largest extent (after scaling)
  double uniformScale = 1;       ///< scales the geometry (and Size) about its origin
  Vec3 initialPosition{0, 0, 0};         ///< where the geometry's origin is placed
  Vec3 initialRotation{0, 0, 0};         ///< Euler degrees, applied X then Y then Z
  Vec3 initialLinearVelocity{0, 0, 0};   ///< of the centre of mass, units/s
  Vec3 initialAngularVelocity{0, 0, 0};  ///< world axes, degrees/s
  double normalAttenuation = 0.5;        ///< restitution e in [0,1]
  double tangentAttenuation = 0.1;       ///< friction in [0,1]
  double mass = 1;                       ///< > 0
  bool isDynamic = true;                 ///< false: static, never moves
  int line = 0;                          ///< source line; not compared
  bool operator==(const ObjectDesc& o) const {
    return name == o.name && geometry == o.geometry && shape == o.shape && size == o.size &&
           particleSize == o.particleSize && uniformScale == o.uniformScale &&
           initialPosition == o.initialPosition && initialRotation == o.initialRotation &&
           initialLinearVelocity == o.initialLinearVelocity &&
           initialAngularVelocity == o.initialAngularVelocity &&
           normalAttenuation == o.normalAttenuation && tangentAttenuation == o.tangentAttenuation &&
           mass == o.mass && isDynamic == o.isDynamic;
  }
};

/// A function plus its velocity terms: one entry of the dictionary of interactions.
struct InteractionDesc {
  forces::PairFunction function = forces::Linear{};
  double damping = 0;           ///< viscosity-like damping of relative velocity, mass/s
  double relativeVelocity = 0;  ///< damping of the normal relative velocity, mass/s
  bool operator==(const InteractionDesc&) const = default;
};

/// `<Pair>`: an override for A and B, each a fluid or an object name (A == B, a fluid,
/// replaces that fluid's own function; a fluid and an object replace FluidObject for them;
/// two objects are refused: objects collide by impulses, not functions).
struct PairDesc {
  std::string a, b;
  InteractionDesc interaction;
  int line = 0;  ///< source line; not compared
  bool operator==(const PairDesc& o) const {
    return a == o.a && b == o.b && interaction == o.interaction;
  }
};

/// `<Interactions>`: the global functions and pair overrides.
struct InteractionsDesc {
  /// Different fluids, unless a Pair overrides: seed default linear, [0,5], cutoff 1.
  InteractionDesc fluidFluid{forces::Linear{5, 1, 0, 5}, 0, 0};
  /// A fluid and an object, unless a Pair overrides: seed default linear, [0,5], cutoff
  /// 1.5, plus our relative-velocity term (the seed's "main missing improvement").
  InteractionDesc fluidObject{forces::Linear{5, 1.5, 0, 5}, 0, 2};
  std::vector<PairDesc> pairs;
  bool operator==(const InteractionsDesc&) const = default;
};

/// A whole scene.
struct SceneDesc {
  SimulationDesc simulation;
  CameraDesc camera;
  std::optional<EnvironmentDesc> environment;  ///< absent: no walls at all
  std::vector<FluidDesc> fluids;
  std::vector<ObjectDesc> objects;
  InteractionsDesc interactions;
  /// The folder relative paths (mesh fills' Geometry) resolve against: the scene file's
  /// folder, absolute. Where the scene came from, not what it says: not compared.
  std::string baseDir;
  /// The scene file as messages name it (the reader's file name); not compared.
  std::string file;
  bool operator==(const SceneDesc& o) const {
    return simulation == o.simulation && camera == o.camera && environment == o.environment &&
           fluids == o.fluids && objects == o.objects && interactions == o.interactions;
  }
};

}  // namespace softsub::scene
