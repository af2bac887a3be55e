#include "scene_source.h"

#include "scene/reader.h"

// Generated from examples/softsub-demo.scene by cmake/Embed.cmake.
extern const char softsub_default_scene[];

namespace softsub::app {

const char* defaultSceneText() { return softsub_default_scene; }

LoadedScene loadScene(const std::string& path, std::uint64_t maxParticles) {
  scene::ReadOptions options;
  if (maxParticles > 0) options.maxParticles = maxParticles;
  LoadedScene out;
  options.warnings = &out.warnings;
  if (path.empty()) {
    out.name = kDefaultSceneName;
    out.desc = scene::readSceneText(softsub_default_scene, out.name + ".scene", options);
    out.defaultOutDir = out.name + "Sim";
    return out;
  }
  const std::filesystem::path file(path);
  out.desc = scene::readSceneFile(path, options);
  out.name = file.stem().string();
  out.defaultOutDir = file.parent_path() / (out.name + "Sim");
  return out;
}

}  // namespace softsub::app
