#include "scene_source.h"

#include <system_error>

#include <fmt/format.h>

#include "cache/naming.h"
#include "cache/obj_format.h"
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

namespace {

struct InputMesh {
  std::filesystem::path path;
  int line;
  std::string element;  // as the reader names it
};

// The meshes a scene reads: its objects' and its mesh fills' <Geometry>.
std::vector<InputMesh> inputMeshes(const LoadedScene& loaded) {
  const scene::SceneDesc& desc = loaded.desc;
  const std::filesystem::path base =
      desc.baseDir.empty() ? std::filesystem::path(".") : std::filesystem::path(desc.baseDir);
  std::vector<InputMesh> inputs;
  for (std::size_t k = 0; k < desc.objects.size(); ++k)
    if (const scene::ObjectDesc& o = desc.objects[k]; !o.geometry.empty())
      inputs.push_back({base / o.geometry, o.line, fmt::format("Object[{}]/Geometry", k + 1)});
  for (const scene::FluidDesc& f : desc.fluids)
    for (std::size_t k = 0; k < f.fills.size(); ++k)
      if (f.fills[k].shape == scene::FillShape::Mesh)
        inputs.push_back({base / f.fills[k].geometry, f.fills[k].line,
                          fmt::format("Fluid '{}'/Fill[{}]/Geometry", f.name, k + 1)});
  return inputs;
}

}  // namespace

std::vector<std::filesystem::path> inputFiles(const LoadedScene& loaded) {
  std::vector<std::filesystem::path> files;
  if (std::error_code ec; !loaded.file.empty() && std::filesystem::is_regular_file(loaded.file, ec))
    files.emplace_back(loaded.file);
  for (InputMesh& in : inputMeshes(loaded)) files.push_back(std::move(in.path));
  return files;
}

void checkInputsKept(const LoadedScene& loaded, const cache::Formats& formats,
                     const std::filesystem::path& outDir) {
  namespace fs = std::filesystem;
  const scene::SceneDesc& desc = loaded.desc;
  const std::vector<InputMesh> inputs = inputMeshes(loaded);
  // Both exist (the input was just read): one file, whatever the paths' spelling.
  const auto same = [](const fs::path& a, const fs::path& b) {
    std::error_code ec;
    return fs::equivalent(a, b, ec) && !ec;
  };
  const auto refuse = [&](const InputMesh& in, const fs::path& out) {
    throw InputError(
        {loaded.file, in.line, in.element},
        fmt::format("the mesh '{}' is a file this run would write over ('{}')", in.path.string(),
                    out.string()),
        "another --out (a run writes each object's mesh to <out>/<scene>Geo/<object>.obj), or the "
        "input mesh moved where the run writes nothing");
  };
  // The scene file itself, in a folder the run fills with files named by frame: a
  // scene named like one of them would be replaced (the embedded scene has no file).
  if (std::error_code ec; !loaded.file.empty() && fs::is_regular_file(loaded.file, ec)) {
    const fs::path folder =
        fs::path(loaded.file).parent_path().empty() ? fs::path(".") : fs::path(loaded.file).parent_path();
    for (const char* sub : {"pdc", "ply", "mesh", "vdb", "manifest", "checkpoint"})
      if (same(folder, outDir / sub))
        throw InputError({loaded.file, 0, "scene file"},
                         fmt::format("the scene is in '{}', a folder this run writes its frames into",
                                     (outDir / sub).string()),
                         "another --out, or the scene kept outside the run's output folders");
  }
  for (const InputMesh& in : inputs) {
    if (formats.sim)
      for (const scene::ObjectDesc& o : desc.objects) {
        const fs::path out = outDir / cache::geometryFileName(loaded.name, o.name);
        if (same(in.path, out)) refuse(in, out);
      }
    // Frame files: "<scene>.NNNN.ply" in ply/, "<fluid>.NNNN.obj" in mesh/.
    const std::string file = in.path.filename().string();
    const auto named = [&](const std::string& stem) {
      return file.size() > stem.size() && file.compare(0, stem.size(), stem) == 0 && file[stem.size()] == '.';
    };
    const fs::path folder = in.path.parent_path();
    if (formats.ply && named(loaded.name) && same(folder, outDir / "ply")) refuse(in, outDir / "ply" / file);
    if (formats.mesh && same(folder, outDir / "mesh"))
      for (const scene::FluidDesc& f : desc.fluids)
        if (named(f.name)) refuse(in, outDir / "mesh" / file);
  }
}

}  // namespace softsub::app
