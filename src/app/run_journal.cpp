#include "run_journal.h"

#include <algorithm>
#include <array>
#include <iterator>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>

#include <fmt/format.h>

#include "cache/atomic_file.h"
#include "cache/manifest.h"
#include "cache/naming.h"
#include "core/error.h"
#include "solver/checkpoint.h"

namespace softsub::app {

namespace {

/// Keeps this many newest checkpoints: the newest may belong to a frame whose manifest a
/// kill prevented, so the one before it is kept too.
constexpr std::size_t kCheckpointsKept = 2;

/// The files the frame after `last` would have, named as `last`'s are: the frame tag
/// `.NNNN.` of sim, ply, mesh and vdb files moved on by one, and a PDC file's ticks by
/// the step from `before`'s (the frame before, if it has the same file) or from 0, give
/// or take one (ticks are rounded). For the frame a killed run was writing.
std::vector<std::filesystem::path> nextFrameFiles(const cache::Manifest& last,
                                                  const std::optional<cache::Manifest>& before) {
  std::vector<std::filesystem::path> out;
  const std::string tag = fmt::format(".{}.", cache::frameTag(last.frame));
  const std::string next = fmt::format(".{}.", cache::frameTag(last.frame + 1));
  for (const cache::ManifestEntry& e : last.files) {
    const std::string& p = e.path;
    if (p.size() > 4 && p.compare(p.size() - 4, 4, ".pdc") == 0) {
      // pdc/<fluid>Shape.<ticks>.pdc
      const std::size_t dot = p.rfind('.', p.size() - 5);
      if (dot == std::string::npos) continue;
      const std::string stem = p.substr(0, dot + 1);
      std::int64_t ticks = 0;
      try {
        ticks = std::stoll(p.substr(dot + 1, p.size() - 5 - dot));
      } catch (const std::exception&) {
        continue;
      }
      std::int64_t step = last.frame > 0 ? ticks / last.frame : 0;
      if (before && before->frame + 1 == last.frame)
        for (const cache::ManifestEntry& b : before->files)
          if (b.path.compare(0, stem.size(), stem) == 0 && b.path.size() > stem.size() + 4) try {
              step = ticks - std::stoll(b.path.substr(stem.size(), b.path.size() - stem.size() - 4));
            } catch (const std::exception&) {}
      if (step <= 0) continue;  // frame 0 alone: the step is not known
      for (std::int64_t d = -1; d <= 1; ++d)
        out.emplace_back(fmt::format("{}{}.pdc", stem, ticks + step + d));
      continue;
    }
    if (const std::size_t at = p.rfind(tag); at != std::string::npos)
      out.emplace_back(fmt::format("{}{}{}", p.substr(0, at), next, p.substr(at + tag.size())));
  }
  return out;
}

void removeQuietly(const std::filesystem::path& p) {
  std::error_code ec;
  std::filesystem::remove(p, ec);
}

}  // namespace

RunJournal::RunJournal(std::filesystem::path outDir, std::string sceneName, std::uint64_t fingerprint,
                       int checkpointEvery, const solver::Simulation& sim,
                       std::vector<WrittenFiles> writers)
    : dir_(std::move(outDir)),
      scene_(std::move(sceneName)),
      fingerprint_(fingerprint),
      every_(checkpointEvery),
      sim_(sim),
      writers_(std::move(writers)) {
  checkpoints_ = cache::checkpointFrames(dir_, scene_);
}

void RunJournal::onFrame(const FrameSnapshot& frame) {
  cache::Manifest m;
  m.frame = frame.frame;
  m.substeps = sim_.substeps();
  m.fingerprint = fingerprint_;
  for (const WrittenFiles& w : writers_)
    for (const std::filesystem::path& p : w()) m.files.push_back(cache::entryOf(dir_, p));
  const bool due = every_ > 0 && frame.frame % every_ == 0;
  if (due) {
    if (sim_.state().frame != frame.frame)
      throw std::logic_error("RunJournal: the simulation is not at the observed frame");
    solver::encodeCheckpoint(sim_, fingerprint_, buffer_);
    const std::filesystem::path path = cache::checkpointPath(dir_, scene_, frame.frame);
    cache::ensureDirectory(path.parent_path());
    cache::writeFileAtomic(path, buffer_);
    m.checkpoint = cache::ManifestEntry{path.lexically_relative(dir_).generic_string(), buffer_.size()};
  }
  if (due) {
    // Older checkpoints go before the manifest: the previous one stays until this frame
    // is complete, so a kill anywhere leaves a complete frame with its checkpoint, and
    // the folder never holds more than the two newest (the same set whatever the kill).
    checkpoints_.erase(std::remove(checkpoints_.begin(), checkpoints_.end(), frame.frame), checkpoints_.end());
    checkpoints_.push_back(frame.frame);
    std::sort(checkpoints_.begin(), checkpoints_.end());
    while (checkpoints_.size() > kCheckpointsKept) {
      removeQuietly(cache::checkpointPath(dir_, scene_, checkpoints_.front()));
      checkpoints_.erase(checkpoints_.begin());
    }
  }
  const std::filesystem::path manifest = cache::manifestPath(dir_, scene_, frame.frame);
  cache::ensureDirectory(manifest.parent_path());
  // Last: the frame is complete from here on.
  cache::writeFileAtomic(manifest, cache::encodeManifest(m));
}

void pruneCheckpoints(const std::filesystem::path& outDir, const std::string& sceneName) {
  std::vector<std::int64_t> frames = cache::checkpointFrames(outDir, sceneName);
  while (frames.size() > kCheckpointsKept) {
    removeQuietly(cache::checkpointPath(outDir, sceneName, frames.front()));
    frames.erase(frames.begin());
  }
}

RunFrames readRunFrames(const std::filesystem::path& outDir, const std::string& sceneName) {
  RunFrames run;
  bool inRow = true;
  for (const std::int64_t f : cache::manifestFrames(outDir, sceneName)) {
    const std::filesystem::path path = cache::manifestPath(outDir, sceneName, f);
    try {
      run.manifests.push_back(cache::decodeManifest(cache::readFileBytes(path), path.string()));
    } catch (const std::exception& e) {  // InputError or IoError: this frame is not complete
      if (inRow) run.stop = e.what();
      inRow = false;
      continue;
    }
    if (!inRow) continue;
    const cache::Manifest& m = run.manifests.back();
    if (m.frame != static_cast<std::int64_t>(run.complete)) {
      run.stop = fmt::format("frame {} has no manifest", run.complete);
      inRow = false;
    } else if (std::string why = cache::incompleteReason(outDir, m, false); !why.empty()) {
      run.stop = fmt::format("frame {}: {}", f, why);
      inRow = false;
    } else {
      ++run.complete;
    }
  }
  return run;
}

std::vector<std::size_t> RunFrames::checkpointed(const std::filesystem::path& outDir) const {
  std::vector<std::size_t> out;
  for (std::size_t k = complete; k-- > 0;)
    if (manifests[k].checkpoint && cache::incompleteReason(outDir, manifests[k], true).empty()) out.push_back(k);
  return out;
}

ResumePoint resumeFrom(const std::filesystem::path& outDir, const std::string& sceneName, std::uint64_t fingerprint,
                       solver::Simulation& sim) {
  ResumePoint point;
  const RunFrames run = readRunFrames(outDir, sceneName);
  // The settings of the run in the folder: every manifest that reads must have ours.
  for (auto it = run.manifests.rbegin(); it != run.manifests.rend(); ++it)
    if (it->fingerprint != fingerprint)
      throw InputError(
          {outDir.string(), 0, "--resume"},
          fmt::format("the folder holds frame {} of '{}' made with other settings (one of: the "
                      "scene or its meshes, --substeps, --integrator, --formats, --voxel-size, "
                      "--blob-radius, --adaptive, --max-substeps, --speed-limit, the softsub version)",
                      it->frame, sceneName),
          "the same scene and options as the run being resumed, or run without --resume to start over");
  point.completeUpTo = static_cast<std::int64_t>(run.complete) - 1;
  // The newest complete frame whose checkpoint restores.
  for (const std::size_t k : run.checkpointed(outDir)) {
    const cache::Manifest& m = run.manifests[k];
    const std::filesystem::path path = outDir / m.checkpoint->path;
    try {
      const std::string bytes = cache::readFileBytes(path);
      if (solver::checkpointInfo(bytes, path.string()).frame != m.frame) continue;
      solver::restoreCheckpoint(sim, bytes, fingerprint, path.string());
      point.frame = m.frame;
      return point;
    } catch (const InputError& e) {
      point.note = e.what();
    } catch (const IoError& e) {
      point.note = e.what();
    }
  }
  if (point.note.empty())
    point.note = run.complete == 0 ? fmt::format("no complete frame of '{}' in {}", sceneName, outDir.string())
                                   : "no complete frame has a checkpoint";
  return point;
}

std::size_t forgetEarlierRun(const std::filesystem::path& outDir, const std::string& sceneName,
                             const std::vector<std::filesystem::path>& keep) {
  namespace fs = std::filesystem;
  constexpr std::array<std::string_view, 4> kFrameFolders{"pdc", "ply", "mesh", "vdb"};
  const auto frameFile = [&](const fs::path& p) {  // relative, without "..": decodeManifest checked
    const auto first = p.begin();
    if (first == p.end()) return false;
    if (std::next(first) == p.end()) return p.extension() == ".sim";
    return std::find(kFrameFolders.begin(), kFrameFolders.end(), first->string()) != kFrameFolders.end();
  };
  std::size_t removed = 0;
  const auto kept = [&](const fs::path& file) {
    return std::any_of(keep.begin(), keep.end(), [&](const fs::path& k) {
      std::error_code ec;
      return fs::equivalent(k, file, ec) && !ec;
    });
  };
  // The newest manifest that reads (its frame and files, and when it was written), and
  // the PDC ticks of the frame before it, for the frame a killed run was writing.
  std::optional<cache::Manifest> last;
  fs::file_time_type lastWritten{};
  std::optional<cache::Manifest> beforeLast;
  for (const std::int64_t f : cache::manifestFrames(outDir, sceneName)) {
    const fs::path path = cache::manifestPath(outDir, sceneName, f);
    // A manifest that does not read names no file.
    const std::optional<cache::Manifest> manifest = cache::readManifestIfValid(path);
    if (manifest) {
      std::error_code ec;
      beforeLast = std::exchange(last, manifest);
      lastWritten = fs::last_write_time(path, ec);
    }
    for (const cache::ManifestEntry& e : manifest.value_or(cache::Manifest{}).files) {
      const fs::path file = outDir / e.path;
      std::error_code ec;
      if (!frameFile(e.path) || !fs::is_regular_file(file, ec) || fs::file_size(file, ec) != e.bytes || ec)
        continue;
      if (kept(file)) continue;
      if (fs::remove(file, ec) && !ec) ++removed;
    }
    removeQuietly(path);
  }
  // A run killed while it wrote a frame left that frame's files without a manifest: they
  // are named as the last manifest's are, with the next frame's number (or PDC ticks one
  // frame's step on), and were written after that manifest. Without this, a shorter run
  // into the folder left them at the end of its sequence.
  if (last)
    for (const fs::path& file : nextFrameFiles(*last, beforeLast)) {
      std::error_code ec;
      const fs::path path = outDir / file;
      if (!frameFile(file) || !fs::is_regular_file(path, ec) || ec ||
          fs::last_write_time(path, ec) < lastWritten || ec || kept(path))
        continue;
      if (fs::remove(path, ec) && !ec) ++removed;
    }
  for (const std::int64_t f : cache::checkpointFrames(outDir, sceneName))
    removeQuietly(cache::checkpointPath(outDir, sceneName, f));
  // The earlier run's --preview picture showed its last frame under this run's name.
  if (const fs::path preview = outDir / (sceneName + ".preview.png"); !kept(preview)) removeQuietly(preview);
  // A frame folder left empty goes too (a folder exists only for a format written);
  // one that still holds anything stays.
  if (removed > 0)
    for (const std::string_view folder : kFrameFolders)
      if (std::error_code ec; fs::is_empty(outDir / folder, ec) && !ec) removeQuietly(outDir / folder);
  // So do the journal's folders once empty (the viewer's S, which writes no journal,
  // left them; a run makes them again as it writes).
  for (const std::string_view folder : {"manifest", "checkpoint"})
    if (std::error_code ec; fs::is_empty(outDir / folder, ec) && !ec) removeQuietly(outDir / folder);
  return removed;
}

void updateFrameManifest(const std::filesystem::path& outDir, const std::string& sceneName,
                         std::int64_t frame, const std::vector<std::filesystem::path>& files) {
  const std::filesystem::path path = cache::manifestPath(outDir, sceneName, frame);
  std::optional<cache::Manifest> m = cache::readManifestIfValid(path);
  if (!m) return;
  for (const std::filesystem::path& file : files) {
    const cache::ManifestEntry now = cache::entryOf(outDir, file);
    const auto it = std::find_if(m->files.begin(), m->files.end(),
                                 [&](const cache::ManifestEntry& e) { return e.path == now.path; });
    if (it != m->files.end()) it->bytes = now.bytes;
    else m->files.push_back(now);
  }
  cache::writeFileAtomic(path, cache::encodeManifest(*m));
}

void refuseOtherScenesFiles(const std::filesystem::path& outDir, const std::string& sceneName,
                            const cache::Formats& formats, const std::vector<std::string>& fluidNames,
                            std::string_view element, std::string_view remedy) {
  if (!formats.pdc && !formats.mesh && !formats.vdb) return;
  // What this run writes under a fluid's name: "pdc/<fluid>Shape.", "mesh/<fluid>.", "vdb/<fluid>.".
  std::vector<std::string> prefixes;
  for (const std::string& f : fluidNames) {
    if (formats.pdc) prefixes.push_back("pdc/" + f + "Shape.");
    if (formats.mesh) prefixes.push_back("mesh/" + f + ".");
    if (formats.vdb) prefixes.push_back("vdb/" + f + ".");
  }
  for (const std::string& other : cache::manifestSceneNames(outDir)) {
    if (other == sceneName) continue;
    for (const std::int64_t frame : cache::manifestFrames(outDir, other)) {
      const std::filesystem::path path = cache::manifestPath(outDir, other, frame);
      const std::optional<cache::Manifest> m = cache::readManifestIfValid(path);
      if (!m) continue;  // a manifest that does not read names no file
      for (const cache::ManifestEntry& e : m->files)
        for (const std::string& prefix : prefixes)
          if (e.path.starts_with(prefix))
            throw InputError(
                {outDir.string(), 0, std::string(element)},
                fmt::format("the folder holds '{}', a file of scene '{}' (listed in {}), which this run "
                            "of '{}' would write over: files of a fluid are named after the fluid, "
                            "not the scene",
                            e.path, other, path.lexically_relative(outDir).generic_string(), sceneName),
                std::string(remedy));
      break;  // one readable manifest lists the scene's fluids
    }
  }
}

}  // namespace softsub::app
