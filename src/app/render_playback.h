#pragma once
/// A recorded `<scene>Sim/` folder as the renderer and the viewer play it back: its
/// frames, and the container, meshes and camera to draw them with.
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/snapshot.h"
#include "render/camera.h"
#include "render/render_scene.h"

namespace softsub::session {
class Playback;
}

namespace softsub::app {

/// Frames of a recorded folder plus what draws them.
class RecordedFrames {
 public:
  /// Opens `folder`; InputError/IoError when it holds no readable frames. `sceneFile`,
  /// when given, is read instead of `<scene>.scene` beside the folder and must read.
  explicit RecordedFrames(const std::string& folder, const std::string& sceneFile = {});
  ~RecordedFrames();
  RecordedFrames(RecordedFrames&&) noexcept;

  [[nodiscard]] std::size_t frameCount() const;
  [[nodiscard]] std::int64_t frameNumber(std::size_t index) const;
  /// The frame at `index` (colours and sizes from the scene file beside the folder).
  [[nodiscard]] FrameSnapshot load(std::size_t index) const;
  /// The folder as played (its notes and warnings: playbackWarnings).
  [[nodiscard]] const session::Playback& playback() const { return *playback_; }

  std::string sceneName;            ///< names the pictures
  double framesPerSecond = 24;      ///< from the scene beside the folder, else 24
  render::RenderScene scene;        ///< container (from the scene beside) and meshes
  render::Camera camera;            ///< the scene's camera, else one that frames frame 0

 private:
  std::unique_ptr<session::Playback> playback_;
};

/// True when `input` names a recording rather than a scene: a folder, or a `.sim` file
/// (which plays its folder).
[[nodiscard]] bool isRecording(const std::string& input);

/// A recording is drawn as it was simulated: the options that change how a scene is
/// simulated (`--substeps`, `--max-particles`) would do nothing, and are refused with it,
/// naming the option and `input` (InputError, exit 2), rather than silently ignored.
void refuseSimulationOptions(const std::string& input, bool substeps, bool maxParticles);

/// Opens a recorded folder (see RecordedFrames).
[[nodiscard]] inline RecordedFrames openRecorded(const std::string& folder,
                                                 const std::string& sceneFile = {}) {
  return RecordedFrames(folder, sceneFile);
}

/// What a command that draws or meshes a recording must say about it, terminal or not
/// (they change its output; `--quiet` alone silences them): no usable scene file (the
/// one looked for, why, what then happens: `withoutScene`), fluids the scene has no
/// `<Fluid>` of, and the frames or other scenes of the folder left out
/// (session::Playback::notes). `how`: how to give the scene ("--scene"). One line
/// each, without the "warning: " prefix.
[[nodiscard]] std::vector<std::string> playbackWarnings(const session::Playback& playback,
                                                        std::string_view withoutScene, std::string_view how);

}  // namespace softsub::app
