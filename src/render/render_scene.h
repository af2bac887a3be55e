#pragma once
/// What the renderer draws besides the particles of a frame: the container, the floor,
/// and the rigid bodies' meshes. Built once per scene (app/scene_view.cpp) and kept.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace softsub::render {

/// A rigid body's triangles in its geometry's own axes; the frame's ObjectSnapshot of the
/// same name places it (scale, rotation, translation).
struct RenderMesh {
  std::string name;
  std::vector<std::array<float, 3>> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::array<float, 3> colour{0.72f, 0.74f, 0.78f};
};

/// The container box: walls at lo/hi on x and z, the floor at lo[1], a lid if closed.
struct RenderContainer {
  std::array<float, 3> lo{-10, 0, -10};
  std::array<float, 3> hi{10, 20, 10};
  bool closed = false;
};

/// One fluid's surface in one frame (scene units, per-vertex unit normals, triangles
/// counter-clockwise from outside), e.g. from softsub::surface. The renderer draws it in
/// the fluid's colour instead of that fluid's particles.
struct RenderSurface {
  std::size_t fluid = 0;  ///< index into the frame's fluids
  std::vector<std::array<float, 3>> vertices;
  std::vector<std::array<float, 3>> normals;  ///< one per vertex
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

/// Everything static the renderer needs.
struct RenderScene {
  std::optional<RenderContainer> container;  ///< absent: no walls, no floor
  bool reflective = false;                   ///< mirror the scene in the floor
  std::vector<RenderMesh> meshes;            ///< one per object, by name
};

}  // namespace softsub::render
