#pragma once
/// The rigid bodies' geometry as the cache writer takes it, shared by `softsub run` and
/// the viewer's recordings so both write the same `<scene>Geo/<name>.obj` files.
#include <string>
#include <vector>

#include "cache/obj_format.h"
#include "geometry/triangle_mesh.h"
#include "solver/model.h"

namespace softsub::session {

/// Points every body's `.sim` Filename at `<scene>Geo/<name>.obj` (cache::geometryFileName)
/// and returns the meshes to write there: `meshes[b]` (scene::Compiled::objectMeshes) is
/// body b's geometry in its own coordinates. Call before a Simulation refers to `model`.
[[nodiscard]] std::vector<cache::ObjectMesh> objectMeshesForCache(solver::Model& model,
                                                                  const std::vector<geometry::TriangleMesh>& meshes,
                                                                  const std::string& sceneName);

/// One body's geometry as the cache writer takes it.
[[nodiscard]] cache::ObjectMesh toObjectMesh(const std::string& name, const geometry::TriangleMesh& mesh);

}  // namespace softsub::session
