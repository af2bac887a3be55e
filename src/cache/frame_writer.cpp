#include "cache/frame_writer.h"

#include <fmt/format.h>

#include "cache/atomic_file.h"
#include "cache/naming.h"
#include "cache/pdc_format.h"
#include "cache/ply_format.h"
#include "cache/sim_format.h"
#include "core/error.h"

namespace softsub::cache {
namespace {

constexpr std::string_view kAllowedFormats =
    "a comma-separated list of sim, pdc, ply, mesh, vdb; or all (sim, pdc, ply); or none";

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

[[noreturn]] void badFormats(std::string problem) {
  throw InputError({"command line", 0, "--formats"}, std::move(problem),
                   std::string(kAllowedFormats));
}

}  // namespace

Formats parseFormats(std::string_view list) {
  if (trim(list) == "none") return {false, false, false, false, false};
  Formats f{false, false, false, false, false};
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = list.find(',', start);
    const std::string_view item = trim(list.substr(
        start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
    if (item == "sim") {
      f.sim = true;
    } else if (item == "pdc") {
      f.pdc = true;
    } else if (item == "ply") {
      f.ply = true;
    } else if (item == "mesh") {
      f.mesh = true;
    } else if (item == "vdb") {
      f.vdb = true;
    } else if (item == "all") {
      f.sim = f.pdc = f.ply = true;
    } else if (item.empty()) {
      badFormats(fmt::format("empty format name in '{}'", list));
    } else if (item == "none") {
      badFormats(fmt::format("'none' combined with other formats in '{}'", list));
    } else {
      badFormats(fmt::format("unknown format '{}'", item));
    }
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return f;
}

std::string formatsToString(const Formats& formats) {
  std::string s;
  for (const auto& [on, name] : {std::pair{formats.sim, "sim"}, std::pair{formats.pdc, "pdc"},
                                 std::pair{formats.ply, "ply"}, std::pair{formats.mesh, "mesh"},
                                 std::pair{formats.vdb, "vdb"}}) {
    if (!on) continue;
    if (!s.empty()) s += ',';
    s += name;
  }
  return s.empty() ? "none" : s;
}

FrameWriter::FrameWriter(std::filesystem::path outputDir, std::string sceneName, Formats formats)
    : dir_(std::move(outputDir)), sceneName_(std::move(sceneName)), formats_(formats) {
  checkFileNamePart(sceneName_, "scene name");
}

void FrameWriter::prepareFolders() {
  if (foldersReady_) return;
  ensureDirectory(dir_);
  if (formats_.pdc) ensureDirectory(dir_ / "pdc");
  if (formats_.ply) ensureDirectory(dir_ / "ply");
  if (formats_.sim && !meshes_.empty()) {
    for (const ObjectMesh& mesh : meshes_) checkFileNamePart(mesh.name, "Object/Name");
    ensureDirectory(dir_ / (sceneName_ + "Geo"));
    for (const ObjectMesh& mesh : meshes_) {
      std::filesystem::path path = dir_ / geometryFileName(sceneName_, mesh.name);
      writeFileAtomic(path, encodeObj(mesh));
      written_.push_back(std::move(path));
    }
  }
  foldersReady_ = true;
}

void FrameWriter::onFrame(const FrameSnapshot& frame) {
  written_.clear();
  if (!formats_.sim && !formats_.pdc && !formats_.ply) return;
  // Names first: a bad fluid name is refused before any file of the frame is written.
  std::vector<std::filesystem::path> pdcPaths;
  if (formats_.pdc) {
    pdcPaths.reserve(frame.fluids.size());
    for (const FluidSnapshot& fluid : frame.fluids) {
      pdcPaths.push_back(pdcPath(dir_, fluid.name, frame.frame, frame.framesPerSecond));
    }
  }
  prepareFolders();  // on the first frame also the objects' meshes
  if (formats_.pdc) {
    for (std::size_t f = 0; f < frame.fluids.size(); ++f) {
      encodePdcInto(buffer_, frame.fluids[f]);
      writeFileAtomic(pdcPaths[f], buffer_);
      written_.push_back(pdcPaths[f]);
    }
  }
  if (formats_.ply) {
    encodePlyInto(buffer_, frame);
    std::filesystem::path path = plyPath(dir_, sceneName_, frame.frame);
    writeFileAtomic(path, buffer_);
    written_.push_back(std::move(path));
  }
  if (formats_.sim) {
    encodeSimInto(buffer_, frame);
    std::filesystem::path path = simPath(dir_, sceneName_, frame.frame);
    writeFileAtomic(path, buffer_);
    written_.push_back(std::move(path));
  }
}

}  // namespace softsub::cache
