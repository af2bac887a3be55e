#pragma once
/// Per-frame manifests: the file written last for a frame, listing every file of that
/// frame with its size. A frame is complete exactly when its manifest exists and every
/// file it lists is there with that size; `softsub run --resume` continues after the
/// last such frame that has a checkpoint. docs/cache-formats.md, "Manifests".
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace softsub::cache {

/// One file of a frame, relative to the output folder (generic '/' separators).
struct ManifestEntry {
  std::string path;
  std::uint64_t bytes = 0;
};

/// What a manifest records.
struct Manifest {
  std::int64_t frame = 0;
  int substeps = 0;               ///< substeps the frame took (adaptive runs vary)
  std::uint64_t fingerprint = 0;  ///< the run's settings (a hash; see `run --resume`)
  std::vector<ManifestEntry> files;
  std::optional<ManifestEntry> checkpoint;  ///< the frame's checkpoint, when one was written
};

/// `<dir>/manifest/<scene>.NNNN.manifest`.
[[nodiscard]] std::filesystem::path manifestPath(const std::filesystem::path& dir, std::string_view sceneName,
                                                 std::int64_t frame);
/// `<dir>/checkpoint/<scene>.NNNN.state`.
[[nodiscard]] std::filesystem::path checkpointPath(const std::filesystem::path& dir, std::string_view sceneName,
                                                   std::int64_t frame);

/// The manifest's text (one line per field; stable, so identical runs give identical bytes).
[[nodiscard]] std::string encodeManifest(const Manifest& manifest);
/// Parses a manifest; InputError naming `file`, the line and the problem when it is not one.
[[nodiscard]] Manifest decodeManifest(std::string_view text, const std::string& file);
/// The manifest file at `path`, or nothing when it is missing, cannot be read or is not
/// one (for readers to whom such a manifest says nothing).
[[nodiscard]] std::optional<Manifest> readManifestIfValid(const std::filesystem::path& path);

/// The entry for `file` (inside `dir`) as it is on disk now; IoError if it cannot be
/// looked at.
[[nodiscard]] ManifestEntry entryOf(const std::filesystem::path& dir, const std::filesystem::path& file);

/// Why the frame a manifest describes is not complete ("" when it is): a listed file is
/// missing or has another size. With `needCheckpoint`, a missing checkpoint counts too.
[[nodiscard]] std::string incompleteReason(const std::filesystem::path& dir, const Manifest& manifest,
                                           bool needCheckpoint);

/// Frames that have a manifest of `sceneName` in `dir`, ascending (none when the folder
/// does not exist).
[[nodiscard]] std::vector<std::int64_t> manifestFrames(const std::filesystem::path& dir, std::string_view sceneName);
/// The scene names with at least one frame manifest in `dir`, sorted.
[[nodiscard]] std::vector<std::string> manifestSceneNames(const std::filesystem::path& dir);
/// Frames that have a checkpoint of `sceneName` in `dir`, ascending.
[[nodiscard]] std::vector<std::int64_t> checkpointFrames(const std::filesystem::path& dir, std::string_view sceneName);

/// Removes the temporary files (`.<name>.tmp.<host>.<pid>.<n>`, writeFileAtomic's) that a
/// killed run on this host left in `dir` and its subfolders (one level), skipping those
/// of a process still running and those of other hosts. A leftover with this process's
/// own id counts as stale: call this before the process writes into `dir`. Returns how
/// many were removed. Errors are ignored: a leftover is harmless.
std::size_t removeStaleTemporaries(const std::filesystem::path& dir);

}  // namespace softsub::cache
