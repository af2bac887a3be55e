#pragma once
/// Reading triangle meshes from the files artists export (OBJ, PLY, STL, glTF, FBX and
/// the other formats assimp reads), checked at the boundary so the rest of the code can
/// trust the mesh.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/triangle_mesh.h"

namespace softsub::geometry {

/// What loadMesh repaired or left out, for the caller to show the user.
struct MeshLoadReport {
  std::vector<std::string> warnings;  ///< one line each, without the file name
  std::size_t droppedTriangles = 0;   ///< degenerate or with out-of-range indices
};

/// How a mesh's edges are shared (an edge: an unordered pair of vertices of a triangle).
struct MeshEdges {
  std::size_t boundary = 0;     ///< used by one triangle only: the mesh is not closed there
  std::size_t nonManifold = 0;  ///< used by more than two triangles
};

/// Counts the boundary and non-manifold edges of mesh (indices must be in range).
[[nodiscard]] MeshEdges countEdges(const TriangleMesh& mesh);

/// Turns triangles wound against their neighbours so that every edge two triangles share
/// runs opposite ways in them (the condition for a closed surface to enclose a volume),
/// one connected part of the mesh (through such edges) at a time, keeping the winding
/// most of that part's triangles have (on a tie, its first triangle's). A part that
/// cannot be oriented (a Moebius strip) is left as it is. Returns the number of
/// triangles turned.
std::size_t orientConsistently(TriangleMesh& mesh);

/// The warning for a volume fill of a mesh with boundary edges, "" when it has none.
[[nodiscard]] std::string openMeshWarning(const MeshEdges& edges);

/// OBJ text as loadMesh hands it to assimp: without a UTF-8 byte-order mark (assimp
/// took it for part of the first line and lost the first vertex), without a comment
/// after the data of a `v`, `vt`, `vn`, `f`, `l` or `p` line (assimp refused
/// `f 1 2 3 # a note`), and without the fourth number of a `v x y z w` line (w weighs
/// the control points of rational curves; Blender and Maya ignore it on polygon
/// vertices, assimp divided the position by it), and without a line's indentation
/// (assimp skipped an indented line, which shifted the vertex numbers after it: a
/// silent misreading). The rest of a line continued with a backslash, every other
/// character, and every line ending are kept as they are.
[[nodiscard]] std::string objForAssimp(std::string_view text);

/// Files larger than this are refused before anything is read.
inline constexpr std::uintmax_t kMaxMeshFileBytes = std::uintmax_t{1} << 30;

/// Reads every mesh of the file's scene into one triangle mesh, each placed by its
/// node's transform (instanced meshes appear once per node). Polygons are triangulated;
/// points and lines are ignored; vertices at exactly the same position are merged, so a
/// closed surface exported with per-face normals or as STL comes back closed. Triangles
/// with a repeated vertex, zero area or an out-of-range index are dropped and counted in
/// `report`, as are edges shared by more than two triangles (non-manifold: kept, with a
/// warning). Vertices no triangle uses are removed. A mirroring node transform has its
/// triangles' winding reversed so orientation is kept. Triangles wound against their
/// neighbours are turned (orientConsistently), with a warning in `report`: a closed
/// mesh with one flipped face is closed, and a body's volume and inertia need its
/// faces to agree. A closed mesh whose whole volume is negative (wound inward) is turned
/// outward, with a warning.
///
/// Throws IoError when the file cannot be opened or read (message names the file and the
/// reason); InputError {file, 0, "mesh"} when the file is larger than
/// kMaxMeshFileBytes, when assimp cannot parse it (assimp's message), when a vertex is
/// NaN or infinite (names the vertex), or when no triangle is left.
///
/// `confineTo` (a scene's folder; empty: anywhere): the files the mesh itself refers to
/// (a glTF's buffers, an OBJ's material library) are read only inside it. A refused one
/// is an InputError naming it when the mesh cannot be read without it, and a warning in
/// `report` when it can (an OBJ without its materials).
[[nodiscard]] TriangleMesh loadMesh(const std::filesystem::path& file, MeshLoadReport* report = nullptr,
                                    const std::filesystem::path& confineTo = {});

}  // namespace softsub::geometry
