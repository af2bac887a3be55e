#pragma once
/// The surface options shared by `run`, `mesh` and `render`: --voxel-size (resolution) and
/// --blob-radius (smoothing), and their checks against a frame's particle sizes.
#include <string>

#include "core/snapshot.h"
#include "surface/surface.h"

namespace CLI {
class App;
}

namespace softsub::app {

/// Adds --voxel-size and --blob-radius to `cmd`, bound to `settings` (`what` ends their
/// help: where they apply).
void addSurfaceOptions(CLI::App* cmd, surface::SurfaceSettings& settings, const std::string& what);

/// Whether either option was changed from its default.
[[nodiscard]] bool surfaceOptionsGiven(const surface::SurfaceSettings& settings);

/// InputError naming --voxel-size when the voxel is too small to mesh a fluid of `frame`
/// (below surface::minimumVoxelSize for its particle size and the blob radius), or naming
/// the fluid's ParticleSize or Particles in `source` (the scene or recording the frame
/// comes from) when the default voxel is too small or a particle is beyond the grid's
/// reach (surface::gridReach). Call it only when surfaces will be made. Unless `quiet`,
/// warns on stderr about a --voxel-size coarser than a fluid's blob radius.
void checkSurfaceOptions(const surface::SurfaceSettings& settings, const FrameSnapshot& frame,
                         const std::string& source, bool quiet);

}  // namespace softsub::app
