#include "scene/bodies.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>
#include <optional>
#include <unordered_map>
#include <unordered_set>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <Eigen/Eigenvalues>

#include "core/error.h"
#include "geometry/fill.h"
#include "geometry/mass_properties.h"
#include "geometry/mesh_loader.h"
#include "geometry/primitives.h"
#include "rigid/body.h"
#include "scene/schema.h"

namespace softsub::scene {

namespace {

constexpr int kSegments = 32;  // primitive meshes: fine enough to fill and to look round
// Triangles near a body particle within this angle of one another are one flat face
// (geometry::surfaceFaces): a box's face is one; a primitive sphere's or cylinder's
// segments (11.25 degrees apart) are many, meeting at less than 30 degrees: a curve.
constexpr double kFlatDegrees = 5;

// Primitive extents (unscaled): Size, or fitted to the mesh's bounding box.
std::vector<double> primitiveSize(const ObjectDesc& o, const Aabb& box) {
  if (!o.size.empty()) return o.size;
  const double ex = box.hi[0] - box.lo[0], ey = box.hi[1] - box.lo[1], ez = box.hi[2] - box.lo[2];
  switch (o.shape) {
    case ObjectShape::Sphere: return {0.5 * std::max({ex, ey, ez})};
    case ObjectShape::Cone:
    case ObjectShape::Cylinder: return {0.5 * std::max(ex, ez), ey};
    case ObjectShape::Box: return {ex, ey, ez};
    case ObjectShape::Mesh: break;
  }
  return {};
}

}  // namespace

std::vector<double> inertiaPrimitiveSize(const ObjectDesc& o, const Aabb& scaledBox) {
  std::vector<double> size = primitiveSize(o, scaledBox);
  if (!o.size.empty())
    for (double& v : size) v *= o.uniformScale;
  return size;
}

namespace {

struct Mass {
  Vec3 center{0, 0, 0};  // centre of mass in scaled geometry coordinates
  Mat3 inertia = Mat3::Identity();
};

Mass massOf(const ObjectDesc& o, const geometry::TriangleMesh& scaled) {
  Mass m;
  const Aabb box = scaled.bounds();
  const Vec3 mid(0.5 * (box.lo[0] + box.hi[0]), 0.5 * (box.lo[1] + box.hi[1]), 0.5 * (box.lo[2] + box.hi[2]));
  if (o.shape == ObjectShape::Mesh) {
    if (!o.isDynamic) {  // a static body needs no inertia; its mesh may be open
      m.center = mid;
      return m;
    }
    const geometry::MassProperties p = geometry::meshMassProperties(scaled, o.mass, o.geometry);
    m.center = p.centerOfMass;
    m.inertia = p.inertia;
    return m;
  }
  // A primitive stands in for the inertia: its Size scaled, or fitted to the scaled box.
  const std::vector<double> size = inertiaPrimitiveSize(o, box);
  const bool fromMesh = !o.geometry.empty();
  m.center = fromMesh ? mid : Vec3::Zero();
  switch (o.shape) {
    case ObjectShape::Sphere: m.inertia = geometry::sphereInertia(o.mass, size[0]); break;
    case ObjectShape::Box: m.inertia = geometry::cuboidInertia(o.mass, size[0], size[1], size[2]); break;
    case ObjectShape::Cylinder: m.inertia = geometry::cylinderInertia(o.mass, size[0], size[1]); break;
    case ObjectShape::Cone:
      m.inertia = geometry::coneInertia(o.mass, size[0], size[1]);
      if (fromMesh) m.center.y() = box.lo[1] + 0.25 * size[1];  // a quarter up from the base
      break;
    case ObjectShape::Mesh: break;
  }
  return m;
}

// A body thin along an axis (a rod, a disc) has a principal moment of inertia near 0,
// whose inverse overflowed the solver's floats: a 4 x 1e-30 cylinder stopped its run at
// the first contact with "angular momentum is not finite", a remedy about substeps that
// could not help. Each principal moment is kept at least 1e-6 of the largest, as
// rigid-body engines bound theirs; no real body is changed (a rod 100 times longer than
// it is wide has 6e-4), and an inertia within the bound is returned exactly as given.
Mat3 boundedInertia(const Mat3& inertia) {
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(inertia);
  Vec3 moments = eig.eigenvalues();
  const double least = 1e-6 * moments.maxCoeff();
  if (!(moments.minCoeff() < least)) return inertia;
  for (int k = 0; k < 3; ++k) moments[k] = std::max(moments[k], least);
  return eig.eigenvectors() * moments.asDiagonal() * eig.eigenvectors().transpose();
}

geometry::TriangleMesh scaledMesh(const geometry::TriangleMesh& mesh, double s) {
  geometry::TriangleMesh out = mesh;
  for (Vec3& v : out.vertices) v *= s;
  return out;
}

bool isClosed(const geometry::TriangleMesh& mesh) {
  try {
    static_cast<void>(geometry::meshMassProperties(mesh, 1.0));
    return true;
  } catch (const InputError&) {
    return false;
  }
}

// The body's particles, in scaled geometry coordinates: the outer two layers of a volume
// fill of a closed mesh, with surface samples where it is thinner than about one particle
// (a lid 0.2 thick at the default particle size 0.5 would otherwise hold no particle at
// all, and fluids would fall through it), or a surface fill of an open mesh; at least one
// particle.
// `solid` (a closed mesh): the whole volume fill, before its shell is taken.
std::vector<Vec3> bodyParticles(const geometry::TriangleMesh& scaled, bool closed, double spacing,
                                const Vec3& center, std::vector<Vec3>& solid) {
  geometry::MeshFillResult r =
      geometry::fillMesh(scaled, {.spacing = spacing,
                                  .surfaceOnly = !closed,
                                  .thinParts = closed,
                                  .maxParticles = geometry::meshFillBound(scaled, spacing)});
  std::vector<Vec3> points = closed ? geometry::latticeShell(r.points, spacing, 2) : r.points;
  if (closed) solid = std::move(r.points);
  if (points.empty()) points.push_back(center);  // smaller than one particle
  // The lattice starts at the mesh's low corner: where a size is not a whole number of
  // particles, the particles reach the low faces and stop up to a particle short of the
  // high ones (a 2-unit box at particle size 0.6 rested on three of its faces exactly
  // and 0.2 deep in the floor on the other three). Centre them in the mesh's box, unless
  // the body has thin parts: their surface samples lie up to half a particle outside the
  // mesh, and the lattice points alone may end short of the box by a thin part's
  // thickness, so either box would shift a table (a thick leg under a top thinner than a
  // particle) off the floor or into it; such a body keeps its lattice where the fill put
  // it, its leg's particles flush with the leg's foot.
  if (closed && r.thinVoxels == 0) {
    Vec3 lo = points.front(), hi = points.front();
    for (const Vec3& p : points) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    const Aabb box = scaled.bounds();
    const Vec3 shift = 0.5 * (Vec3(box.lo[0] + box.hi[0], box.lo[1] + box.hi[1], box.lo[2] + box.hi[2]) - (lo + hi));
    for (Vec3& p : points) p += shift;
    for (Vec3& p : solid) p += shift;  // the volume fill stays the particles' lattice
  }
  return points;
}

}  // namespace

const PairDesc* findPair(const InteractionsDesc& in, const std::string& a, const std::string& b) {
  for (const PairDesc& p : in.pairs)
    if ((p.a == a && p.b == b) || (p.a == b && p.b == a)) return &p;
  return nullptr;
}

geometry::TriangleMesh objectMesh(const ObjectDesc& o, const std::string& baseDir) {
  if (!o.geometry.empty())
    return geometry::loadMesh(std::filesystem::path(baseDir) / o.geometry, nullptr,
                              baseDir.empty() ? std::filesystem::path(".") : std::filesystem::path(baseDir));
  const std::vector<double>& s = o.size;
  switch (o.shape) {
    case ObjectShape::Sphere: return geometry::sphereMesh(Vec3::Zero(), s.at(0), kSegments / 2, kSegments);
    case ObjectShape::Box: {
      const Vec3 h(0.5 * s.at(0), 0.5 * s.at(1), 0.5 * s.at(2));
      return geometry::boxMesh(-h, h);
    }
    case ObjectShape::Cylinder: return geometry::frustumMesh(s.at(0), -0.5 * s.at(1), s.at(0), 0.5 * s.at(1), kSegments);
    case ObjectShape::Cone: return geometry::frustumMesh(s.at(0), -0.25 * s.at(1), 0, 0.75 * s.at(1), kSegments);
    case ObjectShape::Mesh: break;
  }
  throw InputError({"", o.line, "Object"}, "a mesh object needs a Geometry file",
                   "Geometry, or a primitive Shape with Size");
}

namespace {

// A hash key of integer cell coordinates, 21 bits each: unique over [0, 2^21) a side (a
// body's voxels); cells farther apart may share one (the object particles' cells, whose
// map holds the positions, compared one by one).
std::uint64_t cellKey(std::int64_t x, std::int64_t y, std::int64_t z) {
  const auto part = [](std::int64_t v) { return static_cast<std::uint64_t>(v) & 0x1fffff; };
  return part(x) << 42 | part(y) << 21 | part(z);
}

// A closed body's volume fill (voxel centres lo + (k + 0.5) spacing, in the scaled
// mesh's axes) placed at `position` turned by `rotation` (a mesh point x lies at
// position + rotation x): which points of the world lie in it.
class PlacedSolid {
 public:
  // Voxels centred on the fill's points: `lo` is their lowest corner (the points' least
  // coordinates less half a voxel), so a body whose lattice was centred in its mesh's box
  // (bodyParticles) is tested where its particles are (tested from the mesh's corner, a
  // box 2.7 wide at particle size 0.5 left points 0.2 deep on its high side).
  PlacedSolid(const std::vector<Vec3>& solid, double spacing, const Vec3& position, const Quat& rotation)
      : lo_(lowest(solid, spacing)),
        hi_(lo_),
        spacing_(spacing),
        position_(position),
        back_(rotation.conjugate()) {
    const Vec3 lo = lo_;
    voxels_.reserve(solid.size());
    for (const Vec3& p : solid) {
      const Vec3 k = ((p - lo) / spacing).array() - 0.5;
      voxels_.insert(cellKey(std::llround(k.x()), std::llround(k.y()), std::llround(k.z())));
      hi_ = hi_.cwiseMax(p);
    }
    hi_.array() += 0.5 * spacing;
    centre_ = position + rotation * (0.5 * (lo_ + hi_));
    reach2_ = 0.25 * (hi_ - lo_).squaredNorm();
  }
  [[nodiscard]] bool empty() const { return voxels_.empty(); }
  /// 0: p is outside the fill; 1: in one of its voxels; 2: in a voxel whose six
  /// neighbours are in the fill too (at least about half a voxel inside the surface).
  [[nodiscard]] int depth(const Vec3& p) const {
    // Most points lie beyond the box's bounding sphere: tested first, without a turn.
    if (voxels_.empty() || (p - centre_).squaredNorm() > reach2_) return 0;
    const Vec3 x = back_ * (p - position_);
    if ((x.array() < lo_.array()).any() || (x.array() >= hi_.array()).any()) return 0;
    const Vec3 k = (x - lo_) / spacing_;
    const auto i = static_cast<std::int64_t>(k.x()), j = static_cast<std::int64_t>(k.y()),
               l = static_cast<std::int64_t>(k.z());
    if (!in(i, j, l)) return 0;
    return in(i - 1, j, l) && in(i + 1, j, l) && in(i, j - 1, l) && in(i, j + 1, l) && in(i, j, l - 1) &&
                   in(i, j, l + 1)
               ? 2
               : 1;
  }

 private:
  static Vec3 lowest(const std::vector<Vec3>& points, double spacing) {
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
    for (const Vec3& p : points) lo = lo.cwiseMin(p);
    return lo.array() - 0.5 * spacing;
  }
  [[nodiscard]] bool in(std::int64_t x, std::int64_t y, std::int64_t z) const {
    return x >= 0 && y >= 0 && z >= 0 && voxels_.count(cellKey(x, y, z)) != 0;
  }
  std::unordered_set<std::uint64_t> voxels_;
  Vec3 lo_, hi_;
  double spacing_;
  Vec3 position_;
  Quat back_;
  Vec3 centre_{0, 0, 0};
  double reach2_ = 0;
};

// Warnings for objects that start inside each other: the particles of one in an inner
// voxel of the other's volume fill (a closed mesh's), both ways, one warning for each
// pair where one of the two may move. Such bodies are pushed apart over the first
// substeps, or, when one lies in the other's hollow middle (bodies keep only two layers
// of particles), stay trapped there.
void warnOverlappingBodies(const SceneDesc& desc, const rigid::BodySet& set,
                           const std::vector<rigid::BodyState>& states,
                           const std::vector<std::optional<PlacedSolid>>& solids,
                           std::vector<std::string>& warnings) {
  const std::size_t nb = set.bodies.size();
  // How many of b's particles lie deep in a's fill.
  const auto inside = [&](std::size_t b, std::size_t a) {
    if (!solids[a]) return std::size_t{0};
    const rigid::BodyInfo& B = set.bodies[b];
    const Mat3 r = states[b].orientation.toRotationMatrix();
    std::size_t n = 0;
    for (std::uint32_t k = B.firstId - set.firstId; k < B.firstId - set.firstId + B.count; ++k)
      if (solids[a]->depth(states[b].position + r * Vec3(set.ox[k], set.oy[k], set.oz[k])) == 2) ++n;
    return n;
  };
  for (std::size_t a = 0; a < nb; ++a)
    for (std::size_t b = a + 1; b < nb; ++b) {
      const rigid::BodyInfo &A = set.bodies[a], &B = set.bodies[b];
      if (!A.dynamic && !B.dynamic) continue;
      const double apart = (states[a].position - states[b].position).norm();
      if (apart > A.farthest + B.farthest + 2 * (A.particleRadius + B.particleRadius)) continue;
      const std::size_t bInA = inside(b, a), aInB = inside(a, b);
      if (bInA == 0 && aInB == 0) continue;
      const auto part = [&](const rigid::BodyInfo& x, std::size_t n, const rigid::BodyInfo& y) {
        return fmt::format("{} of the {} particle(s) of '{}' lie inside '{}'", n, x.count, x.name, y.name);
      };
      const std::string what = bInA > 0 && aInB > 0 ? part(B, bInA, A) + " and " + part(A, aInB, B)
                               : bInA > 0           ? part(B, bInA, A)
                                                    : part(A, aInB, B);
      warnings.push_back(fmt::format(
          "Objects '{}' (line {}) and '{}' (line {}) start inside each other ({}): they are pushed apart "
          "over "
          "the first substeps, or, where one lies in the other's hollow middle (objects keep only two outer "
          "layers of particles), it stays trapped there; move one of them",
          A.name, desc.objects[a].line, B.name, desc.objects[b].line, what));
    }
}

}  // namespace

double objectParticleSize(const ObjectDesc& o, const geometry::TriangleMesh& mesh) {
  if (o.particleSize > 0) return o.particleSize;
  const Aabb box = mesh.bounds();
  const double extent = std::max({box.hi[0] - box.lo[0], box.hi[1] - box.lo[1], box.hi[2] - box.lo[2]});
  return extent * o.uniformScale / 20.0;
}

// One object's geometry, worked out before the fluids are placed (ObjectShapes).
struct ObjectShapes::Prepared {
  geometry::TriangleMesh mesh;  // objectMesh: in the geometry's own axes, unscaled
  double spacing = 0;           // particle diameter
  Mass mass;
  std::vector<Vec3> points;  // the body's particles, in scaled geometry coordinates
  std::vector<geometry::SurfaceFaces> faces;
  rigid::BodyState state;            // the initial pose and motion
  std::optional<PlacedSolid> solid;  // a closed mesh's volume fill at the initial pose
  std::string fitWarning;            // a primitive fitted to the mesh far from its volume
};

namespace {

// A dynamic body's primitive without Size is fitted to its mesh's bounding box with its
// axis along y (cylinder, cone): a rod modelled along z took the inertia of a disc four
// times its volume, 8.7 times too large about its own axis, without a word (a review).
// Said when the primitive's volume is off the closed mesh's by more than 2.5 times.
std::string fitWarning(const ObjectDesc& o, const geometry::TriangleMesh& scaled, bool closed) {
  if (!o.isDynamic || !o.size.empty() || o.shape == ObjectShape::Mesh || o.geometry.empty() || !closed)
    return {};
  double meshVolume = 0;
  try {
    meshVolume = geometry::meshMassProperties(scaled, 1.0).volume;
  } catch (const std::exception&) {
    return {};
  }
  const std::vector<double> size = inertiaPrimitiveSize(o, scaled.bounds());
  const double pi = std::numbers::pi;
  double fitted = 0;
  switch (o.shape) {
    case ObjectShape::Sphere: fitted = 4.0 / 3.0 * pi * size[0] * size[0] * size[0]; break;
    case ObjectShape::Cylinder: fitted = pi * size[0] * size[0] * size[1]; break;
    case ObjectShape::Cone: fitted = pi * size[0] * size[0] * size[1] / 3.0; break;
    case ObjectShape::Box: fitted = size[0] * size[1] * size[2]; break;
    case ObjectShape::Mesh: return {};
  }
  const double ratio = fitted / meshVolume;
  if (!(meshVolume > 0) || (ratio <= 2.5 && ratio >= 0.4)) return {};
  // The Size as a scene writes it: before UniformScale, which scales it too.
  std::vector<double> written = size;
  for (double& v : written) v /= o.uniformScale;
  const bool axis = o.shape == ObjectShape::Cylinder || o.shape == ObjectShape::Cone;
  const std::string_view shape = kObjectShapeNames[static_cast<std::size_t>(o.shape)];
  return fmt::format(
      "Object '{}' (line {}): the {} fitted to its mesh for the inertia (Size {:.4g}) holds {:.3g} times "
      "the mesh's volume, so its inertia is far off; {}give Size, {}or use Shape mesh for the mesh's exact "
      "inertia",
      o.name, o.line, shape, fmt::join(written, " "), ratio,
      axis ? fmt::format("a {}'s axis is y: ", shape) : std::string(),
      axis ? "turn the mesh so that its axis is y, " : "");
}

}  // namespace

ObjectShapes::ObjectShapes(const SceneDesc& desc) {
  objects_.reserve(desc.objects.size());
  for (const ObjectDesc& od : desc.objects) {
    Prepared& p = objects_.emplace_back();
    p.mesh = objectMesh(od, desc.baseDir);
    const geometry::TriangleMesh scaled = scaledMesh(p.mesh, od.uniformScale);
    p.spacing = objectParticleSize(od, p.mesh);
    p.mass = massOf(od, scaled);
    const bool closed = isClosed(scaled);
    p.fitWarning = fitWarning(od, scaled, closed);
    std::vector<Vec3> solid;
    p.points = bodyParticles(scaled, closed, p.spacing, p.mass.center, solid);
    // 0.8 particles: the outer lattice layer lies a quarter to three quarters of a
    // particle inside a face, the next layer more than a particle.
    p.faces = geometry::surfaceFaces(scaled, p.points, 0.8 * p.spacing, kFlatDegrees, closed);
    rigid::BodyState& st = p.state;
    st.orientation = rigid::rotationFromEulerDegrees(od.initialRotation);
    st.position = od.initialPosition + st.orientation * p.mass.center;
    if (od.isDynamic) {
      st.velocity = od.initialLinearVelocity;
      const Vec3 omega = od.initialAngularVelocity * (std::numbers::pi / 180.0);
      const Mat3 r = st.orientation.toRotationMatrix();
      st.angularMomentum = r * p.mass.inertia * r.transpose() * omega;
    }
    if (!solid.empty()) p.solid.emplace(solid, p.spacing, od.initialPosition, st.orientation);
  }
}

ObjectShapes::~ObjectShapes() = default;
ObjectShapes::ObjectShapes(ObjectShapes&&) noexcept = default;

// Every object's particles where its initial pose puts them, in cells of the largest
// particle diameter (a hash of cell coordinates), for ObjectShapes::inside.
struct ObjectShapes::Particles {
  double cell = 1, largest = 0;  // cell size; the largest particle radius
  std::unordered_map<std::uint64_t, std::vector<std::pair<Vec3, double>>> cells;  // position, radius
};

const ObjectShapes::Particles& ObjectShapes::particles() const {
  if (particles_) return *particles_;
  particles_ = std::make_unique<Particles>();
  Particles& out = *particles_;
  for (const Prepared& o : objects_) out.largest = std::max(out.largest, 0.5 * o.spacing);
  out.cell = std::max(2 * out.largest, 1e-12);
  for (const Prepared& o : objects_) {
    const Mat3 r = o.state.orientation.toRotationMatrix();
    for (const Vec3& q : o.points) {
      const Vec3 w = o.state.position + r * (q - o.mass.center);
      const Vec3 c = (w / out.cell).array().floor();
      out.cells[cellKey(static_cast<std::int64_t>(c.x()), static_cast<std::int64_t>(c.y()),
                        static_cast<std::int64_t>(c.z()))]
          .emplace_back(w, 0.5 * o.spacing);
    }
  }
  return out;
}

bool ObjectShapes::inside(const Vec3& p, double radius) const {
  if (std::any_of(objects_.begin(), objects_.end(),
                  [&](const Prepared& o) { return o.solid && o.solid->depth(p) > 0; }))
    return true;
  if (objects_.empty()) return false;
  const Particles& ps = particles();
  const double reach = radius + ps.largest;
  const auto span = static_cast<std::int64_t>(std::ceil(reach / ps.cell));
  const Vec3 c = (p / ps.cell).array().floor();
  const auto cx = static_cast<std::int64_t>(c.x()), cy = static_cast<std::int64_t>(c.y()),
             cz = static_cast<std::int64_t>(c.z());
  for (std::int64_t x = cx - span; x <= cx + span; ++x)
    for (std::int64_t y = cy - span; y <= cy + span; ++y)
      for (std::int64_t z = cz - span; z <= cz + span; ++z) {
        const auto found = ps.cells.find(cellKey(x, y, z));
        if (found == ps.cells.end()) continue;
        for (const auto& [q, r] : found->second)
          if ((q - p).squaredNorm() < (radius + r) * (radius + r)) return true;
      }
  return false;
}

void addBodies(const SceneDesc& desc, ObjectShapes&& shapes, solver::Model& m, solver::State& state,
               std::vector<geometry::TriangleMesh>& meshes, std::vector<std::string>* warnings) {
  if (desc.objects.empty()) return;
  rigid::BodySet& set = m.bodies;
  const std::size_t nf = desc.fluids.size();
  set.firstEntity = static_cast<std::uint32_t>(nf);
  set.firstId = static_cast<std::uint32_t>(state.particles.size());

  // Material rows: objects with the same fluid interactions share one row.
  std::vector<std::vector<const PairDesc*>> rowKeys;
  std::vector<std::size_t> rowOf(desc.objects.size());
  for (std::size_t o = 0; o < desc.objects.size(); ++o) {
    std::vector<const PairDesc*> key(nf);
    for (std::size_t f = 0; f < nf; ++f) key[f] = findPair(desc.interactions, desc.fluids[f].name, desc.objects[o].name);
    std::size_t row = 0;
    while (row < rowKeys.size()) {
      bool same = true;
      for (std::size_t f = 0; f < nf && same; ++f)
        same = (rowKeys[row][f] == nullptr) == (key[f] == nullptr) &&
               (key[f] == nullptr || rowKeys[row][f]->interaction == key[f]->interaction);
      if (same) break;
      ++row;
    }
    if (row == rowKeys.size()) rowKeys.push_back(std::move(key));
    rowOf[o] = row;
  }
  const std::size_t rows = nf + rowKeys.size();
  forces::InteractionTable table(rows);
  for (std::size_t a = 0; a < nf; ++a)
    for (std::size_t b = a; b < nf; ++b) table.set(a, b, m.table.interaction(a, b));
  for (std::size_t r = 0; r < rowKeys.size(); ++r)
    for (std::size_t f = 0; f < nf; ++f) {
      const InteractionDesc& d = rowKeys[r][f] ? rowKeys[r][f]->interaction : desc.interactions.fluidObject;
      table.set(nf + r, f, {d.function, d.damping, d.relativeVelocity});
    }
  m.table = std::move(table);
  for (std::size_t r = 0; r < rowKeys.size(); ++r) m.materials.push_back({0.0f, 0.0f, true});

  ParticleStore& store = state.particles;
  std::vector<std::optional<PlacedSolid>> solids;  // per object: its placed volume fill
  solids.reserve(desc.objects.size());
  for (std::size_t o = 0; o < desc.objects.size(); ++o) {
    const ObjectDesc& od = desc.objects[o];
    ObjectShapes::Prepared& p = shapes.objects_[o];
    meshes.push_back(std::move(p.mesh));
    if (warnings && !p.fitWarning.empty()) warnings->push_back(p.fitWarning);

    rigid::BodyInfo info;
    info.name = od.name;
    info.dynamic = od.isDynamic;
    info.mass = od.mass;
    info.inverseMass = od.isDynamic ? 1.0 / od.mass : 0.0;
    info.inverseInertia = od.isDynamic ? Mat3(boundedInertia(p.mass.inertia).inverse()) : Mat3::Zero();
    info.restitution = od.normalAttenuation;
    info.friction = od.tangentAttenuation;
    info.particleRadius = 0.5 * p.spacing;
    info.firstId = static_cast<std::uint32_t>(store.size());
    info.count = static_cast<std::uint32_t>(p.points.size());
    info.originInBody = -p.mass.center;
    info.uniformScale = od.uniformScale;
    info.geometryFile = od.name + ".obj";

    const std::size_t row = nf + rowOf[o];
    m.materials[row].radius = std::max(m.materials[row].radius, static_cast<float>(info.particleRadius));
    const auto material = static_cast<std::uint16_t>(row);
    const auto owner = static_cast<std::uint32_t>(nf + o);
    store.reserve(store.size() + p.points.size());
    for (std::size_t k = 0; k < p.points.size(); ++k) {
      const Vec3 off = p.points[k] - p.mass.center;
      info.farthest = std::max(info.farthest, off.norm());
      set.ox.push_back(static_cast<float>(off.x()));
      set.oy.push_back(static_cast<float>(off.y()));
      set.oz.push_back(static_cast<float>(off.z()));
      rigid::BodyFaces f;
      f.count = p.faces[k].count;
      for (int g = 0; g < p.faces[k].count; ++g) {
        for (int c = 0; c < 3; ++c) f.normal[g][c] = static_cast<float>(p.faces[k].normal[g][c]);
        f.sides[g] = p.faces[k].sides[g];
      }
      set.faces.push_back(f);
      store.add(0, 0, 0, 0, 0, 0, material, owner);  // placed from the body's state
    }
    solids.push_back(std::move(p.solid));
    if (warnings != nullptr && solids.back()) {
      // The fluid particles (the slots before the bodies') in the fill, per fluid.
      std::vector<std::size_t> inside(nf, 0);
      for (std::size_t i = 0; i < set.firstId; ++i)
        if (solids.back()->depth(Vec3(store.px[i], store.py[i], store.pz[i])) > 0)
          ++inside[store.material[i]];
      for (std::size_t f = 0; f < nf; ++f) {
        if (inside[f] == 0) continue;
        // Fills with OutsideObjects leave nothing inside: the rest came from fills without
        // it or from explicit positions, which are never left out.
        const std::vector<FillDesc>& fills = desc.fluids[f].fills;
        const bool uncarved = std::any_of(fills.begin(), fills.end(),
                                          [](const FillDesc& fill) { return !fill.outsideObjects; });
        warnings->push_back(fmt::format(
            "Object '{}' (line {}): {} particle(s) of fluid '{}' start inside it: a body is hollow behind "
            "its two "
            "outer layers of particles, so fluid inside it stays there; {}",
            od.name, od.line, inside[f], desc.fluids[f].name,
            uncarved
                ? "give the fluid's fills <OutsideObjects>true</OutsideObjects> to leave out their points "
                  "inside objects, or move the fill or the object so that they do not overlap"
                : "they are explicit positions, which are never left out: move them or the object"));
      }
    }
    set.bodies.push_back(std::move(info));
    state.bodies.push_back(p.state);
  }
  if (warnings != nullptr) warnOverlappingBodies(desc, set, state.bodies, solids, *warnings);
}

}  // namespace softsub::scene
