#pragma once
/// Playing back a recorded folder: the `<scene>Sim/` folder `softsub run` (or the
/// viewer's S key) writes, `<scene>.NNNN.sim` frames plus `<scene>Geo/<name>.obj` meshes
/// (docs/cache-formats.md), or any folder holding `.sim` frames.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "cache/obj_format.h"
#include "core/snapshot.h"
#include "scene/scene_desc.h"

namespace softsub::session {

/// The frames of a recorded folder, loaded on demand.
class Playback {
 public:
  /// Opens `path`: a folder of `<scene>.<frame>.sim` files, or one such file (its folder,
  /// its scene). When the folder holds frames of several scenes, the one the folder is
  /// named after (`<scene>Sim`) is taken, else the one with the most frames. The scene
  /// file `<scene>.scene` beside the folder, when there, gives colours, particle sizes,
  /// the frame rate, the camera and the container. Object meshes are read once from the
  /// OBJ files the first frame names. InputError when there is no frame (saying what is
  /// expected) or a frame or mesh is invalid; IoError when something cannot be read.
  /// When the scene has frame manifests (`manifest/`, written by every run), frames
  /// past the last one are left out: frames no manifest lists (an older softsub's rerun
  /// left them; a fresh run now removes what the earlier run's manifests list) are not
  /// the last run's (notes() says which).
  /// `sceneFile`, when given, is read instead of the scene file beside the folder, and
  /// must read (InputError, IoError otherwise).
  explicit Playback(const std::filesystem::path& path, const std::filesystem::path& sceneFile = {});

  /// Number of frames.
  [[nodiscard]] std::size_t frameCount() const { return frames_.size(); }
  /// Frame numbers, increasing.
  [[nodiscard]] const std::vector<std::int64_t>& frameNumbers() const { return numbers_; }
  /// The frame number at `index` (std::out_of_range past the end).
  [[nodiscard]] std::int64_t frameNumber(std::size_t index) const { return numbers_.at(index); }
  /// The `.sim` file at `index`.
  [[nodiscard]] const std::filesystem::path& framePath(std::size_t index) const { return frames_.at(index); }

  /// Reads frame `index`: positions and object poses from the `.sim` file; colours and
  /// particle sizes of fluids the scene file names (defaults otherwise); the frame rate.
  [[nodiscard]] FrameSnapshot load(std::size_t index) const;

  /// The scene's name (the frames' file-name stem).
  [[nodiscard]] const std::string& sceneName() const { return sceneName_; }
  /// The folder played.
  [[nodiscard]] const std::filesystem::path& folder() const { return folder_; }
  /// Frames per second: the scene file's; else frame / time of a frame past 0; else 24.
  [[nodiscard]] double framesPerSecond() const { return fps_; }
  /// The scene file beside the folder, when there and valid (camera, container).
  [[nodiscard]] const std::optional<scene::SceneDesc>& scene() const { return scene_; }
  /// Why the scene file beside the folder was not used (the error reading it), when it is
  /// there but invalid; "".
  [[nodiscard]] const std::string& sceneNote() const { return sceneNote_; }
  /// The scene file looked for (beside the folder, or the one given).
  [[nodiscard]] const std::filesystem::path& sceneFile() const { return sceneFile_; }
  /// With a scene used: one sentence naming the first frame's fluids the scene has no
  /// `<Fluid>` of (renamed since the run, or another scene given), which are drawn and
  /// meshed with the default colour and ParticleSize 1; "" when every fluid is named.
  [[nodiscard]] const std::string& unnamedFluids() const { return unnamedFluids_; }
  /// Notes for a person: which scene was taken when the folder holds frames of several
  /// (and how to choose another), which frames were left out as an earlier run's (see
  /// the constructor).
  [[nodiscard]] const std::vector<std::string>& notes() const { return notes_; }
  /// The objects' meshes (in their own axes; the frames' ObjectSnapshot places them), in
  /// the order of the first frame's objects.
  [[nodiscard]] const std::vector<cache::ObjectMesh>& objectMeshes() const { return meshes_; }

 private:
  std::filesystem::path folder_;
  std::string sceneName_;
  std::vector<std::filesystem::path> frames_;
  std::vector<std::int64_t> numbers_;
  double fps_ = 24;
  std::optional<scene::SceneDesc> scene_;
  std::string sceneNote_;
  std::filesystem::path sceneFile_;
  std::string unnamedFluids_;
  std::vector<std::string> notes_;
  std::vector<cache::ObjectMesh> meshes_;
};

}  // namespace softsub::session
