#include "scene_view.h"

#include "cache/atomic_file.h"
#include "render/offscreen.h"
#include "render/renderer.h"
#include "surface/surface.h"
#include "surface/surface_writer.h"

namespace softsub::app {

render::RenderMesh renderMeshOf(const std::string& name, const geometry::TriangleMesh& mesh) {
  render::RenderMesh out;
  out.name = name;
  out.vertices.reserve(mesh.vertices.size());
  for (const Vec3& v : mesh.vertices)
    out.vertices.push_back({static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())});
  out.triangles = mesh.triangles;
  return out;
}

render::RenderScene renderSceneOf(const scene::SceneDesc& desc, const std::vector<geometry::TriangleMesh>& meshes) {
  render::RenderScene out;
  if (desc.environment) {
    const scene::EnvironmentDesc& e = *desc.environment;
    render::RenderContainer c;
    c.lo = {static_cast<float>(-0.5 * e.width), 0.0f, static_cast<float>(-0.5 * e.depth)};
    c.hi = {static_cast<float>(0.5 * e.width), static_cast<float>(e.height), static_cast<float>(0.5 * e.depth)};
    c.closed = e.closed;
    out.container = c;
    out.reflective = e.reflective;
  }
  for (std::size_t i = 0; i < desc.objects.size() && i < meshes.size(); ++i)
    out.meshes.push_back(renderMeshOf(desc.objects[i].name, meshes[i]));
  return out;
}

render::Camera cameraOf(const scene::CameraDesc& camera) {
  render::Camera c;
  c.eye = camera.eye;
  c.pitch = camera.verticalAngle;
  c.yaw = camera.horizontalAngle;
  return c;
}

PictureMaker::PictureMaker(const render::RenderScene& scene, int width, int height)
    : context_(std::make_unique<render::OffscreenContext>()),
      renderer_(std::make_unique<render::Renderer>()),
      target_(std::make_unique<render::Framebuffer>(width, height)),
      width_(width),
      height_(height) {
  renderer_->setScene(scene);
}

PictureMaker::~PictureMaker() {
  // GL objects go before their context.
  target_.reset();
  renderer_.reset();
}

render::Image PictureMaker::draw(const FrameSnapshot& frame, const render::Camera& camera,
                                 std::span<const render::RenderSurface> surfaces) {
  target_->bind();
  renderer_->draw(frame, camera, width_, height_, {}, surfaces);
  return target_->read();
}

void PictureMaker::write(const std::filesystem::path& path, const FrameSnapshot& frame, const render::Camera& camera,
                         std::span<const render::RenderSurface> surfaces) {
  cache::writeFileAtomic(path, render::encodePng(draw(frame, camera, surfaces)));
}

std::vector<render::RenderSurface> surfacesOf(const FrameSnapshot& frame, const surface::SurfaceSettings& settings) {
  surface::checkGridReach(frame, settings);  // a clear error, not the grid's internal one
  std::vector<render::RenderSurface> out;
  for (std::size_t i = 0; i < frame.fluids.size(); ++i) {
    const FluidSnapshot& f = frame.fluids[i];
    if (f.count() == 0) continue;
    surface::SurfaceMesh m = surface::meshParticles(f.positions, f.particleSize, settings);
    render::RenderSurface s;
    s.fluid = i;
    s.vertices = std::move(m.vertices);
    s.normals = std::move(m.normals);
    s.triangles = std::move(m.triangles);
    out.push_back(std::move(s));
  }
  return out;
}

std::string PictureMaker::description() const { return context_->description(); }

}  // namespace softsub::app
