#include "geometry/fill.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <numbers>
#include <unordered_map>
#include <unordered_set>

#include "core/error.h"

namespace softsub::geometry {
namespace {

using Point = std::array<double, 3>;

/* Every sample point is its voxel centre moved by kNudge·spacing. A mesh whose vertices or
   faces sit on the lattice (a box from 0 to 20 at spacing 1, a vertex at a voxel centre) would
   otherwise put rays exactly through edges, vertices and faces. The nudge is not a multiple of
   any simple fraction of the spacing and far above the rounding of the coordinates, so exact
   ties only remain by coincidence; those are settled by the tie rule in `side` below. The
   points returned are the centres themselves. */
constexpr double kNudge[3] = {1.4142135e-6, 1.7320508e-6, 2.2360679e-6};

/// The lattice: n[a] voxels of side `spacing` along axis a from `lo`.
struct Grid {
  double lo[3] = {0, 0, 0};
  std::uint64_t n[3] = {1, 1, 1};
  double spacing = 1;

  [[nodiscard]] std::size_t voxels() const { return static_cast<std::size_t>(n[0] * n[1] * n[2]); }
  [[nodiscard]] std::size_t index(std::size_t x, std::size_t y, std::size_t z) const {
    return x + static_cast<std::size_t>(n[0]) * (y + static_cast<std::size_t>(n[1]) * z);
  }
  /// Local (relative to lo) coordinate of voxel centre k along an axis.
  [[nodiscard]] double centre(std::size_t k) const { return (static_cast<double>(k) + 0.5) * spacing; }
};

/// Voxels along an extent: at least one, as a double (may be huge or infinite).
double cellsAlong(double extent, double spacing) { return std::max(1.0, std::ceil(extent / spacing)); }

/// Voxel indices [first, last] whose centre (plus `shift`) may lie in [lo, hi], one voxel of
/// margin each side (the exact tests decide); false when none of [0, n) is in range.
bool voxelRange(double lo, double hi, double shift, const Grid& grid, std::uint64_t n, std::size_t& first,
                std::size_t& last) {
  const double f = std::max(0.0, std::floor((lo - shift) / grid.spacing - 0.5) - 1);
  const double l = std::min(static_cast<double>(n - 1), std::ceil((hi - shift) / grid.spacing - 0.5) + 1);
  if (!(f <= l)) return false;
  first = static_cast<std::size_t>(f);
  last = static_cast<std::size_t>(l);
  return true;
}

/// Which side of the 2-D edge a→b the point q lies on, with the edge function's value.
struct Side {
  double value;   ///< (b - a) × (q - a): twice the signed area of (a, b, q)
  bool positive;  ///< the sign, never "zero": see below
};

/* The edge function, computed the same way whichever direction the edge is walked (from its
   lexicographically smaller end), so two triangles sharing an edge see exactly opposite values.
   A zero is decided as if q were moved by (ε, ε²) (simulation of simplicity): a point on a
   shared edge then lies in exactly one of two triangles that continue the surface across it,
   and in both or neither of two that fold back (a silhouette), which keeps the parity right. */
Side side(const double* a, const double* b, const double* q) {
  const bool swapped = b[0] < a[0] || (b[0] == a[0] && b[1] < a[1]);
  const double* p = swapped ? b : a;
  const double* r = swapped ? a : b;
  const double du = r[0] - p[0];
  const double dv = r[1] - p[1];
  double value = du * (q[1] - p[1]) - dv * (q[0] - p[0]);
  bool positive = value > 0 || (value == 0 && (dv < 0 || (dv == 0 && du > 0)));
  if (swapped) {
    value = -value;
    positive = !positive;
  }
  return {value, positive};
}

/// A ray crossing the surface at parameter t, entering (+1) or leaving (-1) seen from the
/// triangle's winding (the winding only matters to tell duplicates from folds).
struct Crossing {
  double t;
  int dir;
  bool operator<(const Crossing& o) const { return t < o.t || (t == o.t && dir < o.dir); }
};

/// Casts one ray per column along +axis and sets bit `axis` of votes[v] for every voxel whose
/// sample point has an odd number of crossings before it.
void castAxis(int axis, const Grid& grid, const std::vector<Point>& local,
              const std::vector<std::array<std::uint32_t, 3>>& triangles, const std::vector<bool>& usable,
              double tolerance, std::vector<std::uint8_t>& votes) {
  const int u = (axis + 1) % 3;
  const int v = (axis + 2) % 3;
  const auto nu = static_cast<std::size_t>(grid.n[u]);
  const auto nv = static_cast<std::size_t>(grid.n[v]);
  const auto na = static_cast<std::size_t>(grid.n[axis]);
  const double s = grid.spacing;
  const double shift[3] = {kNudge[0] * s, kNudge[1] * s, kNudge[2] * s};

  // Every crossing of every column, found triangle by triangle over the columns its 2-D box covers.
  struct ColumnCrossing {
    std::size_t column;
    Crossing crossing;
  };
  std::vector<ColumnCrossing> found;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    if (!usable[t]) continue;
    const Point& p0 = local[triangles[t][0]];
    const Point& p1 = local[triangles[t][1]];
    const Point& p2 = local[triangles[t][2]];
    const double a[2] = {p0[u], p0[v]};
    const double b[2] = {p1[u], p1[v]};
    const double c[2] = {p2[u], p2[v]};
    const double projected = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    if (projected == 0) continue;  // seen edge-on along this axis: the neighbours are crossed instead
    std::size_t u0 = 0, u1 = 0, v0 = 0, v1 = 0;
    if (!voxelRange(std::min({a[0], b[0], c[0]}), std::max({a[0], b[0], c[0]}), shift[u], grid, grid.n[u], u0,
                    u1) ||
        !voxelRange(std::min({a[1], b[1], c[1]}), std::max({a[1], b[1], c[1]}), shift[v], grid, grid.n[v], v0,
                    v1))
      continue;
    const double tMin = std::min({p0[axis], p1[axis], p2[axis]});
    const double tMax = std::max({p0[axis], p1[axis], p2[axis]});
    for (std::size_t iv = v0; iv <= v1; ++iv)
      for (std::size_t iu = u0; iu <= u1; ++iu) {
        const double q[2] = {grid.centre(iu) + shift[u], grid.centre(iv) + shift[v]};
        const Side w0 = side(b, c, q);  // weight of p0
        const Side w1 = side(c, a, q);  // weight of p1
        const Side w2 = side(a, b, q);  // weight of p2
        if (w0.positive != w1.positive || w1.positive != w2.positive) continue;
        const double sum = w0.value + w1.value + w2.value;
        if (sum == 0) continue;
        const double hit = (w0.value * p0[axis] + w1.value * p1[axis] + w2.value * p2[axis]) / sum;
        found.push_back({iu + nu * iv, {std::clamp(hit, tMin, tMax), w0.positive ? 1 : -1}});
      }
  }

  // Counting sort by column, then each column's crossings by t.
  std::vector<std::size_t> start(nu * nv + 1, 0);
  for (const ColumnCrossing& f : found) ++start[f.column + 1];
  for (std::size_t i = 1; i < start.size(); ++i) start[i] += start[i - 1];
  std::vector<Crossing> sorted(found.size());
  {
    std::vector<std::size_t> next(start.begin(), start.end() - 1);
    for (const ColumnCrossing& f : found) sorted[next[f.column]++] = f.crossing;
  }
  found.clear();
  found.shrink_to_fit();

  std::vector<Crossing> kept;
  const auto bit = static_cast<std::uint8_t>(1u << axis);
  for (std::size_t column = 0; column + 1 < start.size(); ++column) {
    const auto first = sorted.begin() + static_cast<std::ptrdiff_t>(start[column]);
    const auto last = sorted.begin() + static_cast<std::ptrdiff_t>(start[column + 1]);
    if (first == last) continue;
    std::sort(first, last);
    /* A crossing in the same direction as one kept within `tolerance` before it is the same
       surface crossed twice: a duplicated triangle, or a vertex where rounding put the ray in
       two triangles of the fan. Opposite directions are kept: a fold (silhouette) is crossed
       twice or not at all. */
    kept.clear();
    for (auto it = first; it != last; ++it) {
      bool duplicate = false;
      for (std::size_t j = kept.size(); j-- > 0 && it->t - kept[j].t <= tolerance;)
        if (kept[j].dir == it->dir) {
          duplicate = true;
          break;
        }
      if (!duplicate) kept.push_back(*it);
    }
    std::size_t ijk[3] = {0, 0, 0};
    ijk[u] = column % nu;
    ijk[v] = column / nu;
    std::size_t h = 0;
    for (std::size_t k = 0; k < na; ++k) {
      const double sample = grid.centre(k) + shift[axis];
      while (h < kept.size() && kept[h].t < sample) ++h;
      if (h % 2 == 1) {
        ijk[axis] = k;
        votes[grid.index(ijk[0], ijk[1], ijk[2])] |= bit;
      }
    }
  }
}

using Vec = Eigen::Vector3d;

/// The point of the segment a-b nearest p.
Vec segmentClosestPoint(const Vec& p, const Vec& a, const Vec& b) {
  const Vec ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return a + t * ab;
}

/// The point of the triangle (a, b, c) of normal n = (b - a) × (c - a) ≠ 0 nearest p.
Vec triangleClosestPoint(const Vec& p, const Vec& a, const Vec& b, const Vec& c, const Vec& n) {
  if ((b - a).cross(p - a).dot(n) >= 0 && (c - b).cross(p - b).dot(n) >= 0 &&
      (a - c).cross(p - c).dot(n) >= 0)
    return p - ((p - a).dot(n) / n.squaredNorm()) * n;
  Vec best = segmentClosestPoint(p, a, b);
  for (const Vec& q : {segmentClosestPoint(p, b, c), segmentClosestPoint(p, c, a)})
    if ((q - p).squaredNorm() < (best - p).squaredNorm()) best = q;
  return best;
}

/// A marked voxel's nearest surface point facing each way: bin 2k + (n_k < 0) for the
/// normals n whose largest component is along axis k (`has` bit per bin).
struct SurfacePoints {
  std::array<Vec, 6> at;
  std::array<double, 6> distance2{};
  std::uint8_t has = 0;
  /// The nearest of them.
  [[nodiscard]] const Vec& nearest() const {
    int best = -1;
    for (int b = 0; b < 6; ++b)
      if ((has >> b & 1) && (best < 0 || distance2[b] < distance2[best])) best = b;
    return at[best];
  }
};
/// Each marked voxel's surface points (markSurface), by voxel index.
using NearestPoints = std::unordered_map<std::size_t, SurfacePoints>;

/// Marks the voxels whose centre lies within spacing/2 of a usable triangle. For each triangle
/// only the columns along its most normal axis are walked, and in each only the few voxels
/// near the triangle's plane: the cost follows the triangle's area, not its bounding box.
void markSurface(const Grid& grid, const std::vector<Point>& local,
                 const std::vector<std::array<std::uint32_t, 3>>& triangles, const std::vector<bool>& usable,
                 std::vector<std::uint8_t>& marks, NearestPoints* nearest = nullptr) {
  const double s = grid.spacing;
  const double reach = 0.5 * s;
  const double reach2 = reach * reach * (1 + 1e-9);  // a centre exactly spacing/2 away counts
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    if (!usable[t]) continue;
    const Vec a(local[triangles[t][0]].data());
    const Vec b(local[triangles[t][1]].data());
    const Vec c(local[triangles[t][2]].data());
    const Vec n = (b - a).cross(c - a);
    int d = 0;
    for (int k = 1; k < 3; ++k)
      if (std::abs(n[k]) > std::abs(n[d])) d = k;
    const int u = (d + 1) % 3;
    const int v = (d + 2) % 3;
    const Vec lo = a.cwiseMin(b).cwiseMin(c).array() - reach;
    const Vec hi = a.cwiseMax(b).cwiseMax(c).array() + reach;
    std::size_t r[3][2];
    bool empty = false;
    for (int k = 0; k < 3; ++k)
      empty = empty || !voxelRange(lo[k], hi[k], 0, grid, grid.n[k], r[k][0], r[k][1]);
    if (empty) continue;
    const double slab = reach * n.norm() / std::abs(n[d]);  // |Δ along d| of points within reach of the plane
    for (std::size_t iv = r[v][0]; iv <= r[v][1]; ++iv)
      for (std::size_t iu = r[u][0]; iu <= r[u][1]; ++iu) {
        Vec p;
        p[u] = grid.centre(iu);
        p[v] = grid.centre(iv);
        const double onPlane = a[d] - (n[u] * (p[u] - a[u]) + n[v] * (p[v] - a[v])) / n[d];
        std::size_t k0 = 0, k1 = 0;
        if (!voxelRange(std::max(onPlane - slab, lo[d]), std::min(onPlane + slab, hi[d]), 0, grid, grid.n[d],
                        k0, k1))
          continue;
        for (std::size_t k = k0; k <= k1; ++k) {
          p[d] = grid.centre(k);
          const Vec q = triangleClosestPoint(p, a, b, c, n);
          const double d2 = (q - p).squaredNorm();
          if (d2 > reach2) continue;
          std::size_t ijk[3];
          ijk[d] = k;
          ijk[u] = iu;
          ijk[v] = iv;
          const std::size_t i = grid.index(ijk[0], ijk[1], ijk[2]);
          marks[i] = 1;
          if (nearest != nullptr) {
            SurfacePoints& points = (*nearest)[i];
            const int bin = 2 * d + (n[d] < 0 ? 1 : 0);
            if (!(points.has >> bin & 1) || d2 < points.distance2[bin]) {
              points.at[bin] = q;
              points.distance2[bin] = d2;
              points.has |= static_cast<std::uint8_t>(1 << bin);
            }
          }
        }
      }
  }
}

}  // namespace

std::uint64_t meshFillBound(const TriangleMesh& mesh, double spacing) {
  constexpr auto kMax = std::numeric_limits<std::uint64_t>::max();
  if (mesh.vertices.empty()) return 0;
  if (!(spacing > 0) || !std::isfinite(spacing)) return kMax;
  const Aabb box = mesh.bounds();
  double product = 1;
  std::uint64_t exact = 1;
  for (int a = 0; a < 3; ++a) {
    const double cells = cellsAlong(box.hi[a] - box.lo[a], spacing);
    product *= cells;
    if (!(product < 1e19)) return kMax;  // also catches NaN and infinity
    exact *= static_cast<std::uint64_t>(cells);
  }
  return exact;
}

MeshFillResult fillMesh(const TriangleMesh& mesh, const MeshFillOptions& options) {
  const double s = options.spacing;
  if (!(s > 0) || !std::isfinite(s))
    throw InputError({"", 0, "spacing"}, fmt::format("{} is not a usable particle spacing", s),
                     "a finite length > 0, the particle diameter in scene units");
  if (mesh.triangles.empty() || mesh.vertices.empty())
    throw InputError({"", 0, "mesh"}, "the mesh has no triangles to fill",
                     "a mesh with at least one triangle");
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
    if (!mesh.vertices[i].allFinite())
      throw InputError({"", 0, "mesh"}, fmt::format("vertex {} is not finite", i), "finite coordinates");
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (std::uint32_t index : mesh.triangles[t])
      if (index >= mesh.vertices.size())
        throw InputError({"", 0, "mesh"},
                         fmt::format("triangle {} uses vertex {} of {}", t, index, mesh.vertices.size()),
                         "vertex indices below the vertex count");
  const std::uint64_t bound = meshFillBound(mesh, s);
  if (bound > options.maxParticles) {
    const Aabb box = mesh.bounds();
    throw InputError(
        {"", 0, "spacing"},
        fmt::format("filling the mesh's {:g} × {:g} × {:g} box at spacing {:g} needs a grid of {} voxels",
                    box.hi[0] - box.lo[0], box.hi[1] - box.lo[1], box.hi[2] - box.lo[2], s,
                    bound == std::numeric_limits<std::uint64_t>::max() ? std::string("too many")
                                                                       : std::to_string(bound)),
        fmt::format("at most {} particles: a larger spacing, or a higher cap (--max-particles)",
                    options.maxParticles));
  }

  Grid grid;
  grid.spacing = s;
  const Aabb box = mesh.bounds();
  double extent = 0;
  for (int a = 0; a < 3; ++a) {
    grid.lo[a] = box.lo[a];
    grid.n[a] = static_cast<std::uint64_t>(cellsAlong(box.hi[a] - box.lo[a], s));
    // A mesh at most one spacing thick along an axis gets its one layer of voxels
    // centred in it: from the low face, the centres lay s/2 off it, outside a part
    // thinner than that, and a rod thin along two axes (4 x 0.02 x 0.02 at spacing 0.2)
    // had neither an inside voxel nor a surface sample, and became one particle.
    if (grid.n[a] == 1) grid.lo[a] = 0.5 * (box.lo[a] + box.hi[a]) - 0.5 * s;
    extent = std::max(extent, box.hi[a] - box.lo[a]);
  }
  std::vector<Point> local(mesh.vertices.size());
  for (std::size_t i = 0; i < local.size(); ++i)
    for (int a = 0; a < 3; ++a) local[i][static_cast<std::size_t>(a)] = mesh.vertices[i][a] - grid.lo[a];

  MeshFillResult result;
  result.testedVoxels = grid.voxels();
  std::vector<bool> usable(mesh.triangles.size());
  std::size_t zeroArea = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    const Vec3& a = mesh.vertices[tri[0]];
    usable[t] = (mesh.vertices[tri[1]] - a).cross(mesh.vertices[tri[2]] - a).squaredNorm() > 0;
    if (!usable[t]) ++zeroArea;
  }
  if (zeroArea == mesh.triangles.size()) {
    result.warnings.push_back(
        fmt::format("all {} triangles have zero area: there is no surface to fill", zeroArea));
    return result;
  }
  if (zeroArea > 0)
    result.warnings.push_back(fmt::format("{} of the {} triangles have zero area and were skipped", zeroArea,
                                          mesh.triangles.size()));

  std::vector<std::uint8_t> cells(grid.voxels(), 0);
  std::uint64_t anyInside = 0;
  if (options.surfaceOnly) {
    markSurface(grid, local, mesh.triangles, usable, cells);
  } else {
    const double tolerance = 1e-9 * (extent + s);
    for (int axis = 0; axis < 3; ++axis)
      castAxis(axis, grid, local, mesh.triangles, usable, tolerance, cells);
    for (std::uint8_t& votes : cells) {
      const int count = std::popcount(votes);
      if (count > 0) ++anyInside;
      if (count == 1 || count == 2) ++result.votedVoxels;
      votes = count >= 2 ? 1 : 0;
    }
    if (options.thinParts) {
      // A part thinner than the spacing holds few lattice points or none: a flat one
      // none, one modelled at an angle a scattered few (about area × thickness / s³).
      // A surface sample (a voxel centre within s/2 of a triangle) is added where the
      // part is thin, a sample nearby facing the other way (the part's other side,
      // within 1.5 s), and where the surface point nearest it is not already covered by
      // an inside voxel within 0.9 s (then no particle of this size passes there). So a
      // thick part gets none, even where its lattice stops short of a face or an edge.
      std::vector<std::uint8_t> surface(grid.voxels(), 0);
      NearestPoints nearest;
      markSurface(grid, local, mesh.triangles, usable, surface, &nearest);
      const double cover2 = 0.81 * s * s, across2 = 2.25 * s * s;
      const auto wanted = [&](std::size_t x, std::size_t y, std::size_t z, const SurfacePoints& here) {
        const Vec& q = here.nearest();
        // Faces of both senses along one axis: those within s/2 of this voxel, or, for
        // the other sense, within 1.5 s of its nearest point in a neighbouring voxel.
        bool thinHere = false;
        for (int k = 0; k < 3; ++k) thinHere = thinHere || (here.has >> (2 * k) & 3) == 3;
        for (std::size_t c = z > 0 ? z - 1 : 0; c <= std::min<std::size_t>(z + 1, grid.n[2] - 1); ++c)
          for (std::size_t b = y > 0 ? y - 1 : 0; b <= std::min<std::size_t>(y + 1, grid.n[1] - 1); ++b)
            for (std::size_t a = x > 0 ? x - 1 : 0; a <= std::min<std::size_t>(x + 1, grid.n[0] - 1); ++a) {
              const std::size_t j = grid.index(a, b, c);
              if (cells[j] == 1 && (Vec(grid.centre(a), grid.centre(b), grid.centre(c)) - q).squaredNorm() <= cover2)
                return false;
              if (!surface[j] || thinHere) continue;
              const SurfacePoints& other = nearest.at(j);
              for (int bin = 0; bin < 6 && !thinHere; ++bin)
                thinHere = (here.has >> bin & 1) && (other.has >> (bin ^ 1) & 1) &&
                           (other.at[bin ^ 1] - here.at[bin]).squaredNorm() <= across2;
            }
        return thinHere;
      };
      // Marked 2 (not 1) so that one added sample does not count as covering others.
      for (std::size_t z = 0; z < grid.n[2]; ++z)
        for (std::size_t y = 0; y < grid.n[1]; ++y)
          for (std::size_t x = 0; x < grid.n[0]; ++x) {
            const std::size_t i = grid.index(x, y, z);
            if (surface[i] && cells[i] == 0 && wanted(x, y, z, nearest.at(i))) {
              cells[i] = 2;
              ++result.thinVoxels;
            }
          }
    }
  }

  std::size_t total = 0;
  for (std::uint8_t c : cells) total += c != 0 ? 1 : 0;
  result.points.reserve(total);
  for (std::size_t z = 0; z < grid.n[2]; ++z)
    for (std::size_t y = 0; y < grid.n[1]; ++y)
      for (std::size_t x = 0; x < grid.n[0]; ++x)
        if (cells[grid.index(x, y, z)])
          result.points.emplace_back(grid.lo[0] + grid.centre(x), grid.lo[1] + grid.centre(y),
                                     grid.lo[2] + grid.centre(z));

  if (!options.surfaceOnly) {
    if (result.votedVoxels * 100 > anyInside)
      result.warnings.push_back(fmt::format(
          "the three ray directions disagree on {:.0f}% of the {} voxels any of them found inside: the mesh "
          "is "
          "probably not closed (holes or missing faces); the majority of the three was kept",
          100.0 * static_cast<double>(result.votedVoxels) / static_cast<double>(anyInside), anyInside));
    if (result.points.empty())
      result.warnings.push_back(
          "no lattice point lies inside the mesh: it may be open, double-sided or thinner than the spacing "
          "(a surface fill, --surface or <Surface>true</Surface>, samples the surface instead)");
  }
  return result;
}

}  // namespace softsub::geometry

namespace softsub::geometry {

namespace {

/// Integer cell coordinates packed 21 bits an axis into one hash key (coordinates wrap:
/// cells 2 million apart share a key).
std::uint64_t cellKey(long x, long y, long z) {
  return (static_cast<std::uint64_t>(x & 0x1FFFFF) << 42) | (static_cast<std::uint64_t>(y & 0x1FFFFF) << 21) |
         static_cast<std::uint64_t>(z & 0x1FFFFF);
}

}  // namespace

std::vector<Vec3> latticeShell(const std::vector<Vec3>& points, double spacing, int layers) {
  if (points.empty()) return {};
  Vec3 lo = points.front();
  for (const Vec3& p : points) lo = lo.cwiseMin(p);
  // A wrapped key (cellKey) can only make a site look occupied, which at worst drops a
  // shell point of a fill over 2 million steps wide.
  const auto key = cellKey;
  std::vector<std::array<long, 3>> cells(points.size());
  std::unordered_set<std::uint64_t> occupied;
  occupied.reserve(points.size() * 2);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3 q = (points[i] - lo) / spacing;
    cells[i] = {std::lround(q.x()), std::lround(q.y()), std::lround(q.z())};
    occupied.insert(key(cells[i][0], cells[i][1], cells[i][2]));
  }
  std::vector<Vec3> out;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& c = cells[i];
    bool shell = false;
    for (int axis = 0; axis < 3 && !shell; ++axis)
      for (int step = -layers; step <= layers && !shell; ++step) {
        if (step == 0) continue;
        std::array<long, 3> n = c;
        n[axis] += step;
        if (n[0] < 0 || n[1] < 0 || n[2] < 0 || !occupied.contains(key(n[0], n[1], n[2]))) shell = true;
      }
    if (shell) out.push_back(points[i]);
  }
  return out;
}

std::vector<SurfaceFaces> surfaceFaces(const TriangleMesh& mesh, const std::vector<Vec3>& points, double radius,
                                       double toleranceDegrees, bool closed) {
  std::vector<SurfaceFaces> out(points.size());
  if (points.empty() || mesh.triangles.empty() || !(radius > 0) || !std::isfinite(radius)) return out;
  // Triangles bucketed by the cubes of side `radius` their box overlaps: the triangles
  // within `radius` of a point lie in the 27 cubes around the point's own.
  const Aabb box = mesh.bounds();
  const Vec lo(box.lo[0], box.lo[1], box.lo[2]);
  const Vec mid = 0.5 * (lo + Vec(box.hi[0], box.hi[1], box.hi[2]));
  const auto cube = [&](const Vec& p, int k) { return static_cast<long>(std::floor((p[k] - lo[k]) / radius)); };
  const auto key = cellKey;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cubes;
  std::vector<Vec> unit(mesh.triangles.size(), Vec::Zero());
  double volume = 0;  // six times the signed volume: its sign says which way the winding faces
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    if (tri[0] >= mesh.vertices.size() || tri[1] >= mesh.vertices.size() || tri[2] >= mesh.vertices.size()) continue;
    const Vec a = mesh.vertices[tri[0]], b = mesh.vertices[tri[1]], c = mesh.vertices[tri[2]];
    volume += (a - mid).dot((b - mid).cross(c - mid));
    const Vec n = (b - a).cross(c - a);
    if (!(n.squaredNorm() > 0) || !n.allFinite()) continue;
    unit[t] = n.normalized();
    const Vec tlo = a.cwiseMin(b).cwiseMin(c), thi = a.cwiseMax(b).cwiseMax(c);
    for (long z = cube(tlo, 2); z <= cube(thi, 2); ++z)
      for (long y = cube(tlo, 1); y <= cube(thi, 1); ++y)
        for (long x = cube(tlo, 0); x <= cube(thi, 0); ++x) {
          // Only the cubes the triangle's plane passes through (a large slanted face's
          // box holds many it does not).
          const Vec centre =
              lo + radius * (Vec(static_cast<double>(x), static_cast<double>(y), static_cast<double>(z)).array() + 0.5)
                                .matrix();
          if (std::abs(unit[t].dot(centre - a)) > radius) continue;  // > half the cube's diagonal: misses it
          cubes[key(x, y, z)].push_back(static_cast<std::uint32_t>(t));
        }
  }
  const double outward = closed && volume != 0 ? (volume > 0 ? 1.0 : -1.0) : 0.0;
  const double cosTolerance = std::cos(toleranceDegrees * std::numbers::pi / 180.0);
  const double cosEdge = std::cos(30 * std::numbers::pi / 180.0);  // planes meeting at less are a curve
  const double radius2 = radius * radius;
  struct Plane {
    Vec first, nearest;
    double nearest2 = 0;
    bool bothWays = false;
  };
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec p = points[i];
    if (!p.allFinite()) continue;
    const long cx = cube(p, 0), cy = cube(p, 1), cz = cube(p, 2);
    std::array<Plane, SurfaceFaces::kMax> planes;
    int count = 0;
    bool curved = false;
    for (long z = cz - 1; z <= cz + 1 && !curved; ++z)
      for (long y = cy - 1; y <= cy + 1 && !curved; ++y)
        for (long x = cx - 1; x <= cx + 1 && !curved; ++x) {
          const auto found = cubes.find(key(x, y, z));
          if (found == cubes.end()) continue;
          for (const std::uint32_t t : found->second) {
            const auto& tri = mesh.triangles[t];
            const Vec a = mesh.vertices[tri[0]], b = mesh.vertices[tri[1]], c = mesh.vertices[tri[2]];
            const double d2 = (triangleClosestPoint(p, a, b, c, (b - a).cross(c - a)) - p).squaredNorm();
            if (d2 > radius2) continue;
            int g = 0;
            while (g < count && std::abs(unit[t].dot(planes[g].first)) < cosTolerance) ++g;
            if (g == count) {
              if (count == SurfaceFaces::kMax) {
                curved = true;
                break;
              }
              planes[count++] = {unit[t], unit[t], d2, false};
              continue;
            }
            Plane& plane = planes[g];
            plane.bothWays = plane.bothWays || unit[t].dot(plane.first) < 0;
            if (d2 < plane.nearest2) {
              plane.nearest2 = d2;
              plane.nearest = unit[t];
            }
          }
        }
    for (int g = 0; g < count && !curved; ++g)
      for (int h = g + 1; h < count; ++h) curved = curved || std::abs(planes[g].first.dot(planes[h].first)) > cosEdge;
    if (curved) continue;
    SurfaceFaces& faces = out[i];
    faces.count = static_cast<std::uint8_t>(count);
    for (int g = 0; g < count; ++g) {
      const bool oneWay = outward != 0 && !planes[g].bothWays;
      faces.normal[g] = oneWay ? Vec(outward * planes[g].nearest) : planes[g].nearest;
      faces.sides[g] = oneWay ? 1 : 2;
    }
  }
  return out;
}

}  // namespace softsub::geometry
