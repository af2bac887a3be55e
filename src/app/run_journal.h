#pragma once
/// What makes `softsub run` lose no frame and resume exactly: after each frame's cache
/// files, a checkpoint (every K frames) and then the frame's manifest, written last
/// (cache/manifest.h); at the start, stale temporaries removed and, with --resume, the
/// last complete checkpointed frame found and restored. docs/cli.md, "Resuming a run".
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "cache/frame_writer.h"
#include "cache/manifest.h"
#include "core/snapshot.h"
#include "solver/simulation.h"

namespace softsub::app {

/// The files one frame's writers produced, for its manifest.
using WrittenFiles = std::function<std::vector<std::filesystem::path>()>;

/// The FrameObserver that runs after every cache writer: writes the frame's checkpoint
/// (when due) and then its manifest, and keeps only the two newest checkpoints.
class RunJournal : public FrameObserver {
 public:
  /// Checkpoints frames 0, K, 2K, ... (K = checkpointEvery; 0: none).
  RunJournal(std::filesystem::path outDir, std::string sceneName, std::uint64_t fingerprint, int checkpointEvery,
             const solver::Simulation& sim, std::vector<WrittenFiles> writers);

  void onFrame(const FrameSnapshot& frame) override;

 private:
  std::filesystem::path dir_;
  std::string scene_;
  std::uint64_t fingerprint_;
  int every_;
  const solver::Simulation& sim_;
  std::vector<WrittenFiles> writers_;
  std::string buffer_;
  std::vector<std::int64_t> checkpoints_;  ///< frames whose checkpoint this run wrote or kept
};

/// The frames a run left in a folder, as its manifests tell.
struct RunFrames {
  std::vector<cache::Manifest> manifests;  ///< every manifest that reads, by frame
  std::size_t complete = 0;  ///< manifests[0, complete) are frames 0, 1, ... in a row, every file there
  std::string stop;          ///< why the row ends there ("" when nothing follows it)
  /// Indices of the complete frames whose manifest lists a checkpoint that is there at
  /// its size, newest first: where a resume may start.
  [[nodiscard]] std::vector<std::size_t> checkpointed(const std::filesystem::path& outDir) const;
};

/// Reads the manifests of `sceneName` in `outDir` (none when there are none).
[[nodiscard]] RunFrames readRunFrames(const std::filesystem::path& outDir, const std::string& sceneName);

/// Where a resumed run starts.
struct ResumePoint {
  std::int64_t frame = -1;         ///< the restored frame (-1: nothing to resume, start at 0)
  std::int64_t completeUpTo = -1;  ///< the last frame with a complete manifest
  std::string note;                ///< why nothing (or less than expected) could be resumed
};

/// Finds the newest frame of `sceneName` in `outDir` that is complete (its manifest and
/// every earlier frame's are whole) and has an intact checkpoint of a run with
/// `fingerprint`, and restores `sim` to it. InputError when any manifest in the folder
/// belongs to a run with other settings (nothing is changed then). A checkpoint that does
/// not restore leaves `sim` as it was and the next older one is tried.
[[nodiscard]] ResumePoint resumeFrom(const std::filesystem::path& outDir, const std::string& sceneName,
                                     std::uint64_t fingerprint, solver::Simulation& sim);

/// Removes all but the two newest checkpoints of `sceneName` in `outDir` (what a run that
/// was never stopped leaves).
void pruneCheckpoints(const std::filesystem::path& outDir, const std::string& sceneName);

/// Before a fresh (not resumed) run writes anything: removes the folder's manifests and
/// checkpoints of `sceneName`, which describe an earlier run, and the frame files those
/// manifests list (`<scene>.NNNN.sim`, and those in pdc/, ply/, mesh/ and vdb/) that are
/// still there at the listed size. Without this, an earlier run's frames that this run
/// does not write again (the PDC ticks of another frame rate, a renamed fluid's files,
/// frames past this run's end) stayed beside this run's, and Maya or Houdini, which read
/// a sequence by file name, played the two runs mixed. Kept: what the manifests list
/// elsewhere (the objects' meshes in `<scene>Geo/`), files of another size (edited
/// since), and any of `keep` (the scene's input files). Also removed: the files of the
/// frame a killed run was writing (no manifest names them): those named as the last
/// manifest's files with the next frame's number, or PDC ticks one frame's step on, and
/// written after that manifest. And the earlier run's `<scene>.preview.png` (it showed
/// another run's last frame under this run's name). Returns how many frame files went.
std::size_t forgetEarlierRun(const std::filesystem::path& outDir, const std::string& sceneName,
                             const std::vector<std::filesystem::path>& keep);

/// After a command rewrote files of a run's frame (`mesh`: its surfaces at other
/// settings), brings that frame's manifest up to date: each of `files` (inside
/// `outDir`) listed at its new size, or added. Without it the frame read as incomplete
/// (a listed file of another size), so `info`, `render`, the Blender add-on and
/// `--resume` took the run for one that had stopped at frame 0, and a resume wrote the
/// old surfaces back. Nothing happens when the frame has no manifest or it does not read.
void updateFrameManifest(const std::filesystem::path& outDir, const std::string& sceneName,
                         std::int64_t frame, const std::vector<std::filesystem::path>& files);

/// Refuses a run of `sceneName` into `outDir` that would write over another scene's
/// files there: PDC files, surfaces and VDB grids are named after the fluid, not the
/// scene, so two scenes with a fluid of the same name in one folder replaced each
/// other's caches without a word (and `info` then called both runs complete). Looks at
/// the first readable manifest of every other scene in the folder. InputError naming
/// the file, the other scene and its manifest; nothing is changed. `element` and
/// `remedy` are the error's element and what it allows (run's --out by default; mesh
/// names its SIMDIR).
void refuseOtherScenesFiles(
    const std::filesystem::path& outDir, const std::string& sceneName, const cache::Formats& formats,
    const std::vector<std::string>& fluidNames, std::string_view element = "--out",
    std::string_view remedy = "another --out for this scene, or fluids named apart from the other scene's");

}  // namespace softsub::app
