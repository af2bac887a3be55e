#pragma once
/// Mesh → particles (the seed's "convert to particles", report 2.2.3): lattice points of a
/// voxel grid of the particle diameter, inside a mesh by ray parity, or on its surface.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/math.h"
#include "geometry/triangle_mesh.h"

namespace softsub::geometry {

/// How to fill a mesh with particles.
struct MeshFillOptions {
  double spacing = 1;        ///< lattice step = particle diameter, scene units, > 0
  bool surfaceOnly = false;  ///< sample the surface instead of the volume (thin shells, open meshes)
  /// Volume fill: also keep the surface samples (as surfaceOnly makes them) that have no
  /// inside voxel among their 26 neighbours: the parts of the mesh thinner than about one
  /// spacing (a lid, a blade, a handle), which hold no lattice point of their own.
  bool thinParts = false;
  std::uint64_t maxParticles = 20'000'000;  ///< refuse (InputError) before allocating more voxels than this
};

/// The particles of a fill and what the fill noticed about the mesh.
struct MeshFillResult {
  std::vector<Vec3> points;        ///< lattice points inside (or on the surface), x fastest, then y, then z
  std::uint64_t votedVoxels = 0;   ///< voxels where the three ray directions did not all agree (volume fill)
  std::uint64_t testedVoxels = 0;  ///< voxels of the grid
  std::uint64_t thinVoxels = 0;    ///< points added by MeshFillOptions::thinParts
  std::vector<std::string> warnings;  ///< one sentence each, e.g. the axes disagree: the mesh is not closed
};

/// Voxels of the fill grid (an upper bound of the points a fill can make), from the bounding
/// box, without allocating. Saturates at UINT64_MAX; 0 for a mesh without vertices; UINT64_MAX
/// for a spacing that is not a finite positive number.
std::uint64_t meshFillBound(const TriangleMesh& mesh, double spacing);

/// Fills `mesh` with lattice points of step options.spacing over its bounding box: voxel k
/// of an axis has its centre at lo + (k + 0.5)·spacing. Volume fill: a centre is inside when
/// at least two of the rays cast along +x, +y and +z through it have crossed the surface an
/// odd number of times before reaching it (meshes from the wild are not closed; the result
/// warns when the directions disagree on more than 1% of the voxels). Surface fill: centres
/// within spacing/2 of a triangle. Zero-area triangles are skipped; the triangles' orientation
/// does not matter. Throws InputError for an empty mesh, an index out of range, a non-finite
/// vertex, a spacing that is not > 0, or a grid of more than options.maxParticles voxels.
MeshFillResult fillMesh(const TriangleMesh& mesh, const MeshFillOptions& options);

}  // namespace softsub::geometry

namespace softsub::geometry {

/// The points of a lattice fill (step `spacing`) that lie within `layers` lattice steps of
/// an empty lattice site along x, y or z: the outer shell of a solid fill. A rigid body
/// keeps only its shell: interior particles never touch anything. Order is kept.
[[nodiscard]] std::vector<Vec3> latticeShell(const std::vector<Vec3>& points, double spacing, int layers);

/// The flat faces of a mesh near one point (a particle of a rigid body): none where the
/// mesh is curved there (or far), one under a face, two at an edge, three at a corner.
struct SurfaceFaces {
  static constexpr int kMax = 3;
  /// Unit normals, the nearest triangle's of each face.
  std::array<Vec3, kMax> normal{};
  /// Per face: 1 the normal points out of the solid (a closed mesh, the face's triangles
  /// near the point all facing one way); 2 either way (a part thin enough that both of
  /// its sides are near the point, or an open mesh, which has no inside).
  std::array<std::uint8_t, kMax> sides{};
  std::uint8_t count = 0;
};

/// The flat faces within `radius` of each point: the triangles within `radius` fall into
/// at most three planes, each within `toleranceDegrees` of its first triangle (either
/// sense: a thin plate's two sides are one plane), and the planes meet at 30 degrees or
/// more (an edge, a corner). Otherwise (more planes, or planes meeting at a shallow angle:
/// a curved surface's facets, a primitive sphere's 11.25 degree segments) or with no
/// triangle within `radius`, the point has none. `closed`: the mesh is closed and wound
/// consistently (meshMassProperties accepts it), so its winding tells outside from
/// inside (either winding: the sign of its volume says which). Zero-area triangles are
/// skipped.
[[nodiscard]] std::vector<SurfaceFaces> surfaceFaces(const TriangleMesh& mesh, const std::vector<Vec3>& points,
                                                     double radius, double toleranceDegrees, bool closed);

}  // namespace softsub::geometry
