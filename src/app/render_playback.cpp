#include "render_playback.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <regex>

#include <fmt/format.h>

#include "cache/atomic_file.h"
#include "cache/obj_format.h"
#include "cache/sim_format.h"
#include "core/error.h"
#include "scene/reader.h"
#include "render/renderer.h"
#include "scene_view.h"

namespace softsub::session {
/// Placeholder until the session module's Playback lands.
class Playback {
 public:
  std::vector<std::pair<std::int64_t, std::filesystem::path>> frames;
  std::optional<scene::SceneDesc> desc;
};
}  // namespace softsub::session

namespace softsub::app {

RecordedFrames::RecordedFrames(const std::string& folder) : playback_(std::make_unique<session::Playback>()) {
  namespace fs = std::filesystem;
  const fs::path dir(folder);
  std::error_code ec;
  const std::regex frameName(R"((.+)\.(\d{4,})\.sim)");
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
    std::smatch m;
    const std::string name = e.path().filename().string();
    if (!e.is_regular_file() || !std::regex_match(name, m, frameName)) continue;
    if (sceneName.empty()) sceneName = m[1];
    if (m[1] != sceneName) continue;
    playback_->frames.emplace_back(std::stoll(m[2]), e.path());
  }
  if (ec) throw IoError(fmt::format("cannot read folder {}: {}", folder, ec.message()));
  if (playback_->frames.empty())
    throw InputError({folder, 0, "folder"}, "holds no recorded frames", "a folder of <scene>.NNNN.sim files, as 'softsub run' writes");
  std::sort(playback_->frames.begin(), playback_->frames.end());
  const fs::path sceneFile = dir.parent_path() / (sceneName + ".scene");
  if (fs::is_regular_file(sceneFile, ec)) {
    playback_->desc = scene::readSceneFile(sceneFile.string());
    framesPerSecond = playback_->desc->simulation.framesPerSecond;
    scene = renderSceneOf(*playback_->desc, {});
  }
  const FrameSnapshot first = load(0);
  for (const ObjectSnapshot& o : first.objects) {
    const cache::ObjectMesh mesh = cache::decodeObj(cache::readFileBytes(dir / o.filename), (dir / o.filename).string());
    render::RenderMesh r;
    r.name = o.name;
    for (const auto& v : mesh.vertices)
      r.vertices.push_back({static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])});
    r.triangles = mesh.triangles;
    scene.meshes.push_back(std::move(r));
  }
  camera = playback_->desc ? cameraOf(playback_->desc->camera)
                          : render::frameBounds(render::sceneBounds(scene, first), 16.0 / 9.0);
}

RecordedFrames::~RecordedFrames() = default;
RecordedFrames::RecordedFrames(RecordedFrames&&) noexcept = default;

std::size_t RecordedFrames::frameCount() const { return playback_->frames.size(); }

std::int64_t RecordedFrames::frameNumber(std::size_t index) const { return playback_->frames.at(index).first; }

FrameSnapshot RecordedFrames::load(std::size_t index) const {
  FrameSnapshot frame = cache::readSimFile(playback_->frames.at(index).second).frame;
  frame.framesPerSecond = framesPerSecond;
  if (playback_->desc)
    for (FluidSnapshot& f : frame.fluids)
      for (const scene::FluidDesc& d : playback_->desc->fluids)
        if (d.name == f.name) {
          f.colour = {static_cast<float>(d.colour.x()), static_cast<float>(d.colour.y()), static_cast<float>(d.colour.z())};
          f.particleSize = static_cast<float>(d.params.particleSize);
        }
  return frame;
}

}  // namespace softsub::app
