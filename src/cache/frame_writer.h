#pragma once
/// The cache writer the frame loop feeds: writes each frame's `.sim`, `.pdc` and `.ply`
/// files into the output folder, each file atomically.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "cache/obj_format.h"
#include "core/snapshot.h"

namespace softsub::cache {

/// Which cache formats to write.
struct Formats {
  bool sim = true;  ///< `<scene>.NNNN.sim` per frame
  bool pdc = true;  ///< `pdc/<Fluid>Shape.<ticks>.pdc` per fluid and frame
  bool ply = true;  ///< `ply/<scene>.NNNN.ply` per frame
  /// `mesh/<Fluid>.NNNN.obj` per fluid and frame: the fluid's surface (module surface's
  /// SurfaceWriter, not FrameWriter). Off by default and not part of `all`: slow.
  bool mesh = false;
  /// `vdb/<Fluid>.NNNN.vdb` per fluid and frame: the surface's level set (SurfaceWriter).
  bool vdb = false;
};

/// Parses a `--formats` value: a comma-separated list of `sim`, `pdc`, `ply`, `mesh`,
/// `vdb`, or `all` (sim, pdc and ply: the surfaces are opt-in), or `none`. InputError
/// (element "--formats") listing the allowed names otherwise.
[[nodiscard]] Formats parseFormats(std::string_view list);

/// The canonical spelling of `formats` ("sim,pdc,ply", "sim,mesh", "none", ...);
/// parseFormats reads it.
[[nodiscard]] std::string formatsToString(const Formats& formats);

/// Writes the selected cache files of every frame it is given. Folders are created on
/// the first frame; the `.sim` file is written last, so a frame whose `.sim` exists has
/// all its other files too. Identical snapshots give byte-identical files.
class FrameWriter : public FrameObserver {
 public:
  /// Writes into `outputDir` (e.g. `<scene>Sim`), naming files after `sceneName`.
  FrameWriter(std::filesystem::path outputDir, std::string sceneName, Formats formats = {});

  /// The rigid bodies' meshes: with `.sim` output, each is written once, before the
  /// first frame, to `<scene>Geo/<name>.obj` in the output folder (geometryFileName).
  void setObjectMeshes(std::vector<ObjectMesh> meshes) { meshes_ = std::move(meshes); }

  /// Writes the frame's files; IoError if one cannot be written (earlier frames stay intact).
  void onFrame(const FrameSnapshot& frame) override;

  /// The files the last onFrame wrote, in the order written.
  [[nodiscard]] const std::vector<std::filesystem::path>& lastWritten() const { return written_; }

  /// The output folder.
  [[nodiscard]] const std::filesystem::path& outputDir() const { return dir_; }

 private:
  void prepareFolders();

  std::filesystem::path dir_;
  std::string sceneName_;
  Formats formats_;
  bool foldersReady_ = false;
  std::string buffer_;  ///< reused encoding buffer: no per-frame growth after the first
  std::vector<std::filesystem::path> written_;
  std::vector<ObjectMesh> meshes_;
};

}  // namespace softsub::cache
