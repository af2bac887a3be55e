#pragma once
/// The fluids' surfaces as per-frame files: a FrameObserver that meshes each fluid of
/// every frame it is given and writes `<out>/mesh/<Fluid>.NNNN.obj` (OBJ with normals)
/// and/or `<out>/vdb/<Fluid>.NNNN.vdb` (the level set), each file atomically.
#include <filesystem>
#include <string>
#include <vector>

#include "cache/obj_format.h"
#include "core/snapshot.h"
#include "surface/surface.h"

namespace softsub::surface {

/// `<dir>/mesh/<fluid>.NNNN.obj` (NNNN = cache::frameTag(frame)).
[[nodiscard]] std::filesystem::path meshPath(const std::filesystem::path& dir, const std::string& fluid,
                                             std::int64_t frame);
/// `<dir>/vdb/<fluid>.NNNN.vdb`.
[[nodiscard]] std::filesystem::path vdbPath(const std::filesystem::path& dir, const std::string& fluid,
                                            std::int64_t frame);

/// A surface mesh as the cache's OBJ encoder takes it, named `name`, coordinates the
/// shortest decimals that read back as the same floats.
[[nodiscard]] cache::ObjectMesh toObjectMesh(const SurfaceMesh& mesh, const std::string& name);

/// The first particle of `fluid` with a finite coordinate beyond `reach` (gridReach) on
/// some axis, or fluid.count() when there is none.
[[nodiscard]] std::size_t firstBeyondReach(const FluidSnapshot& fluid, double reach);

/// Throws softsub::BlowUpError naming the frame, the fluid, the particle and its position
/// when a (finite) particle of `frame` is beyond gridReach of its fluid's voxel: a particle
/// that flew that far cannot be meshed (the simulation keeps it; its surface cannot).
void checkGridReach(const FrameSnapshot& frame, const SurfaceSettings& settings);

/// The surface files of each frame. A fluid with no particle gets an empty OBJ (a comment
/// and its `o` line: valid, no face) and an empty level set, so every frame of a sequence
/// has its file. Identical frames give byte-identical OBJ files.
class SurfaceWriter : public FrameObserver {
 public:
  /// Writes into `outputDir`: OBJ meshes when `mesh`, level sets when `vdb`.
  SurfaceWriter(std::filesystem::path outputDir, bool mesh, bool vdb, SurfaceSettings settings = {});

  /// Meshes every fluid of the frame and writes its files. IoError when one cannot be
  /// written, InputError for a fluid name that cannot be part of a file name, BlowUpError
  /// (checkGridReach, before anything of the frame is written) for a particle too far out.
  void onFrame(const FrameSnapshot& frame) override;

  /// The files the last onFrame wrote, in the order written.
  [[nodiscard]] const std::vector<std::filesystem::path>& lastWritten() const { return written_; }

 private:
  std::filesystem::path dir_;
  bool mesh_;
  bool vdb_;
  SurfaceSettings settings_;
  bool foldersReady_ = false;
  std::vector<std::filesystem::path> written_;
};

}  // namespace softsub::surface
