#include "cmd_mesh.h"

#include <chrono>
#include <cstdio>
#include <optional>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "cache/folder_lock.h"
#include "cache/frame_writer.h"
#include "core/error.h"
#include "number_checks.h"
#include "progress.h"
#include "render_playback.h"
#include "run_journal.h"
#include "session/playback.h"
#include "surface/surface_writer.h"
#include "surface_options.h"
#include "text_format.h"

namespace softsub::app {

CLI::App* addMeshCommand(CLI::App& root, MeshOptions& o) {
  CLI::App* mesh = root.add_subcommand(
      "mesh", "Write the fluids' surfaces (mesh/*.obj, vdb/*.vdb) of a recorded folder");
  mesh->add_option("SIMDIR", o.folder, "The recorded folder (<scene>Sim) or one of its .sim files")
      ->required()
      ->check(nonEmptyPath(false));
  mesh->add_option("--formats", o.formats, "Surface formats: mesh, vdb or mesh,vdb")->capture_default_str();
  mesh->add_option(
          "--scene", o.scene,
          "The scene file, for the fluids' particle sizes (default: <scene>.scene beside the folder; "
          "without one every fluid is meshed at ParticleSize 1, with a warning)")
      ->check(nonEmptyPath(false));
  addSurfaceOptions(mesh, o.surface, "");
  mesh->add_flag("-q,--quiet", o.quiet, "Print nothing but errors");
  return mesh;
}

int meshCommand(const MeshOptions& o) {
  constexpr const char* kSurfaceFormats = "mesh, vdb or mesh,vdb";
  // run's parser, with what mesh takes as the rule: run's own list would name formats
  // that mesh refuses.
  const cache::Formats formats = [&] {
    try {
      return cache::parseFormats(o.formats);
    } catch (const InputError& e) {
      throw InputError(e.where(), e.problem(), kSurfaceFormats);
    }
  }();
  if (formats.sim || formats.pdc || formats.ply || !(formats.mesh || formats.vdb))
    throw InputError({"command line", 0, "--formats"},
                     fmt::format("'{}' is not a surface format list", o.formats), kSurfaceFormats);
  // One writer at a time in the folder (a run still writing it, or a second mesh): the
  // lock first, then the folder's frames as they are under it.
  const cache::FolderLock lock(session::Playback(o.folder, o.scene).folder(), "mesh",
                               InputLocation{"command line", 0, "SIMDIR"},
                               "wait for it to end: a folder being written has frames still to come");
  const session::Playback playback(o.folder, o.scene);
  const FrameSnapshot first = playback.load(0);
  checkSurfaceOptions(o.surface, first, o.folder, o.quiet);
  // Surfaces are named after their fluid: a folder shared with another scene whose
  // manifests list surfaces of the same names is refused, as run refuses it.
  {
    std::vector<std::string> fluids;
    for (const FluidSnapshot& f : first.fluids) fluids.push_back(f.name);
    refuseOtherScenesFiles(playback.folder(), playback.sceneName(), formats, fluids, "SIMDIR",
                           "mesh a folder of one scene, or run the scenes into folders of their own");
  }
  const surface::SurfaceSettings& settings = o.surface;
  surface::SurfaceWriter writer(playback.folder(), formats.mesh, formats.vdb, settings);

  const bool chatty = stderrIsTerminal() && !o.quiet;
  // The sizes decide the surfaces (a surface of ParticleSize 1 around particles of 0.3
  // encloses 14 times their volume), and frames or scenes left out are missing surfaces:
  // warnings, also where stderr is not a terminal (a farm's log).
  if (!o.quiet)
    for (const std::string& w :
         playbackWarnings(playback, "every fluid is meshed at ParticleSize 1", "--scene"))
      fmt::print(stderr, "warning: {}\n", w);
  const std::int64_t lastFrame = playback.frameNumbers().back();
  std::size_t particles = 0;
  std::optional<ProgressLine> progress;
  const auto start = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < playback.frameCount(); ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    const FrameSnapshot frame = playback.load(i);
    if (!progress) {
      for (const FluidSnapshot& f : frame.fluids) particles += f.ids.size();
      progress.emplace(chatty, lastFrame, particles, playback.frameCount());
      progress->begin(frame.frame, "meshing");
    }
    writer.onFrame(frame);
    updateFrameManifest(playback.folder(), playback.sceneName(), frame.frame, writer.lastWritten());
    solver::FrameProgress p;
    p.frame = frame.frame;
    p.lastFrame = lastFrame;
    p.writeSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    progress->update(p);
  }
  if (progress) progress->end();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (chatty)
    fmt::print(stderr, "done: {} meshed, {:.2f} s, output: {}\n",
               countOf(static_cast<std::uint64_t>(playback.frameCount()), "frame"), seconds,
               playback.folder().generic_string());
  return static_cast<int>(ExitCode::Ok);
}

}  // namespace softsub::app
