#pragma once
/// `softsub mesh SIMDIR`: the fluids' surfaces of a recorded folder, afterwards.
#include <string>

#include "surface/surface.h"

namespace CLI {
class App;
}

namespace softsub::app {

/// The options of `mesh`.
struct MeshOptions {
  std::string folder;              ///< the recorded folder (or one of its .sim files)
  std::string formats = "mesh";    ///< mesh, vdb or both (comma-separated)
  std::string scene;               ///< --scene: the scene file (default: <scene>.scene beside the folder)
  surface::SurfaceSettings surface;  ///< --voxel-size, --blob-radius
  bool quiet = false;              ///< nothing on stderr but errors
};

/// Adds the `mesh` subcommand bound to `options` and returns it.
CLI::App* addMeshCommand(CLI::App& root, MeshOptions& options);

/// Writes `mesh/<Fluid>.NNNN.obj` and/or `vdb/<Fluid>.NNNN.vdb` into the folder for every
/// recorded frame, with particle sizes from the scene file beside the folder. Returns the
/// exit code; InputError for bad options or an invalid folder, IoError when a file cannot
/// be read or written.
int meshCommand(const MeshOptions& options);

}  // namespace softsub::app
