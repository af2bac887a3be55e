#include "cmd_run.h"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <limits>
#include <optional>
#include <stdexcept>
#include <utility>

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "cache/atomic_file.h"
#include "cache/folder_lock.h"
#include "cache/frame_writer.h"
#include "cache/manifest.h"
#include "cache/naming.h"
#include "core/error.h"
#include "number_checks.h"
#include "progress.h"
#include "run_journal.h"
#include "scene/compile.h"
#include "scene/schema.h"
#include "scene/writer.h"
#include "scene_source.h"
#include "scene_view.h"
#include "session/object_meshes.h"
#include "solver/checkpoint.h"
#include "solver/energy.h"
#include "solver/frame_loop.h"
#include "solver/stability.h"
#include "stop_signal.h"
#include "surface/surface_writer.h"
#include "surface_options.h"
#include "text_format.h"

namespace softsub::app {

namespace {

constexpr int kPreviewWidth = 960;
constexpr int kPreviewHeight = 540;

constexpr const char* kSeedGroup = "Seed flags (also accepted with one dash, as in the seed)";

/// Remembers the last frame every earlier observer has finished with.
class LastFrame : public FrameObserver {
 public:
  void onFrame(const FrameSnapshot& frame) override { last = frame.frame; }
  std::int64_t last = -1;  ///< -1: none yet
};

/// --stats: one line per frame on stdout with the state's energies (solver/energy.h).
class StatsObserver : public FrameObserver {
 public:
  explicit StatsObserver(const solver::Simulation& sim) : sim_(sim) {}
  void onFrame(const FrameSnapshot& frame) override {
    if (!headerDone_) {
      fmt::print("# frame time kinetic pair gravity bodies total substeps travel lists\n");
      headerDone_ = true;
    }
    const solver::EnergyReport e = solver::measureEnergy(sim_.model(), sim_.state());
    fmt::print("{} {:.9g} {:.9g} {:.9g} {:.9g} {:.9g} {:.9g} {} {:.4g} {}\n", frame.frame, frame.time, e.kinetic, e.pair,
               e.gravity, e.bodies, e.total(), sim_.substeps(), sim_.travelPerSubstep(), sim_.listBuilds());
    std::fflush(stdout);
  }

 private:
  const solver::Simulation& sim_;
  bool headerDone_ = false;
};

/// The schema's declaration of a <Simulation> tag (the one source of its range).
const scene::FieldInfo* simulationField(std::string_view tag) {
  for (const auto& f : scene::fieldsOf<scene::SimulationDesc>())
    if (f.tag == tag) return &f;
  return nullptr;
}

/// Checks a command-line override, when given, against the schema's range for `tag`
/// (every value given is checked: a negative one is out of range, not "unset").
void checkOverride(std::string_view option, std::string_view tag, const std::optional<std::int64_t>& value) {
  if (!value) return;
  const scene::FieldInfo* info = simulationField(tag);
  if (info == nullptr) throw std::logic_error(fmt::format("no <Simulation> field {}", tag));
  if (info->range.contains(static_cast<double>(*value))) return;
  throw InputError({"command line", 0, std::string(option)}, fmt::format("{} is out of range", *value),
                   scene::allowedText(*info));
}

bool anyFormat(const cache::Formats& f) { return f.sim || f.pdc || f.ply || f.mesh || f.vdb; }

/// Everything `run` checks before it reads the scene: the command line itself.
cache::Formats checkCommandLine(const RunOptions& o) {
  checkOverride("--frames", "Frames", o.frames);
  checkOverride("--substeps", "Substeps", o.substeps);
  cache::Formats formats = cache::parseFormats(o.formats);
  if (o.record == 0) formats = {false, false, false, false, false};
  // A run that writes nothing leaves no frames to continue from, nor continues any: a
  // usage error, not a whole simulation that quietly writes nothing.
  if (o.resume && !anyFormat(formats))
    throw InputError({"command line", 0, "--resume"}, "there is nothing to resume: this run writes no files",
                     "--resume with at least one output format (not --formats none or -record 0)");
  return formats;
}

void applyOverrides(const RunOptions& o, scene::SceneDesc& desc) {
  if (o.frames) desc.simulation.frames = static_cast<int>(*o.frames);
  if (o.substeps) desc.simulation.substeps = static_cast<int>(*o.substeps);
  if (!o.integrator.empty()) {
    const auto& names = scene::kIntegratorNames;
    const auto it = std::find(std::begin(names), std::end(names), o.integrator);
    desc.simulation.integrator = static_cast<scene::Integrator>(it - std::begin(names));
  }
}

/// A hash of everything that decides a run's outputs except how many frames it runs:
/// the scene after the overrides, the simulation's starting state (fills placed, bodies'
/// particles where their bodies put them, the bodies' states), the objects' meshes as
/// written to <scene>Geo/, the output and solver options, and the softsub version. A
/// resumed run must match it; leaving the frame count out lets a finished run be extended.
std::uint64_t runFingerprint(const RunOptions& o, scene::SceneDesc desc, const cache::Formats& formats,
                             const solver::Simulation& sim, const std::vector<cache::ObjectMesh>& meshes) {
  desc.simulation.frames = 1;
  std::uint64_t h = hashBytes(scene::writeSceneText(desc));
  const solver::State& initial = sim.state();
  const ParticleStore& s = initial.particles;
  for (const std::vector<float>* a : {&s.px, &s.py, &s.pz, &s.vx, &s.vy, &s.vz})
    h = hashBytes({reinterpret_cast<const char*>(a->data()), a->size() * sizeof(float)}, h);
  for (const rigid::BodyState& b : initial.bodies)
    h = hashBytes(fmt::format("{:a} {:a} {:a} {:a} {:a} {:a} {:a} {:a} {:a} {:a} {:a} {:a} {:a}", b.position.x(),
                              b.position.y(), b.position.z(), b.orientation.w(), b.orientation.x(),
                              b.orientation.y(), b.orientation.z(), b.velocity.x(), b.velocity.y(), b.velocity.z(),
                              b.angularMomentum.x(), b.angularMomentum.y(), b.angularMomentum.z()),
                  h);
  for (const cache::ObjectMesh& mesh : meshes) h = hashBytes(cache::encodeObj(mesh), h);
  const solver::Model& model = sim.model();
  // --stop-recording-at is not a setting: in a batch run it only ends the run, as
  // --frames does, so a run it ended can be extended. Hashed as the "no limit" it was
  // before, so that folders made without it keep their fingerprint.
  const std::string options = fmt::format(
      "softsub {}|formats {}|voxel {:.17g}|blob {:.17g}|adaptive {} {}|speed-limit {:.17g}|record-up-to -1",
      SOFTSUB_VERSION, cache::formatsToString(formats), o.surface.voxelSize, o.surface.radiusScale,
      model.adaptiveSubsteps, model.maxSubsteps, model.maxTravelPerSubstep);
  return hashBytes(options, h);
}

std::string folderText(const std::filesystem::path& dir) {
  std::string s = dir.generic_string();
  if (s.empty()) s = ".";
  if (s.back() != '/') s += '/';
  return s;
}

}  // namespace

CLI::App* addRunCommand(CLI::App& root, RunOptions& o) {
  CLI::App* run = root.add_subcommand(
      "run", "Simulate a scene into frame caches (the embedded default scene when SCENE is omitted)");
  run->add_option("SCENE,-f,--scene", o.scene, ".scene file to simulate (seed: -f FILE)")->check(nonEmptyPath());
  run->add_option("--frames", o.frames, "Frames to simulate (overrides <Simulation><Frames>)")
      ->transform(wholeNumberIn(0, 1000000));
  run->add_option("--substeps", o.substeps,
                  "Updates per frame (overrides <Simulation><Substeps>; seed: -updateNum N)")
      ->transform(wholeNumberIn(1, 10000));
  run->add_option("--out", o.out, "Output folder (default: <sceneDir>/<sceneName>Sim)")->check(nonEmptyPath());
  run->add_option("--formats", o.formats, "Cache formats: sim,pdc,ply,mesh,vdb (any of them), all (sim,pdc,ply) or none; mesh and vdb are fluid surfaces (slow)")
      ->capture_default_str();
  addSurfaceOptions(run, o.surface, "; for mesh and vdb");
  run->add_flag("--stats", o.stats,
                "Print each frame's energies on stdout: frame, time, kinetic, pair, gravity, bodies, total, "
                "substeps, travel, lists");
  run->add_flag("--resume", o.resume,
                "Continue a run that stopped (killed, interrupted, failed) after its last complete frame; the "
                "outputs are byte-identical to an uninterrupted run. Starts at frame 0 when there is nothing "
                "to resume; needs an output format (not --formats none)");
  run->add_option("--checkpoint-every", o.checkpointEvery,
                  "Write the solver state every K frames for --resume (the two newest are kept); 0: never")
      ->transform(wholeNumberIn(0, 1000000))
      ->capture_default_str();
  CLI::Option* adaptive = run->add_flag(
      "--adaptive", o.adaptive,
      "Choose each frame's substeps from the fastest particle, the strongest force and the stability "
      "estimate (at least the scene's Substeps)");
  run->add_option("--max-substeps", o.maxSubsteps,
                  "The most substeps --adaptive may choose for a frame (at least the scene's Substeps; needs "
                  "--adaptive)")
      ->transform(wholeNumberIn(1, 10000))
      ->needs(adaptive)
      ->capture_default_str();
  run->add_option("--speed-limit", o.speedLimit,
                  "Blow-up check: the most interaction distances a particle may cover in one substep; 0: no "
                  "speed check (non-finite values always stop the run)")
      ->check(finiteNumberIn(0.0, 1e6, "0 to 1e6"))
      ->capture_default_str();
  run->add_option("--integrator", o.integrator, "Overrides <Simulation><Integrator>")
      ->check(oneOf(std::vector<std::string>(std::begin(scene::kIntegratorNames), std::end(scene::kIntegratorNames))));
  run->add_flag("-q,--quiet", o.quiet,
                "Print nothing but errors (and a warning when a --preview picture cannot be drawn)");
  run->add_option("--max-particles", o.maxParticles,
                  "Refuse scenes with more particles than this (default: the reader's limit)")
      ->transform(particleCap());
  run->add_flag("--print-scene", o.printScene,
                "Print the scene's text (SCENE's, or the embedded default scene's without it) and exit");
  run->add_flag("--preview", o.preview,
                "Also draw the last frame into <out>/<scene>.preview.png (off-screen, no display needed; "
                "also with --formats none)");
  run->add_option("--record", o.record, "0: write no caches (same as --formats none); 1: write")
      ->transform(wholeNumberIn(0, 1))
      ->group(kSeedGroup);
  run->add_option("--stop-recording-at", o.stopRecordingAt,
                  "Last frame to write; the run ends there too (-1: no limit)")
      ->transform(wholeNumberIn(-1, std::numeric_limits<std::int64_t>::max()))
      ->group(kSeedGroup);
  run->add_option("--draw-per-frame", o.drawPerFrame, "Accepted for the viewer; ignored by run")
      ->group(kSeedGroup);
  return run;
}

int runCommand(const RunOptions& o) {
  if (o.printScene) {
    // The scene this run would read: SCENE's text as it is, once it reads as a valid
    // scene (the overrides are not applied), or the embedded default scene's.
    if (o.scene.empty()) {
      std::fputs(defaultSceneText(), stdout);
    } else {
      (void)loadScene(o.scene, o.maxParticles);
      const std::string text = cache::readFileBytes(o.scene);
      std::fwrite(text.data(), 1, text.size(), stdout);
    }
    return static_cast<int>(ExitCode::Ok);
  }
  // The stop handlers from the start: Ctrl-C or SIGTERM while the scene loads ends the
  // run before its first frame with the same exit code (130) as later (the Blender
  // add-on's Stop sends SIGTERM whenever it is pressed).
  const std::atomic<bool>& stop = installStopHandlers();
  // Everything is checked before any folder or file is created.
  const cache::Formats formats = checkCommandLine(o);
  TerminalNote reading(
      stderrIsTerminal() && !o.quiet,
      fmt::format("reading {} ...", o.scene.empty() ? "the default scene" : displayFile(o.scene)));
  LoadedScene loaded = loadScene(o.scene, o.maxParticles);
  applyOverrides(o, loaded.desc);
  if (o.adaptive && o.maxSubsteps < loaded.desc.simulation.substeps)
    throw InputError(
        {"command line", 0, "--max-substeps"},
        fmt::format("{} is below the scene's Substeps ({}), the fewest --adaptive uses", o.maxSubsteps,
                    loaded.desc.simulation.substeps),
        fmt::format("{} to 10000, or fewer Substeps (--substeps)", loaded.desc.simulation.substeps));
  const std::string& sceneFile = loaded.file;
  const std::string shownFile = displayFile(sceneFile);  // in warnings: one line whatever the name
  // The scene's name names every file of the run and the preview: with neither, no file.
  checkOutputNames(loaded, formats, anyFormat(formats) || o.preview);
  const std::filesystem::path outDir = o.out.empty() ? loaded.defaultOutDir : std::filesystem::path(o.out);
  // The folder's other files this run must not overwrite: checked now, and again once
  // the run holds the folder's lock.
  const auto checkFolder = [&] {
    checkInputsKept(loaded, formats, outDir);
    std::vector<std::string> fluidNames;
    for (const scene::FluidDesc& f : loaded.desc.fluids) fluidNames.push_back(f.name);
    refuseOtherScenesFiles(outDir, loaded.name, formats, fluidNames);
  };
  if (anyFormat(formats)) checkFolder();
  std::int64_t lastFrame = loaded.desc.simulation.frames;
  if (o.stopRecordingAt >= 0) lastFrame = std::min(lastFrame, o.stopRecordingAt);
  // Maya reads a PDC file's time from its name in 32-bit ticks (6000 a second).
  if (formats.pdc && cache::pdcTicks(lastFrame, loaded.desc.simulation.framesPerSecond) >
                         std::numeric_limits<std::int32_t>::max())
    throw InputError({sceneFile, 0, "Simulation"},
                     fmt::format("frame {} at {} frames a second is {} ticks into the PDC cache, past the "
                                 "2147483647 that Maya's 32-bit ticks hold",
                                 lastFrame, loaded.desc.simulation.framesPerSecond,
                                 cache::pdcTicks(lastFrame, loaded.desc.simulation.framesPerSecond)),
                     "fewer Frames or more FramesPerSecond (at most 357913 seconds of animation), or "
                     "--formats without pdc");

  scene::Compiled compiled = scene::compile(loaded.desc);
  compiled.model.adaptiveSubsteps = o.adaptive;
  compiled.model.maxSubsteps = o.maxSubsteps;
  compiled.model.maxTravelPerSubstep = o.speedLimit;
  std::vector<cache::ObjectMesh> meshes = session::objectMeshesForCache(compiled.model, compiled.objectMeshes, loaded.name);
  std::optional<render::RenderScene> view;
  if (o.preview) view = renderSceneOf(loaded.desc, compiled.objectMeshes);
  const std::size_t particles = compiled.model.particleCount();
  // The viewer's stability hint, as a warning: a scene the estimate calls Unstable at its
  // substeps may blow up, or (below the blow-up check's limits) fling its particles and
  // gain energy without stopping. --adaptive takes the estimate's count itself.
  std::optional<std::string> unstable;
  if (!o.adaptive) {
    const solver::StabilityReport s = solver::assessStability(compiled.model, &compiled.state);
    if (s.verdict == solver::StabilityVerdict::Unstable && s.worst < s.pairs.size()) {
      const solver::PairStability& p = s.pairs[s.worst];
      unstable = fmt::format(
          "the stability estimate calls {} / {} unstable at {} substeps a frame: expect a blow-up, or particles "
          "flung about and energy gained; {}",
          p.first, p.second, s.substeps,
          s.minimumSubsteps > 0 ? fmt::format("raise Substeps to {} or use --adaptive", s.minimumSubsteps)
                                : std::string("soften the interaction (no substep count up to 10,000 is stable)"));
    }
  }
  solver::Simulation sim(compiled.model, std::move(compiled.state));
  const std::uint64_t fingerprint = runFingerprint(o, loaded.desc, formats, sim, meshes);
  if (surfaceOptionsGiven(o.surface) && !(formats.mesh || formats.vdb))
    throw InputError({"command line", 0, "--voxel-size/--blob-radius"}, "are for surfaces",
                     "add mesh or vdb to --formats, or leave them out");
  reading.clear();  // before anything else is printed
  if (formats.mesh || formats.vdb) checkSurfaceOptions(o.surface, sim.snapshot(), sceneFile, o.quiet);
  // Progress, notes and the summary are for a person at a terminal; a pipe, a file or a
  // farm log gets errors and warnings only (a warning is about this run's result: a farm
  // log must show it too). --quiet leaves errors alone.
  const bool chatty = stderrIsTerminal() && !o.quiet;
  if (!o.quiet) {
    for (const std::string& w : loaded.warnings) fmt::print(stderr, "warning: {}\n", w);
    for (const std::string& w : compiled.warnings) fmt::print(stderr, "warning: {}: {}\n", shownFile, w);
    if (unstable) fmt::print(stderr, "warning: {}: {}\n", shownFile, *unstable);
    // The seed ran until -stopRecordingAt; here the scene's Frames ends the run first
    // (a seed scene has none: 120 by default), which a review found stopping at 120 of 300.
    if (o.stopRecordingAt > loaded.desc.simulation.frames)
      fmt::print(
          stderr,
          "warning: {}: --stop-recording-at {} is past the run's last frame {} ({}): the run ends at frame "
          "{}; give --frames {} to simulate up to it\n",
          shownFile, o.stopRecordingAt, loaded.desc.simulation.frames,
          o.frames ? std::string("--frames")
                   : fmt::format("<Simulation><Frames>, {} when left out", scene::SimulationDesc{}.frames),
          loaded.desc.simulation.frames, o.stopRecordingAt);
    // Maya finds a PDC cache by its particle shape's name, and its node names hold no
    // '-' and do not start with a digit: no shape can take such a fluid's files.
    if (formats.pdc)
      for (const scene::FluidDesc& f : loaded.desc.fluids)
        if (f.name.find('-') != std::string::npos || (f.name[0] >= '0' && f.name[0] <= '9'))
          fmt::print(
              stderr,
              "warning: {}: fluid '{}': Maya node names cannot hold '-' or start with a digit, so no "
              "Maya particle shape can be named '{}Shape' to read pdc/{}Shape.*.pdc; for Maya, name the "
              "fluid with letters, digits and '_', starting with a letter or '_'\n",
              shownFile, f.name, f.name, f.name);
  }
  if (!o.drawPerFrame.empty() && chatty)
    fmt::print(stderr, "note: -drawPerFrame applies to the viewer; run ignores it\n");
  // Stopped while the scene was read and prepared: nothing on disk has changed yet.
  if (stop.load()) {
    fmt::print(stderr, "interrupted by {} before the first frame was complete (nothing written)\n",
               stopSignalName());
    return static_cast<int>(ExitCode::Interrupted);
  }

  // Resuming, the run in the folder is checked (a run with other settings is refused
  // before anything on disk changes) and restored; then a killed run's temporary files
  // go; starting afresh, the folder's manifests, checkpoints and frames of this scene's
  // earlier run go too.
  ResumePoint resumed;
  // One run at a time in a folder: a second one's fresh start would delete this one's
  // files under it (a review: the first run then failed as if the disk had, or ended
  // with success over files that were no longer its own).
  const auto lockOut = [&](std::optional<cache::FolderLock>& into) {
    into.emplace(outDir, "run", InputLocation{"command line", 0, "--out"},
                 "wait for it to end, or write into another folder (--out)");
  };
  std::optional<cache::FolderLock> lock;
  if (anyFormat(formats)) {
    lockOut(lock);
    // Checked again now that no other writer can change the folder (a run of another
    // scene may have written it since the checks before the scene was compiled).
    checkFolder();
  }
  if (anyFormat(formats)) {
    if (o.resume) {
      resumed = resumeFrom(outDir, loaded.name, fingerprint, sim);
      if (resumed.frame < 0 && chatty)
        fmt::print(stderr, "note: nothing to resume ({}): starting at frame 0\n", resumed.note);
    }
    const std::size_t stale = cache::removeStaleTemporaries(outDir);
    if (stale > 0 && chatty) fmt::print(stderr, "note: removed {} unfinished temporary file(s) of a stopped run\n", stale);
    if (o.resume && resumed.completeUpTo >= lastFrame) {
      pruneCheckpoints(outDir, loaded.name);
      if (chatty) fmt::print(stderr, "done: frames 0..{} were already complete\n", resumed.completeUpTo);
      return static_cast<int>(ExitCode::Ok);
    }
    if (resumed.frame >= 0 && chatty)
      fmt::print(stderr, "resuming in {} after frame {}\n", folderText(outDir), resumed.frame);
    // A resumed run ends at a later frame than the one the folder's preview shows: it goes,
    // unless --preview draws this run's over it (a review).
    if (resumed.frame >= 0 && !o.preview) {
      std::error_code ignored;
      std::filesystem::remove(outDir / (loaded.name + ".preview.png"), ignored);
    }
    if (resumed.frame < 0)
      if (const std::size_t gone = forgetEarlierRun(outDir, loaded.name, inputFiles(loaded));
          gone > 0 && chatty)
        fmt::print(stderr, "note: removed {} frame file(s) of the earlier run of '{}' in {}\n", gone,
                   loaded.name, folderText(outDir));
  }

  // Only a run that writes cache files has a writer: its name rule is for them.
  std::optional<cache::FrameWriter> writer;
  if (formats.sim || formats.pdc || formats.ply) {
    writer.emplace(outDir, loaded.name, formats);
    if (resumed.frame < 0) writer->setObjectMeshes(std::move(meshes));  // frame 0 wrote them
  }
  // The surfaces after the cache files: a frame's mesh/ and vdb/ files come after its .sim.
  surface::SurfaceWriter surfaces(outDir, formats.mesh, formats.vdb, o.surface);
  LastFrame done;
  done.last = resumed.frame;
  std::vector<FrameObserver*> observers;
  std::vector<WrittenFiles> written;
  if (writer) {
    observers.push_back(&*writer);
    written.emplace_back([&writer] { return writer->lastWritten(); });
  }
  if (formats.mesh || formats.vdb) {
    observers.push_back(&surfaces);
    written.emplace_back([&surfaces] { return surfaces.lastWritten(); });
  }
  // The manifest after every file of the frame: it marks the frame complete.
  std::optional<RunJournal> journal;
  if (anyFormat(formats))
    observers.push_back(&journal.emplace(outDir, loaded.name, fingerprint, o.checkpointEvery, sim,
                                         std::move(written)));
  observers.push_back(&done);
  std::optional<StatsObserver> stats;
  if (o.stats) observers.push_back(&stats.emplace(sim));

  // --stats lines on a terminal's stdout would land inside the progress line: one or
  // the other there.
  ProgressLine progress(chatty && !(o.stats && ::isatty(::fileno(stdout)) == 1), lastFrame, particles);
  solver::FrameLoopHooks hooks;
  hooks.stop = &stop;
  hooks.recordUpTo = o.stopRecordingAt;
  hooks.emitInitial = resumed.frame < 0;
  int fewestSubsteps = std::numeric_limits<int>::max(), mostSubsteps = 0;
  // Once a run: an object moving more than its particles' diameter in a substep can pass
  // into or through a part of another object one particle thick (contacts see overlaps,
  // not paths), and nothing else would say so.
  bool warnedFast = o.quiet;
  constexpr int kMost = solver::kMaxStableSubsteps;  // the most substeps a frame may take
  const auto warnIfFast = [&](std::int64_t frame) {
    // --adaptive chooses each frame's substeps from the speeds (a quarter of the contact
    // reach a substep): only its ceiling leaves an object this fast.
    if (warnedFast || (o.adaptive && sim.substeps() < o.maxSubsteps)) return;
    const std::optional<solver::Simulation::BodyTravel> fast = sim.fastestBody();
    if (!fast || !(fast->travel > 2 * fast->particleRadius)) return;
    warnedFast = true;
    const double needed = std::ceil(sim.substeps() * fast->travel / (2 * fast->particleRadius));
    progress.end();
    fmt::print(
        stderr,
        "warning: {}: object '{}' moves up to {:.3g} units a substep at frame {}, more than its particles' "
        "diameter {:g}: it can pass into or through thin parts of other objects; {}\n",
        shownFile, compiled.model.bodies.bodies[fast->body].name, fast->travel, frame,
        2 * fast->particleRadius,
        o.adaptive && o.maxSubsteps < kMost ? fmt::format("raise --max-substeps (now {})", o.maxSubsteps)
        : !o.adaptive && needed <= kMost ? fmt::format("raise Substeps to {:.0f} or use --adaptive", needed)
                                         : std::string("no substep count up to 10,000 a frame keeps it "
                                                       "within its particles' diameter: slow it down or "
                                                       "give it larger particles (ParticleSize)"));
  };
  warnIfFast(std::max<std::int64_t>(resumed.frame, 0));
  // Once a run: --adaptive held back by its ceiling leaves particles moving further a
  // substep than it allows, which it would otherwise prevent (and the stability warning
  // is not given under --adaptive).
  bool warnedCapped = o.quiet;
  const auto warnIfCapped = [&](std::int64_t frame) {
    const double needed = sim.cappedSubsteps();
    if (warnedCapped || needed <= 0) return;
    warnedCapped = true;
    progress.end();
    fmt::print(
        stderr,
        "warning: {}: frame {} needed {:.0f} substeps for --adaptive's limits, and --max-substeps held it "
        "to {}: particles may move further a substep than is stable, be flung about and gain energy; {}\n",
        shownFile, frame, needed, sim.substeps(),
        o.maxSubsteps < kMost && needed <= kMost
            ? fmt::format("raise --max-substeps to {:.0f}", needed)
            : std::string("no count up to 10,000 a frame suffices: soften the forces (MaximumForce, "
                          "Viscosity) or slow the motion"));
  };
  hooks.onProgress = [&](const solver::FrameProgress& p) {
    progress.update(p);
    if (p.initial) return;  // frame 0: written, no substep taken
    fewestSubsteps = std::min(fewestSubsteps, sim.substeps());
    mostSubsteps = std::max(mostSubsteps, sim.substeps());
    warnIfFast(p.frame);
    warnIfCapped(p.frame);
  };

  const std::string where = anyFormat(formats) ? folderText(outDir) : std::string("nothing written");
  bool complete = false;
  const auto start = std::chrono::steady_clock::now();
  progress.begin(sim.state().frame, hooks.emitInitial ? "writing frame 0" : "simulating");
  try {
    complete = solver::runFrames(sim, lastFrame, observers, hooks);
  } catch (const BlowUpError& e) {
    progress.end();
    throw BlowUpError(done.last < 0 ? std::string(e.what())
                                    : fmt::format("{} (frames 0..{} are complete: {})", e.what(),
                                                  done.last, where));
  }
  progress.end();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!complete) {
    const char* signal = stopSignalName();
    if (done.last < 0)
      fmt::print(stderr, "interrupted by {} before the first frame was complete ({})\n", signal, where);
    else
      fmt::print(stderr, "interrupted by {}: frame {} is the last complete frame ({})\n", signal, done.last,
                 where);
    return static_cast<int>(ExitCode::Interrupted);
  }
  std::string previewNote;
  if (view) {
    // The caches are complete whatever happens here: a system that cannot draw gets a
    // warning, not a failed run. The warning is printed even when quiet: the picture was
    // asked for, and a successful run that silently lacks it would mislead.
    const std::filesystem::path picture = outDir / (loaded.name + ".preview.png");
    try {
      // The folder once the picture can be drawn: with --formats none it holds nothing
      // else, and a system that cannot draw leaves no empty folder.
      PictureMaker maker(*view, kPreviewWidth, kPreviewHeight);
      // With --formats none this run holds no lock yet: not into a folder another one writes.
      std::optional<cache::FolderLock> previewLock;
      if (!lock) lockOut(previewLock);
      cache::ensureDirectory(outDir);
      maker.write(picture, sim.snapshot(), cameraOf(loaded.desc.camera));
      previewNote = ", preview: " + picture.string();
    } catch (const InputError& e) {  // the folder is being written by another process
      fmt::print(stderr, "warning: no preview picture: {}\n", e.what());
    } catch (const IoError& e) {
      fmt::print(stderr, "warning: no preview picture: {}\n", e.what());
      // One an earlier run (or this one, before a resume) drew would pass for this run's.
      std::error_code ignored;
      std::filesystem::remove(picture, ignored);
    }
  }
  if (chatty && o.adaptive && mostSubsteps > 0)
    fmt::print(stderr, "adaptive substeps: {}..{} per frame\n", fewestSubsteps, mostSubsteps);
  if (chatty) {
    // The total over the frames simulated, frame 0's writing included; none: no rate.
    const std::int64_t frames = progress.framesDone();
    fmt::print(stderr, "done: {}, {}, {:.2f} s{}, output: {}{}\n",
               countOf(static_cast<std::uint64_t>(frames), "frame"), countOf(particles, "particle"), seconds,
               frames > 0 ? fmt::format(" ({:.1f} ms/frame)", seconds / static_cast<double>(frames) * 1e3)
                          : std::string(),
               where, previewNote);
  }
  return static_cast<int>(ExitCode::Ok);
}

}  // namespace softsub::app
