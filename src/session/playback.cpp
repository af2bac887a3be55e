#include "session/playback.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <charconv>
#include <map>
#include <system_error>
#include <utility>

#include "cache/atomic_file.h"
#include "cache/manifest.h"
#include "cache/naming.h"
#include "cache/sim_format.h"
#include "core/error.h"
#include "scene/reader.h"

namespace softsub::session {

namespace fs = std::filesystem;

namespace {

constexpr const char* kExpected = "a folder of <scene>.NNNN.sim frames, as 'softsub run' writes (<scene>Sim/)";

/// A mesh file name from a `.sim` file: relative, inside the folder.
void checkMeshName(const std::string& filename, const fs::path& simFile) {
  const fs::path p(filename);
  bool inside = !filename.empty() && p.is_relative() && !p.has_root_name();
  for (const fs::path& part : p)
    if (part == "..") inside = false;
  if (!inside)
    throw InputError({simFile.string(), 0, "Object/Filename"},
                     fmt::format("mesh file '{}' is not inside the recorded folder", filename),
                     "a path relative to the folder, without '..' (<scene>Geo/<name>.obj)");
}

}  // namespace

Playback::Playback(const fs::path& path, const fs::path& givenScene) {
  std::error_code ec;
  fs::path folder = path.lexically_normal();
  if (folder.filename().empty() && folder.has_parent_path()) folder = folder.parent_path();
  std::string wanted;  // the scene whose frames to play, when known
  const bool givenFrame = fs::is_regular_file(folder, ec);  // a frame file names its scene
  if (givenFrame) {
    const std::optional<cache::SimFileName> name = cache::parseSimFileName(folder.filename().string());
    if (!name) throw InputError({path.string(), 0, "file"}, "is not a recorded frame", kExpected);
    wanted = name->scene;
    folder = folder.has_parent_path() ? folder.parent_path() : fs::path(".");
  } else if (!fs::is_directory(folder, ec)) {
    throw IoError(fmt::format("cannot open recorded frames '{}': no such folder", path.string()));
  }
  folder_ = folder;

  // Every frame file, by scene.
  std::map<std::string, std::vector<std::pair<std::int64_t, fs::path>>> byScene;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::optional<cache::SimFileName> name = cache::parseSimFileName(it->path().filename().string());
    if (!name || !it->is_regular_file(ec)) continue;
    byScene[name->scene].emplace_back(name->frame, it->path());
  }
  if (ec) throw IoError(fmt::format("cannot read folder '{}': {}", folder.string(), ec.message()));
  if (byScene.empty())
    throw InputError({folder.string(), 0, "folder"}, "holds no recorded frames (no <scene>.NNNN.sim file)",
                     kExpected);
  if (wanted.empty()) {
    const fs::path absolute = fs::absolute(folder, ec).lexically_normal();
    std::string folderName = (absolute.filename().empty() ? absolute.parent_path() : absolute).filename().string();
    if (folderName.size() > 3 && folderName.ends_with("Sim")) folderName.resize(folderName.size() - 3);
    if (byScene.count(folderName) != 0) {
      wanted = folderName;
    } else {
      std::size_t most = 0;
      for (const auto& [stem, frames] : byScene)
        if (frames.size() > most) {  // ties: the first in name order
          most = frames.size();
          wanted = stem;
        }
    }
  }
  sceneName_ = wanted;
  if (byScene.size() > 1 && !givenFrame) {
    std::string others;
    for (const auto& [stem, frames] : byScene)
      if (stem != wanted) others += fmt::format("{}'{}'", others.empty() ? "" : ", ", stem);
    notes_.push_back(
        fmt::format("the folder holds frames of {} scenes: '{}' taken, not {} (give one of a scene's "
                    ".sim files to take that scene)",
                    byScene.size(), wanted, others));
  }
  auto& frames = byScene.at(wanted);
  std::sort(frames.begin(), frames.end());
  for (const auto& [number, file] : frames) {
    if (!numbers_.empty() && numbers_.back() == number) continue;  // "7" and "0007": the first
    numbers_.push_back(number);
    frames_.push_back(file);
  }
  const std::vector<std::int64_t> manifests = cache::manifestFrames(folder_, sceneName_);
  if (!manifests.empty() && numbers_.front() <= manifests.back() && numbers_.back() > manifests.back()) {
    const auto kept = static_cast<std::size_t>(
        std::upper_bound(numbers_.begin(), numbers_.end(), manifests.back()) - numbers_.begin());
    notes_.push_back(fmt::format(
        "frames {} to {} of '{}' left out: they have no manifest, and the last frame that has one is {} (a "
        "frame a killed run was writing, or an earlier, longer run's frames that a later run did not "
        "replace)",
        numbers_[kept], numbers_.back(), sceneName_, manifests.back()));
    numbers_.resize(kept);
    frames_.resize(kept);
  }
  // A frame whose .sim file is not the size its manifest lists was damaged after the
  // run (cut, edited): it and the frames after it are left out, before anything is
  // drawn or meshed (mesh and render wrote the frames before it, then failed on it).
  // With manifests, a run's frames are consecutive and each has one: a frame whose .sim
  // is gone, or whose manifest is, leaves a gap that the frames after it were drawn
  // across without a word (a review); it and the frames after it are left out too.
  for (std::size_t i = 0; i < numbers_.size(); ++i) {
    std::string why;
    const std::optional<cache::Manifest> m =
        manifests.empty() ? std::nullopt
                          : cache::readManifestIfValid(cache::manifestPath(folder_, sceneName_, numbers_[i]));
    if (i > 0 && !manifests.empty() && numbers_[i] != numbers_[i - 1] + 1) {
      why = numbers_[i] - numbers_[i - 1] == 2
                ? fmt::format("frame {}'s .sim file is missing", numbers_[i - 1] + 1)
                : fmt::format("the .sim files of frames {} to {} are missing", numbers_[i - 1] + 1,
                              numbers_[i] - 1);
      notes_.push_back(fmt::format("frames {} to {} of '{}' left out: {}", numbers_[i - 1] + 1,
                                   numbers_.back(), sceneName_, why));
      numbers_.resize(i);
      frames_.resize(i);
      break;
    }
    if (!manifests.empty() && !m && !fs::exists(cache::manifestPath(folder_, sceneName_, numbers_[i]), ec)) {
      why = fmt::format(
          "frame {} has no manifest (manifest/{}.{}.manifest), though the run's other frames have "
          "one",
          numbers_[i], sceneName_, cache::frameTag(numbers_[i]));
    } else if (m) {
      const std::string name = frames_[i].filename().string();
      const auto entry = std::find_if(m->files.begin(), m->files.end(),
                                      [&](const cache::ManifestEntry& e) { return e.path == name; });
      const std::uintmax_t size = fs::file_size(frames_[i], ec);
      if (entry == m->files.end() || ec || size == entry->bytes) continue;
      why = fmt::format(
          "'{}' has {} bytes, not the {} its manifest lists (changed since the run "
          "wrote it)",
          name, size, entry->bytes);
    } else {
      continue;  // no manifests at all: the viewer's S, an older softsub
    }
    if (i == 0)
      throw InputError(
          {frames_[i].string(), 0, "frame"}, why,
          "a folder whose frames are as the run wrote them: run the scene again, or `softsub info` "
          "the folder to see which frames are whole");
    notes_.push_back(
        fmt::format("frames {} to {} of '{}' left out: {}", numbers_[i], numbers_.back(), sceneName_, why));
    numbers_.resize(i);
    frames_.resize(i);
    break;
  }

  // The scene file (given, or beside the folder): colours, sizes, frame rate, camera,
  // container.
  const fs::path absolute = fs::absolute(folder_, ec).lexically_normal();
  const fs::path sceneFile =
      !givenScene.empty() ? givenScene
                          : (absolute.filename().empty() ? absolute.parent_path() : absolute).parent_path() /
                                (sceneName_ + ".scene");
  sceneFile_ = sceneFile;
  if (!givenScene.empty()) {
    scene_ = scene::readSceneFile(sceneFile.string());
    fps_ = scene_->simulation.framesPerSecond;
  } else if (fs::is_regular_file(sceneFile, ec)) {
    try {
      scene_ = scene::readSceneFile(sceneFile.string());
      fps_ = scene_->simulation.framesPerSecond;
    } catch (const std::exception& e) {  // InputError, IoError: play without it
      sceneNote_ = e.what();
    }
  }

  const FrameSnapshot first = cache::readSimFile(frames_.front()).frame;
  if (!scene_) {
    // No scene: the rate the frames' own times imply.
    FrameSnapshot probe;
    if (first.frame > 0 && first.time > 0) {
      fps_ = static_cast<double>(first.frame) / first.time;
    } else if (frames_.size() > 1) {
      probe = cache::readSimFile(frames_[1]).frame;
      if (probe.frame > 0 && probe.time > 0) fps_ = static_cast<double>(probe.frame) / probe.time;
    }
  }
  if (scene_) {
    std::vector<std::string> missing, named;
    for (const scene::FluidDesc& d : scene_->fluids) named.push_back(fmt::format("'{}'", d.name));
    for (const FluidSnapshot& f : first.fluids)
      if (std::none_of(scene_->fluids.begin(), scene_->fluids.end(),
                       [&](const scene::FluidDesc& d) { return d.name == f.name; }))
        missing.push_back(fmt::format("'{}'", f.name));
    if (!missing.empty())
      unnamedFluids_ = fmt::format(
          "the scene file {} has no fluid {} of the recording (its fluids: {}): drawn and meshed with the "
          "default colour and ParticleSize 1",
          sceneFile_.generic_string(), fmt::join(missing, ", "),
          named.empty() ? "none" : fmt::format("{}", fmt::join(named, ", ")));
  }
  for (const ObjectSnapshot& o : first.objects) {
    checkMeshName(o.filename, frames_.front());
    const fs::path file = folder_ / o.filename;
    meshes_.push_back(cache::decodeObj(cache::readFileBytes(file), file.string()));
    meshes_.back().name = o.name;
  }
}

FrameSnapshot Playback::load(std::size_t index) const {
  FrameSnapshot frame = cache::readSimFile(frames_.at(index)).frame;
  frame.framesPerSecond = fps_;
  if (scene_)
    for (FluidSnapshot& f : frame.fluids)
      for (const scene::FluidDesc& d : scene_->fluids)
        if (d.name == f.name) {
          f.colour = {static_cast<float>(d.colour.x()), static_cast<float>(d.colour.y()),
                      static_cast<float>(d.colour.z())};
          f.particleSize = static_cast<float>(d.params.particleSize);
        }
  return frame;
}

}  // namespace softsub::session
