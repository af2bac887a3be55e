#include "scene_source.h"

#include "cache/naming.h"
#include "core/error.h"
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
    out.file = out.name + ".scene";
    out.desc = scene::readSceneText(softsub_default_scene, out.name + ".scene", options);
    out.defaultOutDir = out.name + "Sim";
    return out;
  }
  const std::filesystem::path file(path);
  out.desc = scene::readSceneFile(path, options);
  out.name = file.stem().string();
  out.file = path;
  out.defaultOutDir = file.parent_path() / (out.name + "Sim");
  return out;
}

void checkOutputName(std::string_view name, std::string_view element, const std::string& file) {
  try {
    cache::checkFileNamePart(name, element);
  } catch (const InputError& e) {
    if (!e.where().file.empty()) throw;
    throw InputError({file, 0, e.where().element}, e.problem(), e.allowed());
  }
}

void checkOutputNames(const LoadedScene& loaded, const cache::Formats& formats, bool sceneNamesFiles) {
  if (sceneNamesFiles) checkOutputName(loaded.name, "scene name", loaded.file);
  if (formats.pdc || formats.mesh || formats.vdb)
    for (const scene::FluidDesc& f : loaded.desc.fluids) checkOutputName(f.name, "Fluid/Name", loaded.file);
  if (formats.sim)
    for (const scene::ObjectDesc& obj : loaded.desc.objects)
      checkOutputName(obj.name, "Object/Name", loaded.file);
}

}  // namespace softsub::app
