// The only translation unit that includes OpenVDB: the blobby field, the level-set
// rebuild, meshing and .vdb files. Keep every other file free of OpenVDB's headers (this
// one alone costs about a minute and 1.4 GB of memory to compile at -O2).
#include <openvdb/openvdb.h>
#include <openvdb/io/File.h>
#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/LevelSetRebuild.h>
#include <openvdb/tools/VolumeToMesh.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <mutex>
#include <stdexcept>

#include "core/error.h"
#include "surface/surface.h"

namespace softsub::surface {

struct LevelSet::Impl {
  // The blobby field as threshold - sum of kernels (negative inside, not a distance); null
  // for a level set read from a file or an empty one. mesh() meshes it directly.
  openvdb::FloatGrid::Ptr field;
  double voxel = 0.0;
  float halfBand = 3.0f;

  // The narrow-band SDF (class GRID_LEVEL_SET): read from a file, or rebuilt from the field
  // on first use. The rebuild (OpenVDB meshes the field and voxelises the mesh back) is
  // three times the cost of the rest of a frame, so a frame that only wants a mesh never
  // pays it; only .vdb output, sample() and activeVoxelCount() do.
  const openvdb::FloatGrid::Ptr& sdf() const {
    std::call_once(sdfOnce, [this] {
      if (!field || grid) return;
      grid = openvdb::tools::levelSetRebuild(*field, 0.0f, halfBand, halfBand);
      grid->setGridClass(openvdb::GRID_LEVEL_SET);
      grid->setName("surface");
    });
    return grid;
  }
  mutable openvdb::FloatGrid::Ptr grid;

 private:
  mutable std::once_flag sdfOnce;
};

namespace {

void initOpenVdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

// Grid coordinates must stay well inside int32: refuse points beyond 2^30 voxels.
constexpr double kMaxIndex = 1073741824.0;

// One particle's kernel as a function of (distance / blob radius)^2: smooth, 1 at the
// centre, 0 with zero slope at the blob radius (the usual Wyvill-style polynomial).
// Clamped at 0 beyond the radius, so that a run of voxels needs no branch.
inline float kernel(float s2) {
  const float u = std::max(0.0f, 1.0f - s2);
  return u * u * u;
}

// floor and ceil for |v| < 2^31 without a libm call (baseline x86-64 has no rounding
// instruction, and these run once per column of voxels).
inline int floorInt(double v) {
  const int i = static_cast<int>(v);
  return i > v ? i - 1 : i;
}
inline int ceilInt(double v) {
  const int i = static_cast<int>(v);
  return i < v ? i + 1 : i;
}

// Refines the ranked threshold t0 so that a sub-voxel volume estimate, not a voxel count,
// encloses `want` voxels' worth. A voxel whose value f is near the iso value t counts
// clamp(1/2 + (f - t) / (|grad f| voxel), 0, 1): the share of it on the inside of a plane
// through it (exact for faces parallel to the grid, which a count gets wrong by whole
// voxel planes: a lattice sheet meshed at +15%). Voxels far above t (f >= t0 + w) count 1,
// far below 0; t is found by bisection in [t0 - w, t0 + w].
float subVoxelThreshold(const openvdb::FloatGrid& field, float t0, float tMax, double want) {
  const float w = 0.5f * t0;
  struct Near { float f, slope; };  // slope: |grad f| x voxel, in field units per voxel
  std::vector<Near> near;
  double full = 0.0;
  auto acc = field.getConstAccessor();
  for (auto it = field.tree().cbeginValueOn(); it; ++it) {
    const float f = *it;
    if (f >= t0 + w) { full += 1.0; continue; }
    if (f <= t0 - w) continue;
    const openvdb::Coord c = it.getCoord();
    const auto d = [&](int a) {
      openvdb::Coord up = c, down = c;
      up[a] += 1;
      down[a] -= 1;
      return 0.5 * (double(acc.getValue(up)) - double(acc.getValue(down)));
    };
    const double gx = d(0), gy = d(1), gz = d(2);
    near.push_back({f, static_cast<float>(std::sqrt(gx * gx + gy * gy + gz * gz))});
  }
  const auto volume = [&](float t) {
    double v = full;
    for (const Near& n : near) {
      if (n.slope > 1e-12f) v += std::clamp(0.5 + double(n.f - t) / double(n.slope), 0.0, 1.0);
      else if (n.f > t) v += 1.0;
    }
    return v;
  };
  float lo = std::max(1e-3f, t0 - w), hi = std::min(tMax, t0 + w);  // volume(lo) >= volume(hi)
  if (volume(lo) < want) return lo;
  if (volume(hi) > want) return hi;
  for (int i = 0; i < 30; ++i) {
    const float mid = 0.5f * (lo + hi);
    (volume(mid) > want ? lo : hi) = mid;
  }
  return 0.5f * (lo + hi);
}

}  // namespace

LevelSet::LevelSet() : impl_(std::make_shared<const Impl>()) {}
LevelSet::LevelSet(std::shared_ptr<const Impl> impl) : impl_(std::move(impl)) {}

LevelSet LevelSet::fromParticles(std::span<const float> xyz, double particleSize,
                                 const SurfaceSettings& s) {
  if (!(particleSize > 0.0) || !std::isfinite(particleSize))
    throw std::invalid_argument("surface: particle size must be positive");
  if (!(s.restVolumePerParticle >= 0.0) || !(s.radiusScale > 0.0) || !(s.threshold > 0.0) || !(s.threshold < 1.0) ||
      !(s.voxelSize >= 0.0) || !(s.halfBandVoxels >= 1.0))
    throw std::invalid_argument(
        "surface: settings out of range (radiusScale > 0, 0 < threshold < 1, voxelSize >= 0, "
        "halfBandVoxels >= 1)");
  if (xyz.size() % 3 != 0) throw std::invalid_argument("surface: positions are not xyz triples");
  initOpenVdb();

  auto impl = std::make_shared<Impl>();
  impl->voxel = s.voxelSize > 0.0 ? s.voxelSize : particleSize / 3.0;
  const double vx = impl->voxel;
  const double radius = s.radiusScale * particleSize;  // blob radius
  const double r2 = radius * radius;
  auto threshold = static_cast<float>(s.threshold);

  // The field phi = threshold - sum of kernels, accumulated sparsely: only voxels within
  // a blob radius of some particle are touched, so far-apart particles cost
  // (2 * radius / voxel)^3 voxels each, not their bounding box.
  auto field = openvdb::FloatGrid::create(0.0f);
  field->setTransform(openvdb::math::Transform::createLinearTransform(vx));
  // Each particle writes straight into the buffers of the 8^3 leaves its blob overlaps (2
  // to 3 per axis): one cached leaf look-up per leaf instead of a tree access per voxel,
  // per (x, y) column only the z run inside the blob, and the active mask set once at the
  // end (the voxels with a positive sum). Sums are taken in particle order (the same
  // float results as a voxel-by-voxel accumulation).
  using Leaf = openvdb::FloatTree::LeafNodeType;
  constexpr int kLeafDim = static_cast<int>(Leaf::DIM);
  auto acc = field->getAccessor();
  const double inv = 1.0 / vx;
  const double invR2 = 1.0 / r2;
  const double invRadius = 1.0 / radius;
  const auto step = static_cast<float>(vx * invRadius);  // one voxel, in blob radii
  std::size_t used = 0;
  for (std::size_t i = 0; i + 2 < xyz.size(); i += 3) {
    const double p[3] = {xyz[i], xyz[i + 1], xyz[i + 2]};
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) continue;
    for (double c : p)
      if (std::abs(c * inv) > kMaxIndex)
        throw std::invalid_argument("surface: a particle is too far from the origin for the voxel grid");
    ++used;
    int lo[3], hi[3];  // voxels within the blob radius along each axis
    for (int a = 0; a < 3; ++a) {
      lo[a] = ceilInt((p[a] - radius) * inv);
      hi[a] = floorInt((p[a] + radius) * inv);
    }
    // Leaf origins are multiples of kLeafDim (>> is floor division for negatives in C++20).
    for (int lx = lo[0] >> 3; lx <= hi[0] >> 3; ++lx)
      for (int ly = lo[1] >> 3; ly <= hi[1] >> 3; ++ly)
        for (int lz = lo[2] >> 3; lz <= hi[2] >> 3; ++lz) {
          const openvdb::Coord origin(lx * kLeafDim, ly * kLeafDim, lz * kLeafDim);
          float* data = acc.touchLeaf(origin)->buffer().data();
          const int x0 = std::max(lo[0], origin.x()), x1 = std::min(hi[0], origin.x() + kLeafDim - 1);
          const int y0 = std::max(lo[1], origin.y()), y1 = std::min(hi[1], origin.y() + kLeafDim - 1);
          const int zl = std::max(lo[2], origin.z()), zh = std::min(hi[2], origin.z() + kLeafDim - 1);
          for (int x = x0; x <= x1; ++x) {
            const double dx = x * vx - p[0];
            for (int y = y0; y <= y1; ++y) {
              const double dy = y * vx - p[1];
              const double rest = r2 - dx * dx - dy * dy;
              if (rest <= 0.0) continue;
              const double half = std::sqrt(rest);
              const int z0 = std::max(zl, ceilInt((p[2] - half) * inv));
              const int z1 = std::min(zh, floorInt((p[2] + half) * inv));
              // The run in float, relative to the particle (short enough to vectorise).
              const auto sxy = static_cast<float>((dx * dx + dy * dy) * invR2);
              const auto dz0 = static_cast<float>((z0 * vx - p[2]) * invRadius);
              float* column = data + Leaf::coordToOffset(openvdb::Coord(x, y, z0));
              for (int k = 0; k <= z1 - z0; ++k) {
                const float t = dz0 + static_cast<float>(k) * step;
                column[k] += kernel(sxy + t * t);
              }
            }
          }
        }
  }
  // The field's support: the voxels a blob reached (a positive sum) are the active ones.
  for (auto leaf = field->tree().beginLeaf(); leaf; ++leaf) {
    const float* data = leaf->buffer().data();
    for (openvdb::Index n = 0; n < Leaf::SIZE; ++n)
      if (data[n] > 0.0f) leaf->setActiveState(n, true);
  }
  if (used == 0) return LevelSet(std::move(impl));  // empty: nothing inside

  if (s.preserveVolume) {
    // The iso value that encloses the rest volume: first the field value of the voxel
    // ranked (rest volume / voxel volume) from the top (a voxel count, O(voxels)), then
    // refined with a sub-voxel volume estimate near the surface. No meshing.
    std::vector<float> values;
    values.reserve(static_cast<std::size_t>(field->activeVoxelCount()));
    for (auto it = field->tree().cbeginValueOn(); it; ++it) values.push_back(*it);
    const double perParticle =
        s.restVolumePerParticle > 0.0 ? s.restVolumePerParticle : particleSize * particleSize * particleSize;
    const double want = double(used) * perParticle / (vx * vx * vx);
    const auto rank = static_cast<std::size_t>(std::clamp(want, 1.0, double(values.size())) - 1.0);
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(rank), values.end(),
                     std::greater<>());
    // Stay strictly between 0 (the blob radius: the field's support) and the peak.
    const float peak = *std::max_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(rank) + 1);
    const float t0 = std::clamp(values[rank], 1e-3f, 0.999f * peak);
    threshold = subVoxelThreshold(*field, t0, 0.999f * peak, want);
  }

  // Sum of kernels -> threshold - sum (negative inside, OpenVDB's level-set sign), with
  // the background (everything never touched) outside at +threshold.
  for (auto it = field->tree().beginValueOn(); it; ++it) it.setValue(threshold - *it);
  field->tree().root().setBackground(threshold, /*updateChildNodes=*/true);

  // The blobby field is not a distance: the narrow-band signed-distance level set that
  // other tools expect in a .vdb is rebuilt from it when first asked for (Impl::sdf).
  // Classed as a level set (negative inside) so that volumeToMesh winds its polygons as it
  // does for the SDF (it reverses them for level sets).
  field->setGridClass(openvdb::GRID_LEVEL_SET);
  impl->halfBand = static_cast<float>(s.halfBandVoxels);
  impl->field = std::move(field);
  return LevelSet(std::move(impl));
}

LevelSet LevelSet::readVdb(const std::filesystem::path& file) {
  initOpenVdb();
  try {
    openvdb::io::File in(file.string());
    in.open();
    openvdb::GridPtrVecPtr grids = in.getGrids();
    in.close();
    for (const auto& base : *grids) {
      if (auto g = openvdb::gridPtrCast<openvdb::FloatGrid>(base)) {
        auto impl = std::make_shared<Impl>();
        impl->grid = g;
        impl->voxel = g->voxelSize()[0];
        return LevelSet(std::move(impl));
      }
    }
  } catch (const openvdb::Exception& e) {
    throw IoError("cannot read " + file.string() + ": " + e.what());
  }
  throw IoError("cannot read " + file.string() + ": no float grid in it");
}

SurfaceMesh LevelSet::mesh() const {
  SurfaceMesh out;
  if (empty()) return out;
  // The field's zero crossing is the surface: mesh it directly (no rebuild). A file's
  // level set is meshed as it is.
  const auto& grid = impl_->field ? *impl_->field : *impl_->sdf();
  std::vector<openvdb::Vec3s> points;
  std::vector<openvdb::Vec3I> tris;
  std::vector<openvdb::Vec4I> quads;
  // Adaptivity 0: uniform quads, which keeps the mesh watertight.
  openvdb::tools::volumeToMesh(grid, points, tris, quads, 0.0, 0.0);

  out.vertices.reserve(points.size());
  for (const auto& p : points) out.vertices.push_back({p[0], p[1], p[2]});
  // OpenVDB winds its polygons clockwise seen from outside (negative inside): reverse
  // them so that triangles are counter-clockwise and the enclosed volume is positive.
  out.triangles.reserve(tris.size() + 2 * quads.size());
  for (const auto& t : tris) out.triangles.push_back({t[2], t[1], t[0]});
  const auto dist2 = [&](unsigned a, unsigned b) { return (points[a] - points[b]).lengthSqr(); };
  for (const auto& q : quads) {
    // Split along the shorter diagonal (better-shaped triangles).
    if (dist2(q[0], q[2]) <= dist2(q[1], q[3])) {
      out.triangles.push_back({q[2], q[1], q[0]});
      out.triangles.push_back({q[3], q[2], q[0]});
    } else {
      out.triangles.push_back({q[3], q[1], q[0]});
      out.triangles.push_back({q[3], q[2], q[1]});
    }
  }

  // Normals: the level set's gradient (central differences, half a voxel apart).
  openvdb::tools::GridSampler<openvdb::FloatGrid, openvdb::tools::BoxSampler> sampler(grid);
  const double h = 0.5 * impl_->voxel;
  out.normals.reserve(points.size());
  for (const auto& p : points) {
    const openvdb::Vec3d c(p[0], p[1], p[2]);
    openvdb::Vec3d g(sampler.wsSample(c + openvdb::Vec3d(h, 0, 0)) - sampler.wsSample(c - openvdb::Vec3d(h, 0, 0)),
                     sampler.wsSample(c + openvdb::Vec3d(0, h, 0)) - sampler.wsSample(c - openvdb::Vec3d(0, h, 0)),
                     sampler.wsSample(c + openvdb::Vec3d(0, 0, h)) - sampler.wsSample(c - openvdb::Vec3d(0, 0, h)));
    const double len = g.length();
    if (len > 0.0) g /= len; else g = openvdb::Vec3d(0, 0, 1);
    out.normals.push_back({static_cast<float>(g[0]), static_cast<float>(g[1]), static_cast<float>(g[2])});
  }
  return out;
}

void LevelSet::writeVdb(const std::filesystem::path& file, const std::string& gridName) const {
  initOpenVdb();
  openvdb::FloatGrid::Ptr grid;
  if (const auto& sdf = impl_->sdf()) {
    grid = sdf->deepCopy();
  } else {
    grid = openvdb::createLevelSet<openvdb::FloatGrid>(impl_->voxel > 0.0 ? impl_->voxel : 1.0);
  }
  grid->setName(gridName);
  try {
    openvdb::io::File out(file.string());
    out.write({grid});
    out.close();
  } catch (const openvdb::Exception& e) {
    throw IoError("cannot write " + file.string() + ": " + e.what());
  }
}

double LevelSet::sample(double x, double y, double z) const {
  const auto& sdf = impl_->sdf();
  if (!sdf) return 1.0;  // empty: outside everywhere
  openvdb::tools::GridSampler<openvdb::FloatGrid, openvdb::tools::BoxSampler> sampler(*sdf);
  return sampler.wsSample(openvdb::Vec3d(x, y, z));
}

double LevelSet::voxelSize() const { return impl_->voxel; }

std::size_t LevelSet::activeVoxelCount() const {
  const auto& sdf = impl_->sdf();
  return sdf ? static_cast<std::size_t>(sdf->activeVoxelCount()) : 0;
}

// A field always has voxels inside (its threshold stays below its peak).
bool LevelSet::empty() const { return !impl_->field && (!impl_->grid || impl_->grid->tree().empty()); }

SurfaceMesh meshParticles(std::span<const float> xyz, double particleSize,
                          const SurfaceSettings& settings) {
  return LevelSet::fromParticles(xyz, particleSize, settings).mesh();
}

}  // namespace softsub::surface
