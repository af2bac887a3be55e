#pragma once
/// What the renderer needs from a scene (container, floor, meshes, camera), and a
/// picture maker on an off-screen context shared by `render`, `run --preview` and `view`.
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/snapshot.h"
#include "geometry/triangle_mesh.h"
#include "render/camera.h"
#include "render/image.h"
#include "render/render_scene.h"
#include "scene/scene_desc.h"
#include "surface/surface.h"

namespace softsub::render {
class OffscreenContext;
class Renderer;
class Framebuffer;
}  // namespace softsub::render

namespace softsub::app {

/// A rigid body's mesh for drawing.
[[nodiscard]] render::RenderMesh renderMeshOf(const std::string& name, const geometry::TriangleMesh& mesh);

/// The container and floor of `desc`, and one mesh per object (`meshes[i]` is object i's).
[[nodiscard]] render::RenderScene renderSceneOf(const scene::SceneDesc& desc,
                                                const std::vector<geometry::TriangleMesh>& meshes);

/// The scene's `<Camera>` as the renderer's camera.
[[nodiscard]] render::Camera cameraOf(const scene::CameraDesc& camera);

/// Each non-empty fluid's surface in `frame` (softsub::surface's blobby level set, at its
/// particle size), for drawing instead of the particles.
[[nodiscard]] std::vector<render::RenderSurface> surfacesOf(const FrameSnapshot& frame,
                                                           const surface::SurfaceSettings& settings = {});

/// Draws frames into pictures off-screen (EGL), all of one size.
class PictureMaker {
 public:
  /// Makes the context; IoError when the system cannot draw off-screen.
  PictureMaker(const render::RenderScene& scene, int width, int height);
  ~PictureMaker();
  PictureMaker(const PictureMaker&) = delete;
  PictureMaker& operator=(const PictureMaker&) = delete;

  /// The frame seen by `camera`; `surfaces` replace their fluids' particles.
  [[nodiscard]] render::Image draw(const FrameSnapshot& frame, const render::Camera& camera,
                                   std::span<const render::RenderSurface> surfaces = {});
  /// Draws and writes a PNG atomically (IoError when it cannot be written).
  void write(const std::filesystem::path& path, const FrameSnapshot& frame, const render::Camera& camera,
             std::span<const render::RenderSurface> surfaces = {});
  /// The OpenGL implementation in use ("llvmpipe ..., OpenGL 4.5 ...").
  [[nodiscard]] std::string description() const;

 private:
  std::unique_ptr<render::OffscreenContext> context_;
  std::unique_ptr<render::Renderer> renderer_;
  std::unique_ptr<render::Framebuffer> target_;
  int width_, height_;
};

}  // namespace softsub::app
