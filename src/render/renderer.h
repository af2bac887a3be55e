#pragma once
/// Draws a frame snapshot with OpenGL 3.3 core: particles as shaded sphere impostors in
/// their fluid's colour and size, the rigid bodies' meshes at their poses, the container,
/// and the floor (mirrored when the scene's environment is Reflective). The same code
/// draws into the viewer's window and into an off-screen framebuffer.
#include <memory>
#include <span>

#include "core/aabb.h"
#include "core/snapshot.h"
#include "render/camera.h"
#include "render/render_scene.h"

namespace softsub::render {

/// What to draw besides the particles.
struct DrawOptions {
  bool container = true;      ///< the container's edges
  bool floor = true;          ///< the floor (and its reflection when reflective)
  bool objects = true;        ///< the rigid bodies' meshes
  float particleScale = 1;    ///< drawn radius = scale * particleSize / 2
};

/// Owns the GL programs and buffers. Construct, use and destroy it with the same OpenGL
/// 3.3 (or later) core context current.
class Renderer {
 public:
  /// Compiles the shaders; std::runtime_error with the driver's log if that fails.
  Renderer();
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Uploads the static part of a scene (meshes, container); replaces the previous one.
  void setScene(const RenderScene& scene);

  /// Draws `frame` seen by `camera` into the currently bound framebuffer, viewport
  /// (0, 0, width, height), clearing it first. The framebuffer needs a depth buffer, and a
  /// stencil buffer for the mirrored floor.
  /// `surfaces` replace their fluids' particles (a fluid may have none: it is drawn as
  /// particles); their vertices count in bounds() like particles.
  void draw(const FrameSnapshot& frame, const Camera& camera, int width, int height,
            const DrawOptions& options = {}, std::span<const RenderSurface> surfaces = {});

  /// The box holding the container and the last drawn frame's particles and objects
  /// (orbit pivot, clip range).
  [[nodiscard]] const Aabb& bounds() const { return bounds_; }

 private:
  struct Gl;
  std::unique_ptr<Gl> gl_;
  RenderScene scene_;
  Aabb bounds_;
};

/// The bounding box of a frame's particles (centres grown by their radius) and object
/// positions, and of the scene's container.
[[nodiscard]] Aabb sceneBounds(const RenderScene& scene, const FrameSnapshot& frame);

}  // namespace softsub::render
