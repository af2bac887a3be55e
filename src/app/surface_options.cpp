#include "surface_options.h"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "core/error.h"
#include "number_checks.h"

namespace softsub::app {

namespace {
constexpr double kMinBlobRadius = 1.0;
constexpr double kMaxBlobRadius = 5.0;
}  // namespace

void addSurfaceOptions(CLI::App* cmd, surface::SurfaceSettings& s, const std::string& what) {
  cmd->add_option("--voxel-size", s.voxelSize,
                  "Surface voxel edge in scene units: the resolution (default 0: half each fluid's particle size)" +
                      what)
      ->check(finiteNonNegative());
  cmd->add_option("--blob-radius", s.radiusScale,
                  fmt::format("Surface blob radius as a multiple of the particle size: the smoothing, {} to {} "
                              "(default {}, the seed's){}",
                              kMinBlobRadius, kMaxBlobRadius, surface::SurfaceSettings{}.radiusScale, what))
      ->check(finiteNumberIn(kMinBlobRadius, kMaxBlobRadius, fmt::format("{} to {}", kMinBlobRadius, kMaxBlobRadius)));
}

bool surfaceOptionsGiven(const surface::SurfaceSettings& s) {
  const surface::SurfaceSettings defaults;
  return s.voxelSize != defaults.voxelSize || s.radiusScale != defaults.radiusScale;
}

void checkSurfaceOptions(const surface::SurfaceSettings& s, const FrameSnapshot& frame) {
  if (s.voxelSize <= 0.0) return;
  for (const FluidSnapshot& f : frame.fluids) {
    const double least = surface::minimumVoxelSize(f.particleSize, s);
    if (s.voxelSize < least)
      throw InputError({"command line", 0, "--voxel-size"},
                       fmt::format("{:g} is too small for fluid '{}' (particle size {:g})", s.voxelSize, f.name,
                                   f.particleSize),
                       fmt::format("at least {:g} (blob radius / 64)", least));
  }
}

}  // namespace softsub::app
