// The only translation unit that includes OpenVDB: the blobby field, the level-set
// rebuild, meshing and .vdb files. Keep every other file free of OpenVDB's headers (this
// one alone costs about a minute and 1.4 GB of memory to compile at -O2).
#include <openvdb/openvdb.h>
#include <openvdb/io/File.h>
#include <openvdb/io/Stream.h>
#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/MeshToVolume.h>
#include <openvdb/tools/VolumeToMesh.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>

#include "cache/atomic_file.h"
#include "core/error.h"
#include "core/hash.h"
#include "surface/surface.h"

namespace softsub::surface {

struct LevelSet::Impl {
  // The blobby field as minus the sum of kernels (more negative inside, not a distance);
  // null for a level set read from a file or an empty one. Its surface is where it
  // crosses `iso` (minus the threshold). mesh() meshes it directly.
  openvdb::FloatGrid::Ptr field;
  float iso = 0.0f;
  double voxel = 0.0;
  float halfBand = 3.0f;

  // OpenVDB's polygons of the surface (volumeToMesh, adaptivity 0: uniform quads and the
  // odd triangle, which keeps the mesh watertight), made once and shared by mesh() and the
  // signed-distance rebuild.
  struct Polygons {
    std::vector<openvdb::Vec3s> points;
    std::vector<openvdb::Vec3I> tris;
    std::vector<openvdb::Vec4I> quads;
  };
  /// Takes polygons already made at `iso` (fromParticles' volume check) as the surface's.
  void adoptPolygons(Polygons&& p) {
    std::call_once(polygonsOnce, [&] {
      polys = std::move(p);
      dropCavities(polys, smallestCavity);
    });
  }
  const Polygons& polygons() const {
    std::call_once(polygonsOnce, [this] {
      const openvdb::FloatGrid& g = field ? *field : *grid;
      openvdb::tools::volumeToMesh(g, polys.points, polys.tris, polys.quads, field ? iso : 0.0, 0.0);
      dropCavities(polys, smallestCavity);
    });
    return polys;
  }
  /// Cavities (closed shells enclosing a negative volume) smaller than this are removed
  /// from the surface: one particle's rest volume for a field of particles, 0 otherwise.
  double smallestCavity = 0.0;

  /// Removes every closed shell of `p` whose enclosed volume is negative (a hole inside
  /// the fluid) and smaller in size than `below`, and the points only they used. A
  /// blobby field dips below its iso value in the gaps of a lattice of particles: the
  /// default scene's blocks had about 1,300 such bubbles of 0.01-0.26 units inside each
  /// fluid, under a voxel across (so their gradient normals pointed against their
  /// winding), specks in any refractive render. A particle fluid cannot resolve a
  /// cavity smaller than one particle. Shells are found by their shared points;
  /// deterministic (the order of the polygons is kept).
  static void dropCavities(Polygons& p, double below) {
    if (!(below > 0.0) || p.points.empty()) return;
    const std::size_t n = p.points.size();
    std::vector<std::uint32_t> parent(n);
    for (std::size_t i = 0; i < n; ++i) parent[i] = static_cast<std::uint32_t>(i);
    const auto find = [&](std::uint32_t a) {
      while (parent[a] != a) a = parent[a] = parent[parent[a]];
      return a;
    };
    const auto join = [&](std::uint32_t a, std::uint32_t b) {
      a = find(a), b = find(b);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    };
    for (const openvdb::Vec3I& t : p.tris) join(t[0], t[1]), join(t[0], t[2]);
    for (const openvdb::Vec4I& q : p.quads) join(q[0], q[1]), join(q[0], q[2]), join(q[0], q[3]);
    // OpenVDB winds clockwise seen from outside: a shell's volume is minus its sum.
    std::vector<double> volume(n, 0.0);
    const auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
      const openvdb::Vec3d pa(p.points[a]), pb(p.points[b]), pc(p.points[c]);
      volume[find(a)] -= pa.dot(pb.cross(pc)) / 6.0;
    };
    for (const openvdb::Vec3I& t : p.tris) add(t[0], t[1], t[2]);
    for (const openvdb::Vec4I& q : p.quads) add(q[0], q[1], q[2]), add(q[0], q[2], q[3]);
    const auto dropped = [&](std::uint32_t a) {
      const double v = volume[find(a)];
      return v < 0.0 && -v < below;
    };
    std::vector<std::uint32_t> index(n, UINT32_MAX);
    std::size_t kept = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (!dropped(static_cast<std::uint32_t>(i))) {
        index[i] = static_cast<std::uint32_t>(kept);
        p.points[kept++] = p.points[i];
      }
    if (kept == n) return;
    p.points.resize(kept);
    std::erase_if(p.tris, [&](const openvdb::Vec3I& t) { return index[t[0]] == UINT32_MAX; });
    std::erase_if(p.quads, [&](const openvdb::Vec4I& q) { return index[q[0]] == UINT32_MAX; });
    for (openvdb::Vec3I& t : p.tris)
      for (int k = 0; k < 3; ++k) t[k] = index[t[k]];
    for (openvdb::Vec4I& q : p.quads)
      for (int k = 0; k < 4; ++k) q[k] = index[q[k]];
  }

  // The narrow-band SDF (class GRID_LEVEL_SET): read from a file, or built on first use
  // from the polygons (meshToLevelSet, the slowest step of a frame: a frame that only
  // wants a mesh never pays it; only .vdb output, sample() and activeVoxelCount() do).
  const openvdb::FloatGrid::Ptr& sdf() const {
    std::call_once(sdfOnce, [this] {
      if (!field || grid) return;
      const Polygons& p = polygons();
      grid = openvdb::tools::meshToLevelSet<openvdb::FloatGrid>(field->transform(), p.points, p.tris, p.quads,
                                                               halfBand);
      grid->setGridClass(openvdb::GRID_LEVEL_SET);
      grid->setName("surface");
    });
    return grid;
  }
  mutable openvdb::FloatGrid::Ptr grid;

 private:
  mutable Polygons polys;
  mutable std::once_flag polygonsOnce, sdfOnce;
};

namespace {

void initOpenVdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

// Grid coordinates must stay well inside int32: refuse points beyond 2^30 voxels.
constexpr double kMaxIndex = 1073741824.0;
// At most this many voxels per blob radius (a blob of about 10^6 voxels).
constexpr double kMaxRadiusVoxels = 64.0;

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

// A leaf of the field grid by its index (voxel index >> 3 per axis).
struct LeafKey {
  int x, y, z;
  auto operator<=>(const LeafKey&) const = default;
};

using Leaf = openvdb::FloatTree::LeafNodeType;

// One particle's kernel as a function of s^2 = (distance / blob radius)^2:
// (max(0, 1 - s^2))^3, smooth, 1 at the centre, 0 with zero slope at the blob radius (the
// usual Wyvill-style polynomial), exactly 0 beyond it so that a run of voxels needs no
// branch. Four floats in one SSE register (GCC/Clang vector extension): the kernel over a column
// of a leaf in two steps, one code path for any x86-64 or ARM target.
using Float4 = float __attribute__((vector_size(16)));

// Sums the particles' kernels into the leaves of `field` (empty on entry) and stores
// minus the sum (negative inside, as OpenVDB's level sets). Returns the leaves, in a fixed
// order, and sets `peak` to the largest sum. keys[j] is the
// leaf particle j's centre is in, sorted (stable: a bin keeps particle order); q holds the
// centres in voxel units, in the same order. Each leaf is one task that gathers from the
// bins around it in a fixed order (bins in key order, particles in bin order), so the
// sums, hence the grid, are bitwise the same for any number of threads; nothing is shared
// between tasks. Voxels with a positive sum (reached by a blob) are the active ones.
std::vector<Leaf*> fillLeaves(openvdb::FloatGrid& field, const std::vector<LeafKey>& keys,
                              const std::vector<double>& q, double radiusVoxels, float& peak) {
  static_assert(Leaf::DIM == 8);
  struct Bin {
    LeafKey key;
    std::size_t begin, end;
  };
  std::vector<Bin> bins;
  for (std::size_t j = 0; j < keys.size(); ++j) {
    if (bins.empty() || bins.back().key != keys[j]) bins.push_back({keys[j], j, j});
    bins.back().end = j + 1;
  }
  // A blob reaches voxels up to ceil(radius) from its centre's voxel: that many leaves
  // (rounded up) around its bin.
  const int reach = (ceilInt(radiusVoxels) + 7) / 8;
  std::vector<LeafKey> targets;
  targets.reserve(bins.size() * static_cast<std::size_t>((2 * reach + 1) * (2 * reach + 1) * (2 * reach + 1)));
  for (const Bin& b : bins)
    for (int dx = -reach; dx <= reach; ++dx)
      for (int dy = -reach; dy <= reach; ++dy)
        for (int dz = -reach; dz <= reach; ++dz) targets.push_back({b.key.x + dx, b.key.y + dy, b.key.z + dz});
  std::sort(targets.begin(), targets.end());
  targets.erase(std::unique(targets.begin(), targets.end()), targets.end());

  const double invR = 1.0 / radiusVoxels;
  const double invR2 = invR * invR;
  const auto step = static_cast<float>(invR);  // one voxel, in blob radii
  const Float4 kLane = {0.0f, 1.0f, 2.0f, 3.0f};
  std::vector<std::unique_ptr<Leaf>> leaves(targets.size());
  std::vector<float> leafPeak(targets.size(), 0.0f);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, targets.size(), 16), [&](const auto& range) {
    alignas(64) float sum[Leaf::SIZE];
    for (std::size_t t = range.begin(); t != range.end(); ++t) {
      const LeafKey key = targets[t];
      const int ox = key.x * 8, oy = key.y * 8, oz = key.z * 8;
      std::fill(std::begin(sum), std::end(sum), 0.0f);
      bool touched = false;
      for (int dx = -reach; dx <= reach; ++dx)
        for (int dy = -reach; dy <= reach; ++dy)
          for (int dz = -reach; dz <= reach; ++dz) {
            const LeafKey near{key.x + dx, key.y + dy, key.z + dz};
            const auto bin = std::lower_bound(bins.begin(), bins.end(), near,
                                              [](const Bin& b, const LeafKey& k) { return b.key < k; });
            if (bin == bins.end() || bin->key != near) continue;
            for (std::size_t j = bin->begin; j < bin->end; ++j) {
              const double px = q[3 * j], py = q[3 * j + 1], pz = q[3 * j + 2];
              const int x0 = std::max(ceilInt(px - radiusVoxels), ox), x1 = std::min(floorInt(px + radiusVoxels), ox + 7);
              const int y0 = std::max(ceilInt(py - radiusVoxels), oy), y1 = std::min(floorInt(py + radiusVoxels), oy + 7);
              if (x0 > x1 || y0 > y1) continue;
              const int z0 = std::max(ceilInt(pz - radiusVoxels), oz), z1 = std::min(floorInt(pz + radiusVoxels), oz + 7);
              if (z0 > z1) continue;
              // The halves of each column (z 0-3, 4-7 in the leaf) the blob reaches.
              const int halfBegin = z0 - oz < 4 ? 0 : 4, halfEnd = z1 - oz < 4 ? 4 : 8;
              // A whole column of 8 per (x, y), in float relative to the particle: the
              // kernel is exactly 0 beyond the blob radius, so no clipping along z and a
              // fixed-length loop that vectorises.
              const auto dz0 = static_cast<float>((oz - pz) * invR);
              for (int x = x0; x <= x1; ++x) {
                const double ddx = x - px;
                for (int y = y0; y <= y1; ++y) {
                  const double ddy = y - py;
                  const double sxyd = (ddx * ddx + ddy * ddy) * invR2;
                  if (sxyd >= 1.0) continue;
                  const auto sxy = static_cast<float>(sxyd);
                  float* column = sum + ((x - ox) << 6) + ((y - oy) << 3);
                  for (int half = halfBegin; half < halfEnd; half += 4) {
                    const Float4 tz = dz0 + (kLane + static_cast<float>(half)) * step;
                    Float4 u = 1.0f - (sxy + tz * tz);
                    u = u > 0.0f ? u : 0.0f;
                    Float4 c;
                    std::memcpy(&c, column + half, sizeof c);
                    c += u * u * u;
                    std::memcpy(column + half, &c, sizeof c);
                  }
                  touched = true;
                }
              }
            }
          }
      if (!touched) continue;
      auto leaf = std::make_unique<Leaf>(openvdb::Coord(ox, oy, oz), 0.0f, false);
      float* data = leaf->buffer().data();
      float top = 0.0f;
      for (openvdb::Index n = 0; n < Leaf::SIZE; ++n) {
        data[n] = -sum[n];
        if (sum[n] > 0.0f) leaf->setActiveState(n, true);
        top = std::max(top, sum[n]);
      }
      if (top > 0.0f) {
        leaves[t] = std::move(leaf);
        leafPeak[t] = top;
      }
    }
  });
  std::vector<Leaf*> out;
  out.reserve(leaves.size());
  peak = 0.0f;
  for (std::size_t t = 0; t < leaves.size(); ++t)
    if (leaves[t]) {
      peak = std::max(peak, leafPeak[t]);
      out.push_back(leaves[t].get());
      field.tree().addLeaf(leaves[t].release());
    }
  return out;
}

// The iso value (a sum of kernels) at which the field encloses `want` voxels' worth of
// volume. First a histogram of the voxels' sums (4096 bins up to the peak) gives t0, the
// value with about `want` voxels above it. Then a sub-voxel volume estimate refines it: a
// voxel whose sum f is near the iso value t counts clamp(1/2 + (f - t) / (|grad f| voxel),
// 0, 1), the share of it on the inside of a plane through it (exact for faces parallel to
// the grid, which a count gets wrong by whole voxel planes: a lattice sheet meshed at
// +15%). Voxels far above t (f >= t0 + w) count 1, far below 0; t is found by bisection in
// [t0 - w, t0 + w]. Every pass runs over leaves in parallel; counts are integers and the
// fractional sums are taken in fixed chunks added in order, so the result does not depend
// on the number of threads.
float volumeThreshold(const openvdb::FloatGrid& field, const std::vector<Leaf*>& leaves, float peak, double want) {
  using Range = tbb::blocked_range<std::size_t>;
  constexpr int kBins = 4096;
  const float toBin = static_cast<float>(kBins) / peak;
  using Histogram = std::vector<std::uint64_t>;
  const Histogram histogram = tbb::parallel_reduce(
      Range(0, leaves.size(), 64), Histogram(kBins, 0),
      [&](const Range& r, Histogram h) {
        for (std::size_t l = r.begin(); l != r.end(); ++l)
          for (auto it = leaves[l]->cbeginValueOn(); it; ++it)
            ++h[static_cast<std::size_t>(std::min(static_cast<int>(-*it * toBin), kBins - 1))];
        return h;
      },
      [](Histogram a, const Histogram& b) {
        for (int i = 0; i < kBins; ++i) a[i] += b[i];
        return a;
      });
  int bin = kBins - 1;
  for (double above = 0.0; bin > 0; --bin) {
    above += static_cast<double>(histogram[bin]);
    if (above >= want) break;
  }
  // Stay strictly between 0 (the blob radius: the field's support) and the peak.
  const float tMax = 0.999f * peak;
  if (!(tMax > 1e-3f)) return 0.5f * peak;  // a field this weak (voxels far coarser than the blob): no range to search
  const float t0 = std::clamp(static_cast<float>(bin) / toBin, 1e-3f, tMax);
  const float w = 0.5f * t0;

  struct Near { float f, slope; };  // slope: |grad f| x voxel, in field units per voxel
  std::vector<std::vector<Near>> nearOf(leaves.size());
  std::vector<std::uint64_t> fullOf(leaves.size(), 0);
  tbb::parallel_for(Range(0, leaves.size(), 16), [&](const Range& r) {
    auto acc = field.getConstAccessor();
    for (std::size_t l = r.begin(); l != r.end(); ++l) {
      const Leaf& leaf = *leaves[l];
      const float* data = leaf.buffer().data();
      for (auto it = leaf.cbeginValueOn(); it; ++it) {
        const float f = -*it;
        if (f >= t0 + w) { ++fullOf[l]; continue; }
        if (f <= t0 - w) continue;
        const openvdb::Index n = it.pos();
        const openvdb::Coord local = Leaf::offsetToLocalCoord(n);
        // Central differences of the sum, inside the leaf's buffer where possible.
        const auto d = [&](int a, openvdb::Index stride) {
          const auto at = [&](int delta) -> double {
            const int c = local[a] + delta;
            if (c >= 0 && c < 8) return -double(data[delta > 0 ? n + stride : n - stride]);
            openvdb::Coord g = leaf.origin() + local;
            g[a] += delta;
            return -double(acc.getValue(g));
          };
          return 0.5 * (at(1) - at(-1));
        };
        const double gx = d(0, 64), gy = d(1, 8), gz = d(2, 1);
        nearOf[l].push_back({f, static_cast<float>(std::sqrt(gx * gx + gy * gy + gz * gz))});
      }
    }
  });
  double full = 0.0;
  std::vector<Near> near;
  for (std::size_t l = 0; l < leaves.size(); ++l) {
    full += static_cast<double>(fullOf[l]);
    near.insert(near.end(), nearOf[l].begin(), nearOf[l].end());
  }
  constexpr std::size_t kChunk = 8192;
  std::vector<double> chunkSum((near.size() + kChunk - 1) / kChunk);
  const auto volume = [&](float t) {
    tbb::parallel_for(Range(0, chunkSum.size()), [&](const Range& r) {
      for (std::size_t c = r.begin(); c != r.end(); ++c) {
        double v = 0.0;
        for (std::size_t i = c * kChunk; i < std::min(near.size(), (c + 1) * kChunk); ++i) {
          const Near& n = near[i];
          if (n.slope > 1e-12f) v += std::clamp(0.5 + double(n.f - t) / double(n.slope), 0.0, 1.0);
          else if (n.f > t) v += 1.0;
        }
        chunkSum[c] = v;
      }
    });
    double v = full;
    for (double c : chunkSum) v += c;
    return v;
  };
  float lo = std::max(1e-3f, t0 - w), hi = std::min(tMax, t0 + w);  // volume(lo) >= volume(hi)
  if (volume(lo) < want) return lo;
  if (volume(hi) > want) return hi;
  for (int i = 0; i < 24; ++i) {
    const float mid = 0.5f * (lo + hi);
    (volume(mid) > want ? lo : hi) = mid;
  }
  return 0.5f * (lo + hi);
}

// A quad of volumeToMesh's as two triangles, split along its shorter diagonal (better-
// shaped triangles), in OpenVDB's winding. LevelSet::mesh() writes this split and the
// volume check measures it: on a blob a few voxels across the quads are far from flat,
// and the other split encloses another volume.
std::array<openvdb::Vec3I, 2> quadTriangles(const std::vector<openvdb::Vec3s>& points, const openvdb::Vec4I& q) {
  const auto dist2 = [&](unsigned a, unsigned b) { return (points[a] - points[b]).lengthSqr(); };
  if (dist2(q[0], q[2]) <= dist2(q[1], q[3]))
    return {openvdb::Vec3I(q[0], q[1], q[2]), openvdb::Vec3I(q[0], q[2], q[3])};
  return {openvdb::Vec3I(q[0], q[1], q[3]), openvdb::Vec3I(q[1], q[2], q[3])};
}

// Meshes `field` at iso value -t into `p` (as Impl::polygons does) and returns the volume
// the mesh encloses, in world units: the signed tetrahedra from the origin, summed in the
// polygons' order (the same for any thread count).
double meshedVolume(const openvdb::FloatGrid& field, float t, LevelSet::Impl::Polygons& p) {
  p.points.clear();
  p.tris.clear();
  p.quads.clear();
  openvdb::tools::volumeToMesh(field, p.points, p.tris, p.quads, static_cast<double>(-t), 0.0);
  const auto at = [&](unsigned i) {
    const openvdb::Vec3s& v = p.points[i];
    return openvdb::Vec3d(v[0], v[1], v[2]);
  };
  double v = 0.0;
  const auto add = [&](unsigned a, unsigned b, unsigned c) { v += at(a).dot(at(b).cross(at(c))); };
  for (const auto& tri : p.tris) add(tri[0], tri[1], tri[2]);
  for (const auto& q : p.quads)
    for (const openvdb::Vec3I& tri : quadTriangles(p.points, q)) add(tri[0], tri[1], tri[2]);
  return std::abs(v) / 6.0;
}

// The volume rule's iso value checked against the mesh it gives. volumeThreshold counts
// voxels; a blob only a few voxels across (a lone drop at the default voxel of half a
// particle) meshes far smaller than its voxels' count (a lone particle: 30% of its rest
// volume). When the mesh at t is off by more than kMeshVolumeTolerance, a secant search on
// the meshed volume (decreasing in t) moves t, at most kMeshVolumeSteps more meshings,
// keeping the best. `p` holds the polygons at the returned value.
constexpr double kMeshVolumeTolerance = 0.02;
constexpr int kMeshVolumeSteps = 6;
float meshVolumeThreshold(const openvdb::FloatGrid& field, float t, float peak, double want,
                          LevelSet::Impl::Polygons& p) {
  double v = meshedVolume(field, t, p);
  const float tMin = 1e-3f, tMax = 0.999f * peak;
  if (!(want > 0.0) || std::abs(v - want) <= kMeshVolumeTolerance * want || !(tMax > tMin)) return t;
  LevelSet::Impl::Polygons trial;
  float best = t, ta = t;
  double bestError = std::abs(v - want), va = v;
  float tb = std::clamp(v < want ? 0.7f * t : 1.3f * t, tMin, tMax);
  for (int step = 0; step < kMeshVolumeSteps && tb != ta; ++step) {
    const double vb = meshedVolume(field, tb, trial);
    if (std::abs(vb - want) < bestError) {
      bestError = std::abs(vb - want);
      best = tb;
      std::swap(p, trial);
    }
    if (bestError <= kMeshVolumeTolerance * want) break;
    // Secant step; where the volume did not change (both ends empty or saturated), a
    // plain step in the needed direction.
    float next = vb != va ? tb + static_cast<float>((want - vb) * double(tb - ta) / (vb - va))
                          : (vb < want ? 0.7f * tb : 1.3f * tb);
    if (!std::isfinite(next)) next = vb < want ? 0.7f * tb : 1.3f * tb;
    ta = tb;
    va = vb;
    tb = std::clamp(next, tMin, tMax);
  }
  return best;
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
  impl->voxel = voxelSizeFor(particleSize, s);
  // With the slack (kMinVoxelSize has room: OpenVDB's own floor is 1.45e-5).
  if (belowVoxelFloor(impl->voxel, kMinVoxelSize))
    throw std::invalid_argument("surface: voxel size below the smallest the grid takes (allowed: voxel >= " +
                                fmt::format("{:g}", kMinVoxelSize) + ")");
  if (!(impl->voxel <= kMaxVoxelSize))
    throw std::invalid_argument(
        fmt::format("surface: voxel size {:g} above the largest the grid takes (allowed: "
                    "voxel <= {:g})",
                    impl->voxel, kMaxVoxelSize));
  const double vx = impl->voxel;
  const double radius = s.radiusScale * particleSize;  // blob radius
  auto threshold = static_cast<float>(s.threshold);

  // The field phi = threshold - sum of kernels, accumulated sparsely: only the 8^3 leaves
  // within a blob radius of some particle exist, so far-apart particles cost their blobs'
  // voxels, not their bounding box.
  auto field = openvdb::FloatGrid::create(0.0f);
  field->setTransform(openvdb::math::Transform::createLinearTransform(vx));
  const double inv = 1.0 / vx;
  const double radiusVoxels = radius * inv;
  // Cost and memory grow as (radius / voxel)^3 per particle: refuse a voxel so small that
  // one blob alone would span millions of voxels.
  if (radiusVoxels > kMaxRadiusVoxels)
    throw std::invalid_argument("surface: voxel size too small for the particle size (allowed: voxel >= blob radius / " +
                                std::to_string(static_cast<int>(kMaxRadiusVoxels)) + ")");
  std::vector<double> q;  // finite particles in voxel units, grouped by bin (below)
  std::vector<Leaf*> leaves;
  float peak = 0.0f;
  std::size_t used = 0;
  {
    // Bin the particles by the leaf their centre is in (bins keep particle order).
    std::vector<LeafKey> binOf;
    std::vector<double> qAll;
    qAll.reserve(xyz.size());
    binOf.reserve(xyz.size() / 3);
    for (std::size_t i = 0; i + 2 < xyz.size(); i += 3) {
      const double p[3] = {xyz[i] * inv, xyz[i + 1] * inv, xyz[i + 2] * inv};
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) continue;
      for (double c : p)
        if (std::abs(c) > kMaxIndex)
          throw std::invalid_argument("surface: a particle is too far from the origin for the voxel grid");
      qAll.insert(qAll.end(), p, p + 3);
      binOf.push_back({floorInt(p[0]) >> 3, floorInt(p[1]) >> 3, floorInt(p[2]) >> 3});
    }
    used = binOf.size();
    if (used == 0) return LevelSet(std::move(impl));  // empty: nothing inside
    std::vector<std::size_t> order(used);
    for (std::size_t i = 0; i < used; ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return binOf[a] < binOf[b]; });
    q.resize(3 * used);
    std::vector<LeafKey> keys(used);
    for (std::size_t j = 0; j < used; ++j) {
      std::copy_n(&qAll[3 * order[j]], 3, &q[3 * j]);
      keys[j] = binOf[order[j]];
    }
    leaves = fillLeaves(*field, keys, q, radiusVoxels, peak);
  }
  // The blobby field is not a distance: the narrow-band signed-distance level set that
  // other tools expect in a .vdb is rebuilt from it when first asked for (Impl::sdf).
  // Classed as a level set (negative inside) so that volumeToMesh winds its polygons as it
  // does for the SDF (it reverses them for level sets).
  field->setGridClass(openvdb::GRID_LEVEL_SET);
  const double perParticle =
      s.restVolumePerParticle > 0.0 ? s.restVolumePerParticle : particleSize * particleSize * particleSize;
  impl->smallestCavity = perParticle;
  if (s.preserveVolume) {
    // The iso value that encloses the rest volume by the voxels' count, then checked
    // against the mesh it gives (whose polygons become the surface's).
    threshold = volumeThreshold(*field, leaves, peak, double(used) * perParticle / (vx * vx * vx));
    Impl::Polygons polygons;
    threshold = meshVolumeThreshold(*field, threshold, peak, double(used) * perParticle, polygons);
    impl->adoptPolygons(std::move(polygons));
  }
  // The field holds minus the sums, so its surface is at minus the threshold; everything
  // never touched is the background 0, outside.
  impl->iso = -threshold;

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
  // The field's crossing of its iso value is the surface: mesh it directly (no rebuild).
  // A file's level set is meshed at zero.
  const auto& grid = impl_->field ? *impl_->field : *impl_->sdf();
  const auto& [points, tris, quads] = impl_->polygons();

  out.vertices.reserve(points.size());
  for (const auto& p : points) out.vertices.push_back({p[0], p[1], p[2]});
  // OpenVDB winds its polygons clockwise seen from outside (negative inside): reverse
  // them so that triangles are counter-clockwise and the enclosed volume is positive.
  out.triangles.reserve(tris.size() + 2 * quads.size());
  for (const auto& t : tris) out.triangles.push_back({t[2], t[1], t[0]});
  for (const auto& q : quads)
    for (const openvdb::Vec3I& t : quadTriangles(points, q)) out.triangles.push_back({t[2], t[1], t[0]});

  // Normals: the level set's gradient (central differences, half a voxel apart), one
  // vertex per index, in parallel (each task with its own cached accessor).
  const double h = 0.5 * impl_->voxel;
  out.normals.resize(points.size());
  using Range = tbb::blocked_range<std::size_t>;
  tbb::parallel_for(Range(0, points.size(), 1024), [&](const Range& r) {
    const auto acc = grid.getConstAccessor();
    const openvdb::tools::GridSampler<openvdb::FloatGrid::ConstAccessor, openvdb::tools::BoxSampler> sampler(
        acc, grid.transform());
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const openvdb::Vec3d c(points[i][0], points[i][1], points[i][2]);
      const auto diff = [&](const openvdb::Vec3d& e) { return sampler.wsSample(c + e) - sampler.wsSample(c - e); };
      openvdb::Vec3d g(diff({h, 0, 0}), diff({0, h, 0}), diff({0, 0, h}));
      const double len = g.length();
      if (len > 0.0) g /= len; else g = openvdb::Vec3d(0, 0, 1);
      out.normals[i] = {static_cast<float>(g[0]), static_cast<float>(g[1]), static_cast<float>(g[2])};
    }
  });
  return out;
}

namespace {

/// OpenVDB stamps every file with a random UUID, so the same grid written twice gives
/// two different files. For outputs that must be byte-identical across runs (a resumed
/// run's, docs/cache-formats.md), the UUID is replaced by one derived from the file's
/// other bytes: the same content, the same id. The header is magic (8 bytes), file
/// version, library major and minor (4 each), a grid-offsets flag (1), then the UUID as
/// 36 characters; anything else is left alone.
void makeFileIdFromContent(std::string& bytes) {
  constexpr std::size_t kUuidAt = 21, kUuidSize = 36;
  if (bytes.size() < kUuidAt + kUuidSize) return;
  for (const std::size_t dash : {8u, 13u, 18u, 23u})
    if (bytes[kUuidAt + dash] != '-') return;
  std::string rest = bytes;
  rest.erase(kUuidAt, kUuidSize);
  const std::uint64_t a = hashBytes(rest), b = hashBytes(rest, a);
  // Version 8 (custom) and the RFC 4122 variant, so readers see a well-formed UUID.
  const std::string id = fmt::format("{:08x}-{:04x}-8{:03x}-{:04x}-{:012x}", a >> 32, (a >> 16) & 0xffff,
                                     a & 0xfff, 0x8000 | ((b >> 48) & 0x3fff), b & 0xffffffffffffULL);
  bytes.replace(kUuidAt, kUuidSize, id);
}

}  // namespace

void LevelSet::writeVdb(const std::filesystem::path& file, const std::string& gridName) const {
  initOpenVdb();
  openvdb::FloatGrid::Ptr grid;
  if (const auto& sdf = impl_->sdf()) {
    grid = sdf->deepCopy();
  } else {
    grid = openvdb::createLevelSet<openvdb::FloatGrid>(impl_->voxel > 0.0 ? impl_->voxel : 1.0);
  }
  grid->setName(gridName);
  // Into memory through OpenVDB's stream writer, then written like every other output
  // (writeFileAtomic: a temporary name, every write and the close checked, renamed).
  // OpenVDB's own file writer does not check the stream after writing: on a full disk it
  // would leave a short file behind.
  std::ostringstream out(std::ios::binary);
  try {
    openvdb::io::Stream(out).write({grid});
  } catch (const openvdb::Exception& e) {
    throw IoError("cannot write " + file.string() + ": " + e.what());
  }
  if (!out) throw IoError("cannot write " + file.string() + ": encoding the level set failed");
  std::string bytes = std::move(out).str();
  makeFileIdFromContent(bytes);
  cache::writeFileAtomic(file, bytes);
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

double minimumVoxelSize(double particleSize, const SurfaceSettings& settings) {
  return std::max(settings.radiusScale * particleSize / kMaxRadiusVoxels, kMinVoxelSize);
}

double voxelSizeFor(double particleSize, const SurfaceSettings& settings) {
  return settings.voxelSize > 0.0 ? settings.voxelSize : particleSize / 2.0;
}

double gridReach(double voxelSize) { return voxelSize * kMaxIndex; }

SurfaceMesh meshParticles(std::span<const float> xyz, double particleSize,
                          const SurfaceSettings& settings) {
  return LevelSet::fromParticles(xyz, particleSize, settings).mesh();
}

}  // namespace softsub::surface
