#include "scene/schema.h"

#include <fmt/format.h>

#include <cmath>

#include "scene/reader.h"

namespace softsub::scene {

using forces::Curve;
using forces::LennardJones;
using forces::LennardJonesForce;
using forces::Linear;

bool Range::contains(double v) const {
  const bool aboveMin = minOpen ? v > min : v >= min;
  const bool belowMax = maxOpen ? v < max : v <= max;
  return aboveMin && belowMax;
}

bool Range::unbounded() const { return std::isinf(min) && std::isinf(max); }

std::string Range::describe() const {
  const bool hasMin = !std::isinf(min);
  const bool hasMax = !std::isinf(max);
  if (hasMin && hasMax) {
    return fmt::format("{}{}, {}{}", minOpen ? "(" : "[", min, max, maxOpen ? ")" : "]");
  }
  if (hasMin) return fmt::format("{} {}", minOpen ? ">" : ">=", min);
  if (hasMax) return fmt::format("{} {}", maxOpen ? "<" : "<=", max);
  return "any";
}

namespace {

// The tables use designated initializers that leave the optional FieldInfo members to
// their defaults; GCC before 14 warns about exactly that under -Wextra.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

// At least 0.001: the time step 1 / (FramesPerSecond * Substeps) is then at most 1000 s,
// finite in single precision (1e-300 once made it infinite and the run "blew up").
constexpr Range kFramesPerSecond{0.001, 1000, false, false};
constexpr Range kSubsteps{1, 10000, false, false};
constexpr Range kFrames{0, 1000000, false, false};

// The tables. Order is the order of the docs and of the writer's output.

constexpr Field<SimulationDesc> kSimulation[] = {
    field<&SimulationDesc::framesPerSecond>(
        {.tag = "FramesPerSecond", .kind = Kind::Real, .unit = "1/s", .range = kFramesPerSecond,
         .meaning = "output frames per second (24 fps = 250 Maya ticks per frame)"}),
    field<&SimulationDesc::substeps>({.tag = "Substeps", .kind = Kind::Int, .unit = "-",
                                      .range = kSubsteps,
                                      .meaning = "updates per frame (the seed's -updateNum)"}),
    field<&SimulationDesc::frames>({.tag = "Frames", .kind = Kind::Int, .unit = "-",
                                    .range = kFrames, .meaning = "frames to simulate"}),
    field<&SimulationDesc::gravity>({.tag = "Gravity", .kind = Kind::Vec3, .unit = "units/s^2",
                                     .meaning = "acceleration of gravity"}),
    field<&SimulationDesc::integrator>(
        {.tag = "Integrator", .kind = Kind::Enum, .unit = "-",
         .meaning = "time integration scheme (explicit-euler is the seed's)",
         .choices = kIntegratorNames}),
};

constexpr Field<CameraDesc> kCamera[] = {
    field<&CameraDesc::eye>({.tag = "Eye", .kind = Kind::Vec3, .unit = "units",
                             .meaning = "camera position (viewer and renderer only)"}),
    field<&CameraDesc::verticalAngle>({.tag = "VerticalAngle", .kind = Kind::Real,
                                       .unit = "degrees", .meaning = "pitch of the camera"}),
    field<&CameraDesc::horizontalAngle>({.tag = "HorizontalAngle", .kind = Kind::Real,
                                         .unit = "degrees", .meaning = "yaw of the camera"}),
};

constexpr Field<EnvironmentDesc> kEnvironment[] = {
    field<&EnvironmentDesc::width>({.tag = "Width", .kind = Kind::Real, .unit = "units",
                                    .range = kPositive,
                                    .meaning = "container extent along x: x in [-Width/2, Width/2]"}),
    field<&EnvironmentDesc::height>({.tag = "Height", .kind = Kind::Real, .unit = "units",
                                     .range = kPositive,
                                     .meaning = "container extent along y: floor at 0, top at Height"}),
    field<&EnvironmentDesc::depth>({.tag = "Depth", .kind = Kind::Real, .unit = "units",
                                    .range = kPositive,
                                    .meaning = "container extent along z: z in [-Depth/2, Depth/2]"}),
    field<&EnvironmentDesc::reflective>({.tag = "Reflective", .kind = Kind::Bool, .unit = "-",
                                         .meaning = "mirror floor (rendering only)"}),
    field<&EnvironmentDesc::normalAttenuation>(
        {.tag = "NormalAttenuation", .kind = Kind::Real, .unit = "-", .range = kUnitInterval,
         .meaning = "restitution e: normal velocity after a wall contact = -e times before"}),
    field<&EnvironmentDesc::tangentAttenuation>(
        {.tag = "TangentAttenuation", .kind = Kind::Real, .unit = "-", .range = kUnitInterval,
         .meaning = "friction: the seed's tangential attenuation at impacts, Coulomb friction in "
                    "resting contact; see docs"}),
    field<&EnvironmentDesc::closed>({.tag = "Closed", .kind = Kind::Bool, .unit = "-",
                                     .meaning = "extension: a lid at y = Height too (a jar)"}),
};

// NumberOfParticles is derived: written from the positions, and only checked on reading.
constexpr Field<FluidDesc> numberOfParticles() {
  Field<FluidDesc> f{{.tag = "NumberOfParticles", .kind = Kind::Int, .unit = "-",
                      .range = kNonNegative,
                      .meaning = "number of explicit positions (0 or absent with fills only)",
                      .rule = "equal to the number of positions in Particles"}};
  f.get = [](const FluidDesc& d) -> Value { return static_cast<std::int64_t>(d.particles.size()); };
  return f;
}

using fluid::FluidParams;
constexpr Field<FluidDesc> kFluid[] = {
    field<&FluidDesc::name>({.tag = "Name", .kind = Kind::String, .unit = "-",
                             .meaning = "the fluid's name; part of output file names",
                             .rule = "letters, digits, _ and -, at most 100 characters; unique",
                             .required = true}),
    field<&FluidDesc::params, &FluidParams::interactionDistance>(
        {.tag = "InteractionDistance", .kind = Kind::Real, .unit = "units", .range = kPositive,
         .meaning = "distance from which the fluid's own force is zero"}),
    field<&FluidDesc::params, &FluidParams::amplitude>(
        {.tag = "Amplitude", .kind = Kind::Real, .unit = "force", .range = kNonNegative,
         .meaning = "A in the fluid's own force 4A((s/r)^12 - (s/r)^6)"}),
    field<&FluidDesc::params, &FluidParams::finiteDistance>(
        {.tag = "FiniteDistance", .kind = Kind::Real, .unit = "units", .range = kPositive,
         .meaning = "s: distance where the fluid's own force is zero"}),
    field<&FluidDesc::params, &FluidParams::minimumForce>(
        {.tag = "MinimumForce", .kind = Kind::Real, .unit = "force",
         .meaning = "lower clamp of the own force (strongest attraction)",
         .rule = "<= MaximumForce"}),
    field<&FluidDesc::params, &FluidParams::maximumForce>(
        {.tag = "MaximumForce", .kind = Kind::Real, .unit = "force",
         .meaning = "upper clamp of the own force (strongest repulsion)",
         .rule = ">= MinimumForce"}),
    field<&FluidDesc::params, &FluidParams::viscosity>(
        {.tag = "Viscosity", .kind = Kind::Real, .unit = "mass/s", .range = kNonNegative,
         .meaning = "F = (v_neighbour - v_self) x Viscosity, over neighbours within "
                    "InteractionDistance"}),
    field<&FluidDesc::params, &FluidParams::particleSize>(
        {.tag = "ParticleSize", .kind = Kind::Real, .unit = "units", .range = kPositive,
         .meaning = "particle diameter (display, walls, surfaces)"}),
    field<&FluidDesc::params, &FluidParams::particleMass>(
        {.tag = "ParticleMass", .kind = Kind::Real, .unit = "mass", .range = Range{1e-30, 1e30},
         .meaning = "extension: mass of one particle (its inverse must fit in single precision)"}),
    field<&FluidDesc::initialSpeed>({.tag = "InitialSpeed", .kind = Kind::Vec3,
                                     .unit = "units/s",
                                     .meaning = "initial velocity of every particle"}),
    field<&FluidDesc::colour>({.tag = "Colour", .kind = Kind::Colour, .unit = "-",
                               .range = kUnitInterval,
                               .meaning = "display colour, red green blue"}),
    numberOfParticles(),
    field<&FluidDesc::particles>({.tag = "Particles", .kind = Kind::PointList, .unit = "units",
                                  .meaning = "explicit positions, x y z for each particle"}),
};

constexpr Field<FillDesc> kFillCommon[] = {
    field<&FillDesc::shape>({.tag = "Shape",
                             .kind = Kind::Enum,
                             .unit = "-",
                             .meaning = "what the lattice fills",
                             .rule = "mesh needs Geometry and Spacing",
                             .choices = kFillShapeNames,
                             .required = true}),
    field<&FillDesc::spacing>({.tag = "Spacing",
                               .kind = Kind::Real,
                               .unit = "units",
                               .range = kPositive,
                               .meaning = "distance between neighbouring lattice points"}),
    // Written only when true (defaultText), so scenes written before it come back unchanged.
    field<&FillDesc::outsideObjects>({.tag = "OutsideObjects",
                                      .kind = Kind::Bool,
                                      .unit = "-",
                                      .meaning = "extension: leave out the points inside or overlapping "
                                                 "an object at its initial pose (fluid filled around "
                                                 "objects)",
                                      .defaultText = "`false`"}),
};

constexpr Field<FillDesc> kFillBox[] = {
    field<&FillDesc::min>({.tag = "Min", .kind = Kind::Vec3, .unit = "units",
                           .meaning = "lower corner of the box",
                           .rule = "< Max on every axis"}),
    field<&FillDesc::max>({.tag = "Max", .kind = Kind::Vec3, .unit = "units",
                           .meaning = "upper corner of the box",
                           .rule = "> Min on every axis"}),
};

constexpr Field<FillDesc> kFillSphere[] = {
    field<&FillDesc::center>({.tag = "Center", .kind = Kind::Vec3, .unit = "units",
                              .meaning = "centre of the sphere (a lattice point)"}),
    field<&FillDesc::radius>({.tag = "Radius", .kind = Kind::Real, .unit = "units",
                              .range = kPositive, .meaning = "radius of the sphere"}),
};

constexpr Field<FillDesc> kFillMesh[] = {
    field<&FillDesc::geometry>({.tag = "Geometry", .kind = Kind::String, .unit = "-",
                                .meaning = "closed mesh file (OBJ, PLY, STL, glTF, FBX...), "
                                           "relative to the scene's folder",
                                .rule = "a relative path that stays inside the scene's folder "
                                        "tree (symbolic links resolved)",
                                .required = true}),
    field<&FillDesc::surface>({.tag = "Surface", .kind = Kind::Bool, .unit = "-",
                               .meaning = "extension: particles on the surface only (thin "
                                          "shells, open meshes) instead of the volume"}),
};

constexpr Field<Linear> kLinear[] = {
    field<&Linear::atZero>({.tag = "AtZero", .kind = Kind::Real, .unit = "force",
                            .meaning = "force at r = 0"}),
    field<&Linear::cutoff>({.tag = "Cutoff", .kind = Kind::Real, .unit = "units",
                            .range = kPositive,
                            .meaning = "distance where the line reaches 0; zero from there on"}),
    field<&Linear::min>({.tag = "Min", .kind = Kind::Real, .unit = "force",
                         .meaning = "lower clamp", .rule = "<= Max"}),
    field<&Linear::max>({.tag = "Max", .kind = Kind::Real, .unit = "force",
                         .meaning = "upper clamp", .rule = ">= Min"}),
};

constexpr Field<LennardJones> kLennardJones[] = {
    field<&LennardJones::amplitude>({.tag = "Amplitude", .kind = Kind::Real, .unit = "force",
                                     .range = kNonNegative,
                                     .meaning = "A in F(r) = 4A((s/r)^12 - (s/r)^6)"}),
    field<&LennardJones::finiteDistance>({.tag = "FiniteDistance", .kind = Kind::Real,
                                          .unit = "units", .range = kPositive,
                                          .meaning = "s: distance where F = 0"}),
    field<&LennardJones::min>({.tag = "Min", .kind = Kind::Real, .unit = "force",
                               .meaning = "lower clamp (strongest attraction)",
                               .rule = "<= Max"}),
    field<&LennardJones::max>({.tag = "Max", .kind = Kind::Real, .unit = "force",
                               .meaning = "upper clamp (strongest repulsion)",
                               .rule = ">= Min"}),
    field<&LennardJones::cutoff>({.tag = "Cutoff", .kind = Kind::Real, .unit = "units",
                                  .range = kPositive,
                                  .meaning = "distance from which F is zero"}),
};

constexpr Field<LennardJonesForce> kLennardJonesForce[] = {
    field<&LennardJonesForce::epsilon>(
        {.tag = "Epsilon", .kind = Kind::Real, .unit = "energy", .range = kNonNegative,
         .meaning = "well depth of U = 4 eps ((sigma/r)^12 - (sigma/r)^6)"}),
    field<&LennardJonesForce::sigma>({.tag = "Sigma", .kind = Kind::Real, .unit = "units",
                                      .range = kPositive, .meaning = "distance where U = 0"}),
    field<&LennardJonesForce::cutoff>({.tag = "Cutoff", .kind = Kind::Real, .unit = "units",
                                       .range = kPositive,
                                       .meaning = "distance from which the force -dU/dr is zero"}),
};

constexpr Field<Curve> kCurve[] = {
    field<&Curve::points>(
        {.tag = "Points", .kind = Kind::RealList, .unit = "units, force",
         .meaning = "r0 f0 r1 f1 ...: piecewise linear, f0 below r0, zero past the last r",
         .rule = "an even count, at least 4; r0 >= 0; r strictly increasing",
         .required = true}),
};

constexpr Field<InteractionDesc> kInteraction[] = {
    field<&InteractionDesc::damping>(
        {.tag = "Damping", .kind = Kind::Real, .unit = "mass/s", .range = kNonNegative,
         .meaning = "damping of the relative velocity, like a fluid's Viscosity"}),
    field<&InteractionDesc::relativeVelocity>(
        {.tag = "RelativeVelocity", .kind = Kind::Real, .unit = "mass/s",
         .range = kNonNegative,
         .meaning = "damping of the relative velocity along the line between the particles"}),
};

constexpr Field<PairDesc> kPair[] = {
    field<&PairDesc::a>({.tag = "A", .kind = Kind::String, .unit = "-",
                         .meaning = "first fluid or object of the pair",
                         .rule = "the Name of a fluid or an object of the scene; not two objects",
                         .required = true}),
    field<&PairDesc::b>({.tag = "B", .kind = Kind::String, .unit = "-",
                         .meaning = "second fluid or object; B = A, a fluid, replaces that "
                                    "fluid's own function",
                         .rule = "the Name of a fluid or an object of the scene; not two objects",
                         .required = true}),
};

constexpr Field<ObjectDesc> kObject[] = {
    field<&ObjectDesc::name>(
        {.tag = "Name",
         .kind = Kind::String,
         .unit = "-",
         .meaning = "the object's name, in .sim files and in Pair",
         .rule = "at most 100 bytes (UTF-8), no slash, backslash or control character, not . or ..; "
                 "unique among the objects and fluids",
         .defaultText = "`object<N>`, N its position among the objects (from 1)"}),
    field<&ObjectDesc::geometry>(
        {.tag = "Geometry",
         .kind = Kind::String,
         .unit = "-",
         .meaning = "mesh file (OBJ, PLY, STL, glTF, FBX...), relative to the scene's folder; "
                    "closed when Shape is mesh and IsDynamic is true",
         .rule = "a relative path that stays inside the scene's folder tree (symbolic links "
                 "resolved)",
         .defaultText = "none: a primitive (Shape and Size)"}),
    field<&ObjectDesc::shape>({.tag = "Shape",
                               .kind = Kind::Enum,
                               .unit = "-",
                               .meaning =
                                   "the primitive whose inertia approximates the body, or mesh: the exact "
                                   "inertia of the closed mesh",
                               .rule = "mesh needs Geometry; a primitive without Geometry needs Size",
                               .choices = kObjectShapeNames,
                               .defaultText = "mesh when Geometry is given (else required)"}),
    field<&ObjectDesc::size>(
        {.tag = "Size",
         .kind = Kind::RealList,
         .unit = "units",
         .range = kPositive,
         .meaning = "the primitive's extents: sphere radius; cone and cylinder radius height "
                    "(axis along y); box width height depth",
         .rule = "1, 2 or 3 numbers by Shape (sphere, cone/cylinder, box); not with Shape mesh",
         .defaultText = "none: fitted to Geometry"}),
    field<&ObjectDesc::particleSize>(
        {.tag = "ParticleSize",
         .kind = Kind::Real,
         .unit = "units",
         .range = kPositive,
         .meaning = "diameter of the particles that fill the body; also how hard fluid is pushed off it (the "
                    "FluidObject function acts per body particle: finer pushes harder)",
         .defaultText = "1/20 of the largest extent (after UniformScale)"}),
    field<&ObjectDesc::uniformScale>({.tag = "UniformScale",
                                      .kind = Kind::Real,
                                      .unit = "-",
                                      .range = kPositive,
                                      .meaning = "scales the geometry (and Size) about its origin"}),
    field<&ObjectDesc::initialPosition>({.tag = "InitialPosition",
                                         .kind = Kind::Vec3,
                                         .unit = "units",
                                         .meaning = "where the geometry's origin is placed"}),
    field<&ObjectDesc::initialRotation>({.tag = "InitialRotation",
                                         .kind = Kind::Vec3,
                                         .unit = "degrees",
                                         .meaning = "Euler angles, applied about X, then Y, then Z"}),
    field<&ObjectDesc::initialLinearVelocity>({.tag = "InitialLinearVelocity",
                                               .kind = Kind::Vec3,
                                               .unit = "units/s",
                                               .meaning = "velocity of the centre of mass"}),
    field<&ObjectDesc::initialAngularVelocity>({.tag = "InitialAngularVelocity",
                                                .kind = Kind::Vec3,
                                                .unit = "degrees/s",
                                                .meaning = "angular velocity about the world axes"}),
    field<&ObjectDesc::normalAttenuation>(
        {.tag = "NormalAttenuation",
         .kind = Kind::Real,
         .unit = "-",
         .range = kUnitInterval,
         .meaning = "restitution e at contacts with walls and objects (each side's mean)"}),
    field<&ObjectDesc::tangentAttenuation>(
        {.tag = "TangentAttenuation",
         .kind = Kind::Real,
         .unit = "-",
         .range = kUnitInterval,
         .meaning = "friction at contacts with walls and objects (each side's mean)"}),
    field<&ObjectDesc::mass>({.tag = "Mass",
                              .kind = Kind::Real,
                              .unit = "mass",
                              .range = Range{1e-30, 1e30},
                              .meaning = "mass of the whole body (its inertia's inverse must stay finite)"}),
    field<&ObjectDesc::isDynamic>(
        {.tag = "IsDynamic",
         .kind = Kind::Bool,
         .unit = "-",
         .meaning =
             "false: a static body that never moves (an open mesh is fine then; its initial velocities "
             "are not used, with a warning)"}),
};

constexpr std::string_view kOneFunction = "exactly one function per parent";
static_assert(kMaxFluids == 1024, "the count of <Fluid> in kElements names the cap");

constexpr ElementInfo kElements[] = {
    {"Scene", "", false, "the root, exactly one", "the whole scene; attribute version=\"1\""},
    {"Simulation", "Scene", false, "optional", "timing, gravity and integrator"},
    {"Camera", "Scene", false, "optional", "start pose of the viewer and renderer"},
    {"Environment", "Scene", false, "optional", "the container; absent: no walls at all"},
    {"Fluid", "Scene", true, "up to 1024", "one substance and its particles"},
    {"Object", "Scene", true, "any number", "a rigid body made of particles"},
    {"Interactions", "Scene", false, "optional", "the dictionary of interactions"},
    {"Fill", "Fluid", true, "any number", "a lattice of particles filling a shape"},
    {"FluidFluid", "Interactions", false, "optional",
     "the function between particles of two different fluids"},
    {"FluidObject", "Interactions", false, "optional",
     "the function between a fluid's particles and an object's"},
    {"Pair", "Interactions", true, "any number",
     "an override for A and B, each a fluid or an object"},
    {"Linear", "FluidFluid", false, kOneFunction, "a clamped straight line"},
    {"LennardJones", "FluidFluid", false, kOneFunction, "the seed's clamped 12-6 shape"},
    {"LennardJonesForce", "FluidFluid", false, kOneFunction, "the true 12-6 force -dU/dr"},
    {"Curve", "FluidFluid", false, kOneFunction, "a piecewise linear function"},
    {"Linear", "FluidObject", false, kOneFunction, "a clamped straight line"},
    {"LennardJones", "FluidObject", false, kOneFunction, "the seed's clamped 12-6 shape"},
    {"LennardJonesForce", "FluidObject", false, kOneFunction, "the true 12-6 force -dU/dr"},
    {"Curve", "FluidObject", false, kOneFunction, "a piecewise linear function"},
    {"Linear", "Pair", false, kOneFunction, "a clamped straight line"},
    {"LennardJones", "Pair", false, kOneFunction, "the seed's clamped 12-6 shape"},
    {"LennardJonesForce", "Pair", false, kOneFunction, "the true 12-6 force -dU/dr"},
    {"Curve", "Pair", false, kOneFunction, "a piecewise linear function"},
};

#pragma GCC diagnostic pop

std::string joinChoices(std::span<const std::string_view> choices) {
  std::string s;
  for (const auto c : choices) s += (s.empty() ? "" : ", ") + std::string(c);
  return s;
}

std::string vec3Text(const Vec3& v) { return fmt::format("{} {} {}", v.x(), v.y(), v.z()); }

}  // namespace

template <>
std::span<const Field<SimulationDesc>> fieldsOf<SimulationDesc>() { return kSimulation; }
template <>
std::span<const Field<CameraDesc>> fieldsOf<CameraDesc>() { return kCamera; }
template <>
std::span<const Field<EnvironmentDesc>> fieldsOf<EnvironmentDesc>() { return kEnvironment; }
template <>
std::span<const Field<FluidDesc>> fieldsOf<FluidDesc>() { return kFluid; }
template <>
std::span<const Field<FillDesc>> fieldsOf<FillDesc>() { return kFillCommon; }
template <>
std::span<const Field<Linear>> fieldsOf<Linear>() { return kLinear; }
template <>
std::span<const Field<LennardJones>> fieldsOf<LennardJones>() { return kLennardJones; }
template <>
std::span<const Field<LennardJonesForce>> fieldsOf<LennardJonesForce>() {
  return kLennardJonesForce;
}
template <>
std::span<const Field<Curve>> fieldsOf<Curve>() { return kCurve; }
template <>
std::span<const Field<InteractionDesc>> fieldsOf<InteractionDesc>() { return kInteraction; }
template <>
std::span<const Field<PairDesc>> fieldsOf<PairDesc>() { return kPair; }
template <>
std::span<const Field<ObjectDesc>> fieldsOf<ObjectDesc>() { return kObject; }

std::size_t objectSizeCount(ObjectShape shape) {
  switch (shape) {
    case ObjectShape::Mesh: return 0;
    case ObjectShape::Sphere: return 1;
    case ObjectShape::Cone:
    case ObjectShape::Cylinder: return 2;
    case ObjectShape::Box: return 3;
  }
  return 0;
}

std::string_view objectSizeWords(ObjectShape shape) {
  switch (shape) {
    case ObjectShape::Mesh: return "";
    case ObjectShape::Sphere: return "radius";
    case ObjectShape::Cone:
    case ObjectShape::Cylinder: return "radius height";
    case ObjectShape::Box: return "width height depth";
  }
  return "";
}

std::span<const Field<FillDesc>> fillShapeFields(FillShape shape) {
  switch (shape) {
    case FillShape::Box: return kFillBox;
    case FillShape::Sphere: return kFillSphere;
    case FillShape::Mesh: return kFillMesh;
  }
  return {};
}

std::span<const ElementInfo> elements() { return kElements; }

const ElementInfo* findElement(std::string_view parent, std::string_view name) {
  for (const auto& e : kElements) {
    if (e.parent == parent && e.name == name) return &e;
  }
  return nullptr;
}

std::string_view kindName(Kind kind) {
  switch (kind) {
    case Kind::Real: return "real";
    case Kind::Int: return "int";
    case Kind::Bool: return "bool";
    case Kind::Vec3: return "vec3";
    case Kind::Colour: return "colour";
    case Kind::String: return "string";
    case Kind::Enum: return "enum";
    case Kind::RealList: return "real list";
    case Kind::PointList: return "vec3 list";
  }
  return "?";
}

std::string allowedText(const FieldInfo& info) {
  std::string s;
  switch (info.kind) {
    case Kind::Real:
      s = info.range.unbounded() ? "any finite number" : info.range.describe();
      break;
    case Kind::Int:
      s = info.range.unbounded() ? "any integer" : "integer " + info.range.describe();
      break;
    case Kind::Vec3: s = "3 finite numbers"; break;
    case Kind::Colour: s = "3 numbers in " + info.range.describe(); break;
    case Kind::Bool: s = "true, false, 1, 0"; break;
    case Kind::Enum: s = joinChoices(info.choices); break;
    case Kind::String: s = info.rule.empty() ? "any text" : std::string(info.rule); break;
    case Kind::RealList:
      s = info.range.unbounded() ? "finite numbers" : "numbers " + info.range.describe();
      break;
    case Kind::PointList: s = "3 finite numbers per point"; break;
  }
  if (!info.rule.empty() && info.kind != Kind::String) s += "; " + std::string(info.rule);
  return s;
}

std::string formatValue(const FieldInfo& info, const Value& value) {
  switch (info.kind) {
    case Kind::Real: return fmt::format("{}", std::get<double>(value));
    case Kind::Int: return fmt::format("{}", std::get<std::int64_t>(value));
    case Kind::Bool: return std::get<bool>(value) ? "true" : "false";
    case Kind::Vec3:
    case Kind::Colour: return vec3Text(std::get<Vec3>(value));
    case Kind::String: return std::get<std::string>(value);
    case Kind::Enum: {
      const auto i = static_cast<std::size_t>(std::get<std::int64_t>(value));
      return i < info.choices.size() ? std::string(info.choices[i]) : std::string("?");
    }
    case Kind::RealList: return fmt::format("{}", fmt::join(std::get<std::vector<double>>(value), " "));
    case Kind::PointList: {
      std::string s;
      for (const Vec3& p : std::get<std::vector<Vec3>>(value)) {
        s += (s.empty() ? "" : "\n") + vec3Text(p);
      }
      return s;
    }
  }
  return {};
}

namespace {

// One table; defaults is the struct the defaults are read from (a default-constructed S,
// or where an element starts from other values, such as <FluidObject>).
template <class S>
void appendTable(std::string& out, std::string_view title, std::span<const Field<S>> fields,
                 const S& defaults = S{}) {
  out += fmt::format("### {}\n\n", title);
  out += "| Tag | Type | Unit | Default | Allowed | Meaning |\n";
  out += "|---|---|---|---|---|---|\n";
  for (const Field<S>& f : fields) {
    std::string def = "required";
    if (!f.defaultText.empty()) {
      def = f.defaultText;
    } else if (!f.required) {
      def = formatValue(f, f.get(defaults));
      def = def.empty() ? "none" : "`" + def + "`";
    }
    out += fmt::format("| `{}` | {} | {} | {} | {} | {} |\n", f.tag, kindName(f.kind), f.unit,
                       def, allowedText(f), f.meaning);
  }
  out += "\n";
}

}  // namespace

std::string schemaMarkdown() {
  std::string out = "### Elements\n\n| Element | Parent | Count | Meaning |\n|---|---|---|---|\n";
  for (const auto& e : kElements) {
    out += fmt::format("| `{}` | {} | {} | {} |\n", e.name,
                       e.parent.empty() ? std::string("-") : fmt::format("`{}`", e.parent),
                       e.count, e.meaning);
  }
  out += "\n";
  appendTable<SimulationDesc>(out, "`<Simulation>`", kSimulation);
  appendTable<CameraDesc>(out, "`<Camera>`", kCamera);
  appendTable<EnvironmentDesc>(out, "`<Environment>`", kEnvironment);
  appendTable<FluidDesc>(out, "`<Fluid>`", kFluid);
  appendTable<FillDesc>(out, "`<Fill>`, every shape", kFillCommon);
  appendTable<FillDesc>(out, "`<Fill>` with Shape `box`", kFillBox);
  appendTable<FillDesc>(out, "`<Fill>` with Shape `sphere`", kFillSphere);
  appendTable<FillDesc>(out, "`<Fill>` with Shape `mesh`", kFillMesh);
  appendTable<ObjectDesc>(out, "`<Object>`", kObject);
  appendTable<Linear>(out, "`<Linear>`", kLinear);
  appendTable<LennardJones>(out, "`<LennardJones>`", kLennardJones);
  appendTable<LennardJonesForce>(out, "`<LennardJonesForce>`", kLennardJonesForce);
  appendTable<Curve>(out, "`<Curve>`", kCurve);
  appendTable<InteractionDesc>(out, "`<FluidFluid>` and `<Pair>`: velocity terms", kInteraction);
  appendTable<InteractionDesc>(out, "`<FluidObject>`: velocity terms", kInteraction,
                               InteractionsDesc{}.fluidObject);
  appendTable<PairDesc>(out, "`<Pair>`: the two fluids or objects", kPair);
  return out;
}

}  // namespace softsub::scene
