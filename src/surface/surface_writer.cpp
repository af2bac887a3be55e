#include "surface/surface_writer.h"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <system_error>

#include <fmt/format.h>

#include "cache/atomic_file.h"
#include "cache/naming.h"
#include "core/error.h"

namespace softsub::surface {
namespace {

/// The double whose shortest decimal is the float's shortest decimal (0.1f -> 0.1, not
/// 0.10000000149011612): the OBJ stays as short as the float needs.
double shortDouble(float v) {
  char buf[32];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  double d = static_cast<double>(v);
  if (ec == std::errc()) std::from_chars(buf, end, d);
  return d;
}

std::filesystem::path fileIn(const std::filesystem::path& dir, const char* folder, const std::string& fluid,
                             std::int64_t frame, const char* extension) {
  return dir / folder / (fluid + "." + cache::frameTag(frame) + extension);
}

}  // namespace

std::filesystem::path meshPath(const std::filesystem::path& dir, const std::string& fluid, std::int64_t frame) {
  return fileIn(dir, "mesh", fluid, frame, ".obj");
}

std::filesystem::path vdbPath(const std::filesystem::path& dir, const std::string& fluid, std::int64_t frame) {
  return fileIn(dir, "vdb", fluid, frame, ".vdb");
}

cache::ObjectMesh toObjectMesh(const SurfaceMesh& mesh, const std::string& name) {
  cache::ObjectMesh out;
  out.name = name;
  out.comment = "fluid surface";
  out.vertices.reserve(mesh.vertices.size());
  for (const auto& v : mesh.vertices) out.vertices.push_back({shortDouble(v[0]), shortDouble(v[1]), shortDouble(v[2])});
  out.normals.reserve(mesh.normals.size());
  for (const auto& n : mesh.normals) out.normals.push_back({shortDouble(n[0]), shortDouble(n[1]), shortDouble(n[2])});
  out.triangles = mesh.triangles;
  return out;
}

SurfaceWriter::SurfaceWriter(std::filesystem::path outputDir, bool mesh, bool vdb, SurfaceSettings settings)
    : dir_(std::move(outputDir)), mesh_(mesh), vdb_(vdb), settings_(settings) {}

std::size_t firstBeyondReach(const FluidSnapshot& fluid, double reach) {
  for (std::size_t i = 0; i < fluid.count(); ++i)
    for (int k = 0; k < 3; ++k) {
      const float x = fluid.positions[3 * i + static_cast<std::size_t>(k)];
      if (std::isfinite(x) && std::abs(double(x)) > reach) return i;
    }
  return fluid.count();
}

void checkGridReach(const FrameSnapshot& frame, const SurfaceSettings& settings) {
  for (const FluidSnapshot& fluid : frame.fluids) {
    const double voxel = voxelSizeFor(fluid.particleSize, settings);
    const double reach = gridReach(voxel);
    if (const std::size_t i = firstBeyondReach(fluid, reach); i < fluid.count()) {
      const float* p = &fluid.positions[3 * i];
      throw BlowUpError(fmt::format(
          "frame {}: fluid '{}', particle id {} is at ({:g}, {:g}, {:g}), too far from the origin for the "
          "surface's voxel grid (|x|, |y|, |z| <= {:g}: 2^30 voxels of {:g}); keep the particles in with an "
          "<Environment>, or give a larger --voxel-size",
          frame.frame, fluid.name, fluid.ids[i], p[0], p[1], p[2], reach, voxel));
    }
  }
}

void SurfaceWriter::onFrame(const FrameSnapshot& frame) {
  written_.clear();
  if (!mesh_ && !vdb_) return;
  for (const FluidSnapshot& fluid : frame.fluids) cache::checkFileNamePart(fluid.name, "Fluid/Name");
  checkGridReach(frame, settings_);
  if (!foldersReady_) {
    if (mesh_) cache::ensureDirectory(dir_ / "mesh");
    if (vdb_) cache::ensureDirectory(dir_ / "vdb");
    foldersReady_ = true;
  }
  for (const FluidSnapshot& fluid : frame.fluids) {
    const LevelSet level = LevelSet::fromParticles(fluid.positions, fluid.particleSize, settings_);
    if (mesh_) {
      std::filesystem::path path = meshPath(dir_, fluid.name, frame.frame);
      cache::writeFileAtomic(path, cache::encodeObj(toObjectMesh(level.mesh(), fluid.name)));
      written_.push_back(std::move(path));
    }
    if (vdb_) {
      std::filesystem::path path = vdbPath(dir_, fluid.name, frame.frame);
      level.writeVdb(path, fluid.name);  // atomic: a temporary name, then renamed
      written_.push_back(std::move(path));
    }
  }
}

}  // namespace softsub::surface
