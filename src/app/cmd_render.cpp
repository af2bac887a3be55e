#include "cmd_render.h"
#include "number_checks.h"

#include <optional>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <charconv>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "cache/atomic_file.h"
#include "cache/naming.h"
#include "core/error.h"
#include "progress.h"
#include "render_playback.h"
#include "scene/compile.h"
#include "scene_source.h"
#include "scene_view.h"
#include "surface_options.h"
#include "solver/frame_loop.h"
#include "stop_signal.h"
#include "text_format.h"

extern char** environ;

namespace softsub::app {

namespace {

std::optional<std::int64_t> parseFrameNumber(std::string_view s) {
  std::int64_t v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || v < 0) return std::nullopt;
  return v;
}

constexpr int kMaxSide = 16384;

/// Renders each frame it is given inside the range into `<out>/<scene>.NNNN.png`.
class PictureObserver : public FrameObserver {
 public:
  PictureObserver(PictureMaker& maker, render::Camera camera, std::filesystem::path out, std::string scene,
                  FrameRange range, std::optional<surface::SurfaceSettings> surfaces)
      : maker_(maker),
        camera_(std::move(camera)),
        out_(std::move(out)),
        scene_(std::move(scene)),
        range_(range),
        surfaces_(std::move(surfaces)) {}
  void onFrame(const FrameSnapshot& frame) override {
    if (!range_.contains(frame.frame)) return;
    const auto surfaces = surfaces_ ? surfacesOf(frame, *surfaces_) : std::vector<render::RenderSurface>{};
    std::filesystem::path path = picturePath(out_, scene_, frame.frame);
    maker_.write(path, frame, camera_, surfaces);
    pictures.push_back(std::move(path));
    ++written;
  }
  std::int64_t written = 0;
  std::vector<std::filesystem::path> pictures;  // written by this render, in frame order

 private:
  PictureMaker& maker_;
  render::Camera camera_;
  std::filesystem::path out_;
  std::string scene_;
  FrameRange range_;
  std::optional<surface::SurfaceSettings> surfaces_;  // set: draw surfaces with these settings
};

void checkSize(const RenderOptions& o) {
  for (const auto& [option, v] : {std::pair{"--width", o.width}, std::pair{"--height", o.height}})
    if (v < 16 || v > kMaxSide)
      throw InputError({"command line", 0, option}, fmt::format("{} pixels is out of range", v),
                       fmt::format("an integer in [16, {}]", kMaxSide));
  if (!o.movie.empty() && (o.width % 2 != 0 || o.height % 2 != 0))
    throw InputError({"command line", 0, "--movie"},
                     fmt::format("{}x{} cannot be encoded as H.264 4:2:0", o.width, o.height),
                     "an even --width and --height");
}

}  // namespace

std::filesystem::path picturePath(const std::filesystem::path& dir, std::string_view scene, std::int64_t frame) {
  return dir / fmt::format("{}.{}.png", scene, cache::frameTag(frame));
}

FrameRange parseFrameRange(const std::string& text, const std::string& option) {
  FrameRange r;
  if (text.empty()) return r;
  auto refuse = [&](std::string_view problem) -> InputError {
    return InputError({"command line", 0, option}, fmt::format("'{}' {}", text, problem),
                      "a:b (first and last frame, inclusive), a: (from a), :b (up to b) or a (one frame), "
                      "frame numbers >= 0");
  };
  const auto colon = text.find(':');
  const std::string_view a = std::string_view(text).substr(0, colon);
  const std::string_view b = colon == std::string::npos ? a : std::string_view(text).substr(colon + 1);
  if (a.empty() && b.empty()) throw refuse("is not a frame range");
  if (!a.empty()) {
    const auto v = parseFrameNumber(a);
    if (!v) throw refuse("is not a frame range");
    r.first = *v;
  }
  if (!b.empty()) {
    const auto v = parseFrameNumber(b);
    if (!v) throw refuse("is not a frame range");
    r.last = *v;
  }
  if (r.last && *r.last < r.first) throw refuse("ends before it starts");
  return r;
}

std::string findOnPath(const std::string& name) {
  if (name.find('/') != std::string::npos) return ::access(name.c_str(), X_OK) == 0 ? name : std::string();
  const char* path = std::getenv("PATH");
  std::string_view rest = path ? path : "/usr/bin:/bin";
  while (true) {
    const auto colon = rest.find(':');
    const std::filesystem::path dir(std::string(rest.substr(0, colon)));
    const std::filesystem::path candidate = (dir.empty() ? std::filesystem::path(".") : dir) / name;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate.string();
    if (colon == std::string_view::npos) return {};
    rest.remove_prefix(colon + 1);
  }
}

std::string findFfmpeg() { return findOnPath("ffmpeg"); }

void encodeMovie(const std::vector<std::filesystem::path>& pictures, double fps, const std::string& movie) {
  const std::string ffmpeg = findFfmpeg();
  if (ffmpeg.empty()) throw IoError("cannot write " + movie + ": ffmpeg is not installed (Debian: apt-get install ffmpeg)");
  if (pictures.empty()) throw IoError("cannot write " + movie + ": no picture to encode");
  // Encoded next to the target, then renamed: a movie is complete or absent.
  const std::filesystem::path target(movie);
  const std::filesystem::path parent =
      target.parent_path().empty() ? std::filesystem::path(".") : target.parent_path();
  const std::filesystem::path partial = parent / ("." + target.filename().string() + ".part.mp4");
  // ffmpeg reads a numbered sequence: the pictures of this render only, numbered from 0
  // as links in a folder of their own. Reading the output folder's <scene>.%04d.png
  // from the first frame on took every later picture there too, an earlier render's
  // (another take, another size) included, and stopped at a gap in the numbers.
  const std::filesystem::path links =
      parent / fmt::format(".{}.frames.{}", target.filename().string(), ::getpid());
  struct RemoveLinks {
    std::filesystem::path dir;
    ~RemoveLinks() {
      std::error_code ignored;
      std::filesystem::remove_all(dir, ignored);
    }
  } removeLinks{links};
  std::error_code ec;
  std::filesystem::remove_all(links, ec);
  std::filesystem::create_directory(links, ec);
  if (ec)
    throw IoError(fmt::format("cannot write {}: cannot make {}: {}", movie, links.string(), ec.message()));
  // A symbolic link, else (a file system without them) a hard link, else a copy.
  for (std::size_t k = 0; k < pictures.size(); ++k) {
    const std::filesystem::path to = links / fmt::format("{:08}.png", k);
    std::filesystem::create_symlink(std::filesystem::absolute(pictures[k]), to, ec);
    if (ec) std::filesystem::create_hard_link(pictures[k], to, ec);
    if (ec) std::filesystem::copy_file(pictures[k], to, ec);
    if (ec)
      throw IoError(
          fmt::format("cannot write {}: cannot link {}: {}", movie, pictures[k].string(), ec.message()));
  }
  const std::vector<std::string> args = {ffmpeg,
                                         "-nostdin",
                                         "-y",
                                         "-loglevel",
                                         "error",
                                         "-framerate",
                                         fmt::format("{:g}", fps),
                                         "-start_number",
                                         "0",
                                         "-i",
                                         (links / "%08d.png").string(),
                                         "-frames:v",
                                         std::to_string(pictures.size()),
                                         "-c:v",
                                         "libx264",
                                         "-pix_fmt",
                                         "yuv420p",
                                         "-movflags",
                                         "+faststart",
                                         partial.string()};
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawn(&pid, ffmpeg.c_str(), nullptr, nullptr, argv.data(), environ) != 0)
    throw IoError("cannot write " + movie + ": cannot start " + ffmpeg);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::error_code ignored;
    std::filesystem::remove(partial, ignored);
    throw IoError(fmt::format("cannot write {}: ffmpeg failed (exit status {})", movie,
                              WIFEXITED(status) ? WEXITSTATUS(status) : -1));
  }
  std::filesystem::rename(partial, target, ec);
  if (ec) throw IoError(fmt::format("cannot write {}: {}", movie, ec.message()));
}

CLI::App* addRenderCommand(CLI::App& root, RenderOptions& o) {
  CLI::App* cmd = root.add_subcommand(
      "render", "Draw a scene's frames (simulated on the way) or a recorded folder's frames into PNG pictures, "
                "off-screen (no display or GPU needed)");
  cmd->add_option("INPUT", o.input, ".scene file or recorded <scene>Sim folder (default: the embedded default scene)")
      ->check(nonEmptyPath());
  cmd->add_option("--out", o.out, "Folder for the pictures <scene>.NNNN.png")->required()->check(nonEmptyPath(false));
  cmd->add_option("--scene", o.scene,
                  "With a recorded folder: the scene file it was made with, for colours, particle sizes, the "
                  "container and the camera (default: <scene>.scene beside the folder)")
      ->check(nonEmptyPath());
  cmd->add_option("--width", o.width, "Picture width in pixels, 16 to 16384")
      ->transform(wholeNumberIn(16, 16384))
      ->capture_default_str();
  cmd->add_option("--height", o.height, "Picture height in pixels, 16 to 16384")
      ->transform(wholeNumberIn(16, 16384))
      ->capture_default_str();
  cmd->add_option("--frames", o.frames, "Frames to draw: a:b (inclusive), a:, :b or a (default: all)");
  cmd->add_option("--movie", o.movie,
                  "Also encode this render's pictures (the frames drawn, nothing else) into this .mp4 file "
                  "(needs ffmpeg)")
      ->check(nonEmptyPath())
      ->check(outputFileWithExtension(".mp4", "an MP4 movie"));
  cmd->add_option("--substeps", o.substeps, "Overrides the scene's <Simulation><Substeps> (1 to 10000, as in a scene)")
      ->transform(wholeNumberIn(1, 10000));
  cmd->add_option("--max-particles", o.maxParticles, "Refuse scenes with more particles than this")
      ->transform(particleCap());
  cmd->add_flag("--surface", o.surface,
                "Draw each fluid's surface (as softsub mesh makes it) instead of its particles");
  addSurfaceOptions(cmd, o.surfaceSettings, "; with --surface");
  cmd->add_flag("-q,--quiet", o.quiet, "Print nothing but errors");
  return cmd;
}

int renderCommand(const RenderOptions& o) {
  // From the start, as run's: a stop while the scene loads ends with exit code 130.
  const std::atomic<bool>& stop = installStopHandlers();
  checkSize(o);
  const FrameRange range = parseFrameRange(o.frames, "--frames");
  if (surfaceOptionsGiven(o.surfaceSettings) && !o.surface)
    throw InputError({"command line", 0, "--voxel-size/--blob-radius"}, "are for surfaces",
                     "add --surface, or leave them out");
  const std::optional<surface::SurfaceSettings> surfaceSettings =
      o.surface ? std::optional<surface::SurfaceSettings>(o.surfaceSettings) : std::nullopt;
  if (!o.movie.empty() && findFfmpeg().empty())
    throw InputError({"command line", 0, "--movie"}, "ffmpeg is not installed", "install ffmpeg, or leave out --movie");
  const bool chatty = stderrIsTerminal() && !o.quiet;
  const std::filesystem::path out(o.out);
  // Both output folders are made once every option has been checked (the movie's too,
  // so a missing folder does not fail it after every picture is drawn).
  auto prepareOutputs = [&] {
    cache::ensureDirectory(out);
    if (!o.movie.empty()) {
      const std::filesystem::path parent = std::filesystem::path(o.movie).parent_path();
      if (!parent.empty()) cache::ensureDirectory(parent);
    }
  };

  std::string sceneName;
  double fps = 24;
  std::unique_ptr<PictureMaker> maker;  // outlives the observer that draws with it
  std::optional<PictureObserver> observer;
  PictureObserver* pictures = nullptr;
  const bool recorded = isRecording(o.input);
  const auto start = std::chrono::steady_clock::now();
  if (recorded) {
    refuseSimulationOptions(o.input, o.substeps.has_value(), o.maxParticles != 0);
    RecordedFrames rec = openRecorded(o.input, o.scene);
    sceneName = rec.sceneName;
    checkOutputName(sceneName, "scene name", o.input);  // it names the pictures
    fps = rec.framesPerSecond;
    bool any = false;
    for (std::size_t i = 0; i < rec.frameCount() && !any; ++i) any = range.contains(rec.frameNumber(i));
    if (!any)
      throw InputError({"command line", 0, "--frames"},
                       fmt::format("no frame of {} is in '{}'", o.input, o.frames),
                       fmt::format("frames {} to {}, the recorded ones", rec.frameNumber(0),
                                   rec.frameNumber(rec.frameCount() - 1)));
    if (o.surface) checkSurfaceOptions(o.surfaceSettings, rec.load(0), o.input, o.quiet);
    // What changes the pictures (no scene: grey particles of size 1, no container, a
    // camera of our choosing; frames or scenes left out), terminal or not.
    if (!o.quiet)
      for (const std::string& w :
           playbackWarnings(rec.playback(),
                            "every fluid is drawn grey at ParticleSize 1, with no container, from a camera "
                            "that frames the first frame",
                            "--scene"))
        fmt::print(stderr, "warning: {}\n", w);
    const std::int64_t lastRecorded = rec.frameNumber(rec.frameCount() - 1);
    if (range.last && *range.last > lastRecorded && chatty)
      fmt::print(stderr, "note: --frames reaches frame {}; the recording ends at frame {}, the last drawn\n",
                 *range.last, lastRecorded);
    // The drawing context first: without one (no EGL) nothing is made, no empty folder.
    maker = std::make_unique<PictureMaker>(rec.scene, o.width, o.height);
    prepareOutputs();
    observer.emplace(*maker, rec.camera, out, sceneName, range, surfaceSettings);
    pictures = &*observer;
    // The progress runs to the last recorded frame in the range, with the particles of
    // the first one drawn (it counted every recorded frame and showed 0 particles).
    std::int64_t lastDrawn = 0;
    std::optional<std::size_t> firstDrawn;
    for (std::size_t i = 0; i < rec.frameCount(); ++i)
      if (range.contains(rec.frameNumber(i))) {
        lastDrawn = rec.frameNumber(i);
        if (!firstDrawn) firstDrawn = i;
      }
    std::size_t particles = 0, drawn = 0;
    if (firstDrawn)
      for (const FluidSnapshot& f : rec.load(*firstDrawn).fluids) particles += f.ids.size();
    for (std::size_t i = 0; i < rec.frameCount(); ++i) drawn += range.contains(rec.frameNumber(i)) ? 1 : 0;
    ProgressLine progress(chatty, lastDrawn, particles, drawn);
    for (std::size_t i = 0; i < rec.frameCount(); ++i) {
      if (!range.contains(rec.frameNumber(i))) continue;
      if (stop.load()) break;
      const auto t0 = std::chrono::steady_clock::now();
      pictures->onFrame(rec.load(i));
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      progress.update({rec.frameNumber(i), lastDrawn, 0, seconds});
    }
    progress.end();
    if (stop.load()) {
      fmt::print(stderr, "interrupted: {} pictures written to {}\n", pictures->written, out.string());
      return static_cast<int>(ExitCode::Interrupted);
    }
  } else {
    if (!o.scene.empty())
      throw InputError({"command line", 0, "--scene"},
                       fmt::format("is for a recorded folder: {} is a scene",
                                   o.input.empty() ? "the default scene" : o.input),
                       "give the scene as INPUT, or leave --scene out");
    TerminalNote reading(chatty,
                         fmt::format("reading {} ...", o.input.empty() ? "the default scene" : o.input));
    LoadedScene loaded = loadScene(o.input, o.maxParticles);
    if (o.substeps) loaded.desc.simulation.substeps = static_cast<int>(*o.substeps);
    sceneName = loaded.name;
    checkOutputName(sceneName, "scene name", loaded.file);  // it names the pictures
    fps = loaded.desc.simulation.framesPerSecond;
    std::int64_t lastFrame = loaded.desc.simulation.frames;
    if (range.last) lastFrame = std::min(lastFrame, *range.last);
    if (range.first > loaded.desc.simulation.frames)
      throw InputError({"command line", 0, "--frames"},
                       fmt::format("frame {} is past the scene's last frame {}", range.first,
                                   loaded.desc.simulation.frames),
                       fmt::format("frames in [0, {}]", loaded.desc.simulation.frames));
    scene::Compiled compiled = scene::compile(loaded.desc);
    reading.clear();  // before anything is printed
    if (range.last && *range.last > loaded.desc.simulation.frames && chatty)
      fmt::print(stderr, "note: --frames reaches frame {}; the scene ends at frame {}, the last drawn\n",
                 *range.last, loaded.desc.simulation.frames);
    if (!o.quiet)  // warnings, unlike notes, also for a pipe or a log (as run's)
      for (const std::string& w : compiled.warnings)
        fmt::print(stderr, "warning: {}: {}\n", displayFile(loaded.file), w);
    const render::RenderScene view = renderSceneOf(loaded.desc, compiled.objectMeshes);
    const std::size_t particles = compiled.model.particleCount();
    solver::Simulation sim(compiled.model, std::move(compiled.state));
    if (o.surface) checkSurfaceOptions(o.surfaceSettings, sim.snapshot(), loaded.file, o.quiet);
    if (stop.load()) {  // stopped while the scene was read: nothing made yet, as run
      fmt::print(stderr, "interrupted before the first picture (nothing written)\n");
      return static_cast<int>(ExitCode::Interrupted);
    }
    maker = std::make_unique<PictureMaker>(view, o.width, o.height);
    prepareOutputs();
    observer.emplace(*maker, cameraOf(loaded.desc.camera), out, sceneName, range, surfaceSettings);
    pictures = &*observer;
    FrameObserver* observers[] = {pictures};
    // The frames drawn are the items (frame 0 among them when in range): the rate and
    // the ETA are theirs, simulation and drawing; the frames simulated on the way to
    // the range say so (a review: their fast frames made the ETA a fraction of the time
    // the pictures still took).
    const auto drawn = static_cast<std::size_t>(lastFrame - range.first + 1);
    ProgressLine progress(chatty, lastFrame, particles, drawn);
    solver::FrameLoopHooks hooks;
    hooks.stop = &stop;
    hooks.onProgress = [&](const solver::FrameProgress& p) {
      if (p.frame < range.first)
        return progress.note(p.frame, fmt::format("simulating to frame {}", range.first));
      solver::FrameProgress item = p;
      item.initial = false;  // frame 0 in range is a picture like any other
      progress.update(item);
    };
    const bool complete = solver::runFrames(sim, lastFrame, observers, hooks);
    progress.end();
    if (!complete) {
      fmt::print(stderr, "interrupted: {} pictures written to {}\n", pictures->written, out.string());
      return static_cast<int>(ExitCode::Interrupted);
    }
  }
  if (pictures->written == 0)
    throw InputError({"command line", 0, "--frames"}, fmt::format("no frame of {} is in '{}'", o.input, o.frames),
                     "a range that holds at least one frame");
  if (!o.movie.empty()) {
    if (chatty) fmt::print(stderr, "encoding {} ...\n", o.movie);
    encodeMovie(pictures->pictures, fps, o.movie);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (chatty)
    fmt::print(stderr, "done: {} written to {} ({}x{}), {:.2f} s{}\n", countOf(static_cast<std::uint64_t>(pictures->written), "picture"),
               out.string(), o.width, o.height, seconds, o.movie.empty() ? "" : ", movie: " + o.movie);
  return static_cast<int>(ExitCode::Ok);
}

}  // namespace softsub::app
