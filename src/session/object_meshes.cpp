#include "session/object_meshes.h"

#include <stdexcept>

namespace softsub::session {

cache::ObjectMesh toObjectMesh(const std::string& name, const geometry::TriangleMesh& mesh) {
  cache::ObjectMesh out;
  out.name = name;
  out.vertices.reserve(mesh.vertices.size());
  for (const Vec3& v : mesh.vertices) out.vertices.push_back({v.x(), v.y(), v.z()});
  out.triangles.assign(mesh.triangles.begin(), mesh.triangles.end());
  return out;
}

std::vector<cache::ObjectMesh> objectMeshesForCache(solver::Model& model,
                                                    const std::vector<geometry::TriangleMesh>& meshes,
                                                    const std::string& sceneName) {
  auto& bodies = model.bodies.bodies;
  if (meshes.size() != bodies.size())
    throw std::invalid_argument("objectMeshesForCache: one mesh per body expected");
  std::vector<cache::ObjectMesh> out;
  out.reserve(bodies.size());
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    bodies[b].geometryFile = cache::geometryFileName(sceneName, bodies[b].name);
    out.push_back(toObjectMesh(bodies[b].name, meshes[b]));
  }
  return out;
}

}  // namespace softsub::session
