#pragma once
/// Where `run` gets its scene: a .scene file, or the embedded default scene.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "cache/frame_writer.h"
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
  std::string file;                    ///< the scene file messages name (`<name>.scene`: embedded)
  std::filesystem::path defaultOutDir; ///< <sceneDir>/<name>Sim
  std::vector<std::string> warnings;   ///< the reader's warnings (meshes repaired or not closed)
};

/// Reads and validates `path`, or the embedded default scene when `path` is empty.
/// `maxParticles` 0 keeps the reader's default limit. Throws InputError / IoError.
LoadedScene loadScene(const std::string& path, std::uint64_t maxParticles);

/// Checks that `name`, which becomes part of output file names, can be one
/// (cache::checkFileNamePart); the rule knows names, not files: the InputError names
/// `file`, where the name comes from.
void checkOutputName(std::string_view name, std::string_view element, const std::string& file);

/// The names that become parts of the output files' names, checked before anything is
/// created: the scene's when `sceneNamesFiles` (every file of a run, pictures, the
/// preview, screenshots), the fluids' when `formats` has PDC files or surfaces, and the
/// objects' (their OBJ files beside the .sim frames) when it has `.sim` frames. An error
/// names the scene file.
void checkOutputNames(const LoadedScene& loaded, const cache::Formats& formats, bool sceneNamesFiles);

/// The files a scene was read from: the scene file (none for the embedded scene), then
/// every mesh its objects and mesh fills read.
[[nodiscard]] std::vector<std::filesystem::path> inputFiles(const LoadedScene& loaded);

/// Refuses a run into `outDir` that would write over one of the scene's own input meshes
/// (an object's or a mesh fill's <Geometry>): the run writes each object's mesh to
/// `<out>/<scene>Geo/<name>.obj`, where the docs suggest keeping input meshes, so an
/// --out of the scene's own folder would replace them. Compared by file identity (a link
/// or another spelling of the path is the same file). Also refused: an input mesh in
/// one of the run's frame folders (ply/, mesh/) under a name the run's frames take
/// there. The InputError names the <Object> or <Fill> line. And refused: the scene file
/// itself in one of the run's frame folders (pdc/, ply/, mesh/, vdb/, manifest/,
/// checkpoint/). Nothing is created or changed.
void checkInputsKept(const LoadedScene& loaded, const cache::Formats& formats,
                     const std::filesystem::path& outDir);

}  // namespace softsub::app
