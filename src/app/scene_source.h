#pragma once
/// Where `run` gets its scene: a .scene file, or the embedded default scene.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "scene/scene_desc.h"

namespace softsub::app {

/// Name of the embedded default scene (and so of its output folder, `softsub-demoSim`).
inline constexpr const char* kDefaultSceneName = "softsub-demo";

/// The embedded default scene's text (examples/softsub-demo.scene).
const char* defaultSceneText();

/// A read and validated scene with the names its outputs take.
struct LoadedScene {
  scene::SceneDesc desc;               ///< validated description
  std::string name;                    ///< file stem: names the output files
  std::filesystem::path defaultOutDir; ///< <sceneDir>/<name>Sim
  std::vector<std::string> warnings;   ///< the reader's warnings (meshes repaired or not closed)
};

/// Reads and validates `path`, or the embedded default scene when `path` is empty.
/// `maxParticles` 0 keeps the reader's default limit. Throws InputError / IoError.
LoadedScene loadScene(const std::string& path, std::uint64_t maxParticles);

}  // namespace softsub::app
