#include "render_playback.h"

#include <cctype>
#include <filesystem>
#include <utility>

#include <fmt/format.h>

#include "core/error.h"
#include "render/renderer.h"
#include "scene_view.h"
#include "session/playback.h"

namespace softsub::app {

RecordedFrames::RecordedFrames(const std::string& folder, const std::string& sceneFile)
    : playback_(std::make_unique<session::Playback>(folder, sceneFile)) {
  sceneName = playback_->sceneName();
  framesPerSecond = playback_->framesPerSecond();
  if (playback_->scene()) scene = renderSceneOf(*playback_->scene(), {});
  for (const cache::ObjectMesh& m : playback_->objectMeshes()) {
    render::RenderMesh r;
    r.name = m.name;
    for (const auto& v : m.vertices)
      r.vertices.push_back({static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])});
    r.triangles = m.triangles;
    scene.meshes.push_back(std::move(r));
  }
  camera = playback_->scene() ? cameraOf(playback_->scene()->camera)
                              : render::frameBounds(render::sceneBounds(scene, load(0)), 16.0 / 9.0);
}

bool isRecording(const std::string& input) {
  if (input.empty()) return false;
  std::error_code ec;
  const std::filesystem::path p(input);
  if (std::filesystem::is_directory(p, ec)) return true;
  std::string ext = p.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".sim";
}

void refuseSimulationOptions(const std::string& input, bool substeps, bool maxParticles) {
  for (const auto& [given, option] :
       {std::pair{substeps, "--substeps"}, std::pair{maxParticles, "--max-particles"}})
    if (given)
      throw InputError({"command line", 0, option},
                       fmt::format("is for a scene: {} is a recording, drawn as it was simulated", input),
                       fmt::format("a .scene input, or leave {} out", option));
}

RecordedFrames::~RecordedFrames() = default;
RecordedFrames::RecordedFrames(RecordedFrames&&) noexcept = default;

std::size_t RecordedFrames::frameCount() const { return playback_->frameCount(); }

std::int64_t RecordedFrames::frameNumber(std::size_t index) const { return playback_->frameNumber(index); }

FrameSnapshot RecordedFrames::load(std::size_t index) const { return playback_->load(index); }

std::vector<std::string> playbackWarnings(const session::Playback& playback, std::string_view withoutScene,
                                          std::string_view how) {
  std::vector<std::string> out;
  if (!playback.scene()) {
    const std::string file = playback.sceneFile().generic_string();
    out.push_back(
        playback.sceneNote().empty()
            ? fmt::format("no usable scene file at {}: {} (give the scene with {})", file, withoutScene, how)
            : fmt::format("no usable scene file at {} ({}): {} (give the scene with {})", file,
                          playback.sceneNote(), withoutScene, how));
  }
  if (!playback.unnamedFluids().empty())
    out.push_back(
        fmt::format("{}; give the scene the recording was made with ({})", playback.unnamedFluids(), how));
  for (const std::string& note : playback.notes()) out.push_back(note);
  return out;
}

}  // namespace softsub::app
