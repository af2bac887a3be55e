#include "surface_options.h"

#include <CLI/CLI.hpp>
#include <cstdio>

#include <fmt/format.h>

#include "core/error.h"
#include "number_checks.h"
#include "surface/surface_writer.h"

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

void checkSurfaceOptions(const surface::SurfaceSettings& s, const FrameSnapshot& frame,
                         const std::string& source, bool quiet) {
  for (const FluidSnapshot& f : frame.fluids) {
    const double least = surface::minimumVoxelSize(f.particleSize, s);
    const double voxel = surface::voxelSizeFor(f.particleSize, s);
    if (least > surface::kMaxVoxelSize)
      throw InputError(
          {source, 0, fmt::format("Fluid '{}'/ParticleSize", f.name)},
          fmt::format("{:g} is too large for surfaces: the finest voxel its blob radius allows ({:g}) is "
                      "above the largest the surfaces' grid takes ({:g})",
                      f.particleSize, least, surface::kMaxVoxelSize),
          fmt::format("ParticleSize <= {:g} with surfaces at blob radius {:g}",
                      surface::kMaxVoxelSize / (least / f.particleSize), s.radiusScale));
    if (s.voxelSize > surface::kMaxVoxelSize)
      throw InputError({"command line", 0, "--voxel-size"},
                       fmt::format("{:g} is above the largest voxel the surfaces' grid takes", s.voxelSize),
                       fmt::format("at most {:g}", surface::kMaxVoxelSize));
    if (s.voxelSize <= 0.0 && voxel > surface::kMaxVoxelSize)
      throw InputError(
          {source, 0, fmt::format("Fluid '{}'/ParticleSize", f.name)},
          fmt::format("{:g} is too large for surfaces: the default voxel, half of it ({:g}), is above "
                      "the largest the surfaces' grid takes",
                      f.particleSize, voxel),
          fmt::format("ParticleSize <= {:g} with surfaces, or --voxel-size {:g} to {:g}",
                      2.0 * surface::kMaxVoxelSize, least, surface::kMaxVoxelSize));
    if (s.voxelSize > 0.0 && s.voxelSize < least)
      throw InputError({"command line", 0, "--voxel-size"},
                       fmt::format("{:g} is too small for fluid '{}' (particle size {:g})", s.voxelSize, f.name,
                                   f.particleSize),
                       fmt::format("at least {:g} (blob radius / 64, and never below {:g})", least,
                                   surface::kMinVoxelSize));
    // Coarser than the blob radius a lone blob is under two voxels across: its surface
    // comes out displaced by most of a voxel, or empty. Warned, not refused: a voxel that
    // coarse is also the only way to mesh a fluid beyond the finer grid's reach.
    if (const double blob = s.radiusScale * f.particleSize; s.voxelSize > blob && !quiet)
      fmt::print(
          stderr,
          "warning: --voxel-size {:g} is coarser than fluid '{}''s blob radius ({:g}): its surface will be "
          "displaced by up to a voxel or empty; at most {:g} keeps it\n",
          s.voxelSize, f.name, blob, blob);
    if (s.voxelSize <= 0.0 && surface::belowVoxelFloor(voxel, least))
      throw InputError({source, 0, fmt::format("Fluid '{}'/ParticleSize", f.name)},
                       fmt::format("{:g} is too small for surfaces: the default voxel, half of it ({:g}), is below "
                                   "the smallest the surfaces' grid takes",
                                   f.particleSize, voxel),
                       fmt::format("ParticleSize >= {:g} with surfaces, or --voxel-size {:g} or more",
                                   2.0 * surface::kMinVoxelSize, least));
    const double reach = surface::gridReach(voxel);
    if (const std::size_t i = surface::firstBeyondReach(f, reach); i < f.count()) {
      const float* p = &f.positions[3 * i];
      throw InputError({source, 0, fmt::format("Fluid '{}'/Particles", f.name)},
                       fmt::format("particle id {} at ({:g}, {:g}, {:g}) is too far from the origin for the surfaces' "
                                   "voxel grid (2^30 voxels of {:g})",
                                   f.ids[i], p[0], p[1], p[2], voxel),
                       fmt::format("|x|, |y|, |z| <= {:g} with surfaces; or a larger --voxel-size", reach));
    }
  }
}

}  // namespace softsub::app
