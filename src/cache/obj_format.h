#pragma once
/// Wavefront OBJ for the rigid bodies' geometry: written once per run into
/// `<output>/<scene>Geo/<object>.obj`, the file each `.sim` `<Object>` names, so the frame
/// files plus that folder rebuild the animation in any package. The fluids' surfaces
/// (`<output>/mesh/<Fluid>.NNNN.obj`, module surface) use the same encoder with normals.
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace softsub::cache {

/// A triangle mesh as the OBJ writer takes it.
struct ObjectMesh {
  std::string name;                                      ///< the object's name (file and `o` line)
  std::vector<std::array<double, 3>> vertices;           ///< scene units, the geometry's own axes
  std::vector<std::array<std::uint32_t, 3>> triangles;   ///< 0-based indices into vertices
  /// Per-vertex normals: empty (rigid bodies) or one per vertex, then written as `vn`
  /// lines with faces `f a//a b//b c//c`.
  std::vector<std::array<double, 3>> normals;
  /// What the first comment line says after "softsub "; empty: "rigid body geometry".
  std::string comment;
};

/// The OBJ text: a comment, `o name`, one `v x y z` per vertex (shortest round-trip
/// numbers), with normals one `vn x y z` per vertex, one `f a b c` (with normals
/// `f a//a b//b c//c`) per triangle (1-based). Throws std::invalid_argument for an index
/// out of range or a normal count other than 0 or the vertex count.
[[nodiscard]] std::string encodeObj(const ObjectMesh& mesh);

/// Reads back what encodeObj writes (o, v, vn and f lines, faces `f a b c` or with
/// `/`-separated texture and normal indices, of which only the vertex is kept; other lines
/// ignored). Throws InputError naming `fileName` and the line for anything else malformed.
[[nodiscard]] ObjectMesh decodeObj(std::string_view text, const std::string& fileName);

/// `<scene>Geo/<object>.obj`, relative to the output folder: the `.sim` Filename.
[[nodiscard]] std::string geometryFileName(std::string_view sceneName, std::string_view objectName);

}  // namespace softsub::cache
