// `softsub info` on cache files (.sim, .pdc, .ply), a run's journal (.manifest, .state)
// and output folders.
#include <algorithm>
#include <array>
#include <filesystem>
#include <map>
#include <optional>

#include <fmt/format.h>

#include "cache/atomic_file.h"
#include "cache/folder_lock.h"
#include "cache/manifest.h"
#include "cache/naming.h"
#include "cache/pdc_format.h"
#include "cache/ply_format.h"
#include "cache/sim_format.h"
#include "cmd_info.h"
#include "core/aabb.h"
#include "core/error.h"
#include "run_journal.h"
#include "solver/checkpoint.h"
#include "text_format.h"

namespace softsub::app {

namespace {

std::string_view pdcTypeName(cache::PdcType t) {
  switch (t) {
    case cache::PdcType::Int: return "int";
    case cache::PdcType::IntArray: return "int array";
    case cache::PdcType::Double: return "double";
    case cache::PdcType::DoubleArray: return "double array";
    case cache::PdcType::Vector: return "vector";
    case cache::PdcType::VectorArray: return "vector array";
  }
  return "?";
}

std::string_view plyTypeName(cache::PlyScalar t) {
  constexpr std::array<std::string_view, 8> names{"int8",  "uint8",  "int16",   "uint16",
                                                  "int32", "uint32", "float32", "float64"};
  return names[static_cast<std::size_t>(t)];
}

}  // namespace

void printSimInfo(const std::string& path) {
  const cache::SimFile sim = cache::readSimFile(path);
  std::size_t total = 0;
  for (const FluidSnapshot& f : sim.frame.fluids) total += f.count();
  fmt::print("sim {}: frame {}, time {:g} s, {} fluids, {} particles, {} objects\n", path, sim.frame.frame,
             sim.frame.time, sim.frame.fluids.size(), groupThousands(total), sim.frame.objects.size());
  for (const FluidSnapshot& f : sim.frame.fluids) {
    Aabb box;
    for (std::size_t k = 0; k < f.count(); ++k)
      box.add(f.positions[3 * k], f.positions[3 * k + 1], f.positions[3 * k + 2]);
    fmt::print("  {}: {} particles, bounds {}\n", f.name, groupThousands(f.count()), describeBox(box));
  }
  for (const cache::SimObject& o : sim.frame.objects)
    fmt::print("  object {}: position {:g} {:g} {:g}, rotation {:g} {:g} {:g} {:g}, scale {:g}, file {}\n",
               o.name, o.position[0], o.position[1], o.position[2], o.rotation[0], o.rotation[1],
               o.rotation[2], o.rotation[3], o.uniformScale, o.filename);
}

void printPdcInfo(const std::string& path) {
  const cache::PdcFile pdc = cache::readPdcFile(path);
  fmt::print("pdc {}: version {}, byte order {}, {} particles, {} attributes\n", path, pdc.version,
             pdc.byteOrder, groupThousands(static_cast<std::uint64_t>(pdc.count)), pdc.attributes.size());
  for (const cache::PdcAttribute& a : pdc.attributes)
    fmt::print("  {}: {}, {} values\n", a.name, pdcTypeName(a.type), groupThousands(a.values.size()));
  if (const cache::PdcAttribute* p = pdc.find("position"); p && p->type == cache::PdcType::VectorArray) {
    Aabb box;
    for (std::size_t k = 0; k + 2 < p->values.size(); k += 3) box.add(p->values[k], p->values[k + 1], p->values[k + 2]);
    fmt::print("position bounds {}\n", describeBox(box));
  }
}

void printPlyInfo(const std::string& path) {
  const cache::PlyCloud ply = cache::readPlyFile(path);
  fmt::print("ply {}: {}, {} vertices, {} properties", path, ply.format, groupThousands(ply.vertexCount),
             ply.properties.size());
  if (ply.hasFrame) fmt::print(", frame {}, time {:g} s", ply.frame, ply.time);
  fmt::print("\n");
  for (const cache::PlyProperty& p : ply.properties) fmt::print("  {}: {}\n", p.name, plyTypeName(p.type));
  const cache::PlyProperty* x = ply.find("x");
  const cache::PlyProperty* y = ply.find("y");
  const cache::PlyProperty* z = ply.find("z");
  if (x && y && z) {
    Aabb box;
    for (std::size_t k = 0; k < ply.vertexCount; ++k) box.add(x->values[k], y->values[k], z->values[k]);
    fmt::print("position bounds {}\n", describeBox(box));
  }
  if (const cache::PlyProperty* fluid = ply.find("fluid")) {
    std::map<long long, std::size_t> counts;
    for (double v : fluid->values) ++counts[static_cast<long long>(v)];
    for (const auto& [index, n] : counts) {
      const bool named = index >= 0 && static_cast<std::size_t>(index) < ply.fluidNames.size();
      fmt::print("  fluid {} {}: {} particles\n", index, named ? ply.fluidNames[static_cast<std::size_t>(index)] : "",
                 groupThousands(n));
    }
  }
}

void printManifestInfo(const std::string& path) {
  const cache::Manifest m = cache::decodeManifest(cache::readFileBytes(path), path);
  // The output folder is the manifest's folder's parent.
  const std::filesystem::path dir = std::filesystem::absolute(path).parent_path().parent_path();
  std::uint64_t bytes = 0;
  for (const cache::ManifestEntry& e : m.files) bytes += e.bytes;
  const std::string why = cache::incompleteReason(dir, m, false);
  fmt::print("manifest {}: frame {}, {} substeps, run {:016x}, {} files, {} bytes: {}\n", path, m.frame, m.substeps,
             m.fingerprint, m.files.size(), groupThousands(bytes), why.empty() ? "complete" : "incomplete, " + why);
  for (const cache::ManifestEntry& e : m.files) fmt::print("  {} ({} bytes)\n", e.path, groupThousands(e.bytes));
  if (m.checkpoint) {
    const std::string ck = cache::incompleteReason(dir, cache::Manifest{m.frame, m.substeps, m.fingerprint, {}, m.checkpoint}, true);
    const bool removed = !std::filesystem::exists(dir / m.checkpoint->path);
    fmt::print("  checkpoint {} ({} bytes){}\n", m.checkpoint->path, groupThousands(m.checkpoint->bytes),
               ck.empty() ? "" : removed ? ": removed since (a run keeps its two newest)" : ": " + ck);
  }
}

void printCheckpointInfo(const std::string& path) {
  const solver::CheckpointInfo c = solver::checkpointInfo(cache::readFileBytes(path), path);
  fmt::print("checkpoint {}: frame {}, {} particles, {} objects, run {:016x}, intact\n", path, c.frame,
             groupThousands(c.particles), c.bodies, c.fingerprint);
}

void printRunFolderInfo(const std::string& dirText) {
  const std::filesystem::path dir(dirText);
  // A run (or mesh, or the viewer's S) writing the folder now: what follows is a moment
  // of it, and --resume would be refused until it ends.
  const std::optional<std::string> writer = cache::FolderLock::holder(dir);
  if (writer) fmt::print("{}: being written now by {}\n", dirText, *writer);
  const std::vector<std::string> names = cache::manifestSceneNames(dir);
  if (names.empty()) {
    // Frames without manifests (the viewer's S writes none; an older softsub's run): what
    // render, mesh and the add-on would play, said per scene, rather than refused.
    std::map<std::string, std::vector<std::int64_t>> byScene;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
      const std::optional<cache::SimFileName> name =
          cache::parseSimFileName(entry.path().filename().string());
      if (name && entry.is_regular_file(ec)) byScene[name->scene].push_back(name->frame);
    }
    if (byScene.empty())
      throw InputError(
          {dirText, 0, {}},
          "no manifest/ with frame manifests and no .sim frames: not a softsub "
          "output folder",
          "a folder `softsub run` or the viewer's S wrote (.sim frames, manifest/<scene>.NNNN.manifest)");
    for (auto& [scene, numbers] : byScene) {
      std::sort(numbers.begin(), numbers.end());
      numbers.erase(std::unique(numbers.begin(), numbers.end()), numbers.end());
      const std::int64_t missing =
          numbers.back() - numbers.front() + 1 - static_cast<std::int64_t>(numbers.size());
      fmt::print(
          "frames of {} in {}: {} frame{}, {}..{}{}, without manifests (as the viewer's S writes them): "
          "render, mesh and the Blender add-on play them; run --resume has nothing to continue\n",
          scene, dirText, numbers.size(), numbers.size() == 1 ? "" : "s", numbers.front(), numbers.back(),
          missing > 0 ? fmt::format(" ({} missing in between)", missing) : std::string());
    }
    if (byScene.size() > 1)
      fmt::print(
          "  the folder holds frames of {} scenes: render and mesh take the one the folder is named "
          "after (<scene>Sim), else the one with the most frames, unless given one of a scene's .sim "
          "files\n",
          byScene.size());
    return;
  }
  for (const std::string& name : names) {
    const RunFrames run = readRunFrames(dir, name);
    fmt::print("run {} in {}: ", name, dirText);
    if (run.complete == 0) {
      fmt::print("no complete frame ({})\n", run.stop);
    } else {
      // Frame 0 is the initial state: it took no substep.
      int fewest = 0, most = 0;
      for (std::size_t k = 1; k < run.complete; ++k) {
        fewest = most == 0 ? run.manifests[k].substeps : std::min(fewest, run.manifests[k].substeps);
        most = std::max(most, run.manifests[k].substeps);
      }
      const std::string substeps = most == 0        ? std::string("no substep yet")
                                   : fewest == most ? fmt::format("{} substeps a frame", most)
                                                    : fmt::format("{}..{} substeps a frame", fewest, most);
      fmt::print("frames 0..{} complete, {}, run {:016x}\n", run.complete - 1, substeps,
                 run.manifests[run.complete - 1].fingerprint);
      if (!run.stop.empty()) fmt::print("  then: {}\n", run.stop);
    }
    const std::vector<std::int64_t> checkpoints = cache::checkpointFrames(dir, name);
    std::string list;
    for (const std::int64_t f : checkpoints) list += (list.empty() ? "" : ", ") + std::to_string(f);
    fmt::print("  checkpoints: {}\n", checkpoints.empty() ? std::string("none") : list);
    // Where --resume would start: the checkpoints it would try, newest first, until one
    // reads intact (its checksum) and is its frame's, of this run (the manifest's
    // settings: a checkpoint copied from another run is skipped), as resumeFrom does.
    std::int64_t resumeAt = -1;
    for (const std::size_t k : run.checkpointed(dir)) {
      const cache::Manifest& m = run.manifests[k];
      const std::filesystem::path p = dir / m.checkpoint->path;
      try {
        const solver::CheckpointInfo c = solver::checkpointInfo(cache::readFileBytes(p), p.string());
        if (c.frame == m.frame && c.fingerprint == m.fingerprint) {
          resumeAt = m.frame;
          break;
        }
        if (c.frame == m.frame)
          fmt::print("  {}: made by another run (other settings): skipped\n", p.string());
      } catch (const std::exception& e) {
        fmt::print("  {}\n", e.what());
      }
    }
    if (writer) fmt::print("  run --resume would be refused while the folder is being written\n");
    else if (resumeAt >= 0) fmt::print("  run --resume would continue after frame {}\n", resumeAt);
    else
      fmt::print("  run --resume would start over at frame 0\n");
  }
}

}  // namespace softsub::app
