#include "viewer.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

// OpenGL's prototypes first; GLFW must not pull in its own gl.h.
#include "render/gl.h"
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <fmt/format.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include "cache/atomic_file.h"
#include "cache/folder_lock.h"
#include "core/error.h"
#include "render/offscreen.h"
#include "render/renderer.h"
#include "render_playback.h"
#include "run_journal.h"
#include "scene_source.h"
#include "scene_view.h"
#include "session/live_session.h"

namespace softsub::app {

namespace {

std::string glfwFailure;  // the last GLFW error, for the message when a window fails

void onGlfwError(int code, const char* text) { glfwFailure = fmt::format("{} (GLFW error 0x{:x})", text, code); }

Viewer* viewerOf(GLFWwindow* w) { return static_cast<Viewer*>(glfwGetWindowUserPointer(w)); }

/// The scale of the scene: how far one arrow-key press moves the camera.
double stepLength(const Aabb& box) {
  if (box.empty()) return 0.5;
  const double d = std::hypot(box.hi[0] - box.lo[0], box.hi[1] - box.lo[1], box.hi[2] - box.lo[2]);
  return std::max(0.02 * d, 1e-3);
}

Vec3 pivotOf(const Aabb& box, const render::Camera& camera) {
  if (box.empty()) return camera.eye + camera.forward() * 10.0;
  return {0.5 * (box.lo[0] + box.hi[0]), 0.5 * (box.lo[1] + box.hi[1]), 0.5 * (box.lo[2] + box.hi[2])};
}

int keyOf(const std::string& name) {
  static const std::pair<const char*, int> keys[] = {
      {"R", GLFW_KEY_R},       {"S", GLFW_KEY_S},         {"N", GLFW_KEY_N},       {"M", GLFW_KEY_M},  {"SPACE", GLFW_KEY_SPACE},
      {"UP", GLFW_KEY_UP},     {"DOWN", GLFW_KEY_DOWN},   {"LEFT", GLFW_KEY_LEFT}, {"RIGHT", GLFW_KEY_RIGHT},
      {"H", GLFW_KEY_H},       {"P", GLFW_KEY_P},         {"C", GLFW_KEY_C},       {"ESCAPE", GLFW_KEY_ESCAPE}};
  for (const auto& [n, k] : keys)
    if (name == n) return k;
  return GLFW_KEY_UNKNOWN;
}

}  // namespace

Viewer::Viewer(const ViewOptions& options) : options_(options) {
  paused_ = options.paused;
  if (!options.script.empty()) {
    const std::vector<session::ScriptCommand> commands = session::readScriptFile(options.script);
    script_.assign(commands.begin(), commands.end());
  }
  if (isRecording(options.input)) {
    refuseSimulationOptions(options.input, options.substeps.has_value(), options.maxParticles != 0);
    recorded_ = std::make_unique<RecordedFrames>(options.input);
    sceneName_ = recorded_->sceneName;
    checkOutputName(sceneName_, "scene name", options.input);  // P's screenshots are named after it
    // As render and mesh say them (defaults drawn, frames left out), and in the panel.
    playbackWarnings_ = playbackWarnings(
        recorded_->playback(), "every fluid is drawn grey at ParticleSize 1, with no container",
        fmt::format("a copy of it beside the folder named {}.scene", sceneName_));
    for (const std::string& w : playbackWarnings_) fmt::print(stderr, "warning: {}\n", w);
    renderScene_ = recorded_->scene;
    startCamera_ = recorded_->camera;
    playFrame_ = recorded_->load(0);
  } else {
    LoadedScene loaded = loadScene(options.input, options.maxParticles);
    if (options.substeps) loaded.desc.simulation.substeps = static_cast<int>(*options.substeps);
    sceneName_ = loaded.name;
    const std::filesystem::path outDir = options.out.empty() ? loaded.defaultOutDir : std::filesystem::path(options.out);
    // The seed's -record 0 keeps no frame, frame 0 included: S then has nothing to write.
    cache::Formats formats;
    if (options.record == 0) formats.sim = formats.pdc = formats.ply = false;
    // Checked as run checks them, before the window opens: S writes files named after the
    // scene, fluids and objects, P screenshots named after the scene.
    checkOutputNames(loaded, formats, true);
    checkInputsKept(loaded, formats, outDir);
    inputFiles_ = inputFiles(loaded);
    session_ = std::make_unique<session::LiveSession>(loaded.desc, loaded.name, outDir, formats);
    if (options.stopRecordingAt >= 0) session_->setStopRecordingAt(options.stopRecordingAt);
    renderScene_ = renderSceneOf(session_->desc(), session_->objectMeshes());
    startCamera_ = cameraOf(session_->desc().camera);
    const std::string save = (std::filesystem::path(loaded.defaultOutDir).parent_path() / (loaded.name + "-tweaked.scene")).string();
    std::snprintf(savePath_, sizeof savePath_, "%s", save.c_str());
    refreshStability();
  }
  camera_ = startCamera_;
}

Viewer::~Viewer() {
  if (imguiReady_) {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
  renderer_.reset();  // its GL objects go with the context still current
  if (window_ != nullptr) glfwDestroyWindow(window_);
  glfwTerminate();
}

const FrameSnapshot& Viewer::frame() const { return live() ? session_->snapshot() : playFrame_; }

void Viewer::openWindow() {
  glfwSetErrorCallback(onGlfwError);
  if (glfwInit() == GLFW_FALSE)
    throw IoError(fmt::format("cannot open a window: {}; without a display use 'softsub render' (off-screen), "
                              "or run the viewer under xvfb-run",
                              glfwFailure.empty() ? "no display" : glfwFailure));
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_SAMPLES, 4);
  glfwWindowHint(GLFW_STENCIL_BITS, 8);
  glfwWindowHint(GLFW_DEPTH_BITS, 24);
  const std::string title = fmt::format("softsub view: {}", sceneName_);
  window_ = glfwCreateWindow(options_.width, options_.height, title.c_str(), nullptr, nullptr);
  if (window_ == nullptr)
    throw IoError(fmt::format("cannot open an OpenGL 3.3 window: {}", glfwFailure.empty() ? "unknown reason" : glfwFailure));
  glfwMakeContextCurrent(window_);
  render::pinGraphicsDrivers();
  glfwSwapInterval(1);
  glfwSetWindowUserPointer(window_, this);
  // Ours first: ImGui's backend chains to callbacks installed before it.
  glfwSetKeyCallback(window_, [](GLFWwindow* w, int key, int, int action, int mods) {
    if (!ImGui::GetIO().WantCaptureKeyboard) viewerOf(w)->onKey(key, action, mods);
  });
  glfwSetScrollCallback(window_, [](GLFWwindow* w, double, double dy) {
    if (!ImGui::GetIO().WantCaptureMouse) viewerOf(w)->onScroll(dy);
  });
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini dropped in the user's folder
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(window_, true);
  ImGui_ImplOpenGL3_Init("#version 330 core");
  imguiReady_ = true;
  renderer_ = std::make_unique<render::Renderer>();
  renderer_->setScene(renderScene_);
}

void Viewer::setMessage(std::string text, bool error) {
  message_ = std::move(text);
  messageIsError_ = error;
  if (error || !options_.script.empty()) fmt::print(stderr, "{}{}\n", error ? "error: " : "view: ", message_);
}

void Viewer::onKey(int key, int action, int /*mods*/) {
  if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
  const Aabb box = renderer_ ? renderer_->bounds() : Aabb{};
  switch (key) {
    case GLFW_KEY_UP: camera_.moveForward(stepLength(box)); break;
    case GLFW_KEY_DOWN: camera_.moveForward(-stepLength(box)); break;
    case GLFW_KEY_LEFT: camera_.turn(3); break;
    case GLFW_KEY_RIGHT: camera_.turn(-3); break;
    default: break;
  }
  if (action != GLFW_PRESS) return;
  switch (key) {
    case GLFW_KEY_R: restart(); break;
    case GLFW_KEY_S: writeCaches(); break;
    case GLFW_KEY_SPACE: paused_ = !paused_; break;
    case GLFW_KEY_N: stepOnce_ = true; paused_ = true; break;
    case GLFW_KEY_H:
    case GLFW_KEY_F1: showHelp_ = !showHelp_; break;
    case GLFW_KEY_C: camera_ = startCamera_; break;
    case GLFW_KEY_M: surfaces_ = !surfaces_; break;
    case GLFW_KEY_P:
      screenshot(std::filesystem::path(fmt::format("{}.screenshot.{:04d}.png", sceneName_, frame().frame)));
      break;
    case GLFW_KEY_ESCAPE:
    case GLFW_KEY_Q: quit_ = true; break;
    default: break;
  }
}

void Viewer::onScroll(double dy) {
  const Aabb box = renderer_ ? renderer_->bounds() : Aabb{};
  camera_.zoom(std::pow(0.9, dy), pivotOf(box, camera_));
}

void Viewer::handleInput() {
  const ImGuiIO& io = ImGui::GetIO();
  double x = 0, y = 0;
  glfwGetCursorPos(window_, &x, &y);
  const bool down = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
  if (down && !dragging_ && !io.WantCaptureMouse) {
    dragging_ = true;
  } else if (!down) {
    dragging_ = false;
  } else if (dragging_) {
    const Aabb box = renderer_->bounds();
    camera_.orbit(-0.3 * (x - lastX_), -0.3 * (y - lastY_), pivotOf(box, camera_));
  }
  lastX_ = x;
  lastY_ = y;
}

void Viewer::advance(bool wholeFrame) {
  if (live()) {
    try {
      if (wholeFrame) session_->advanceFrame();
      else session_->advanceSubstep();
    } catch (const BlowUpError& e) {
      paused_ = true;
      setMessage(fmt::format("{} (paused: lower the forces or raise Substeps, then press R)", e.what()), true);
      if (!options_.script.empty()) {
        exitCode_ = static_cast<int>(ExitCode::BlowUp);
        quit_ = true;
      }
    }
    return;
  }
  if (playIndex_ + 1 < recorded_->frameCount()) {
    ++playIndex_;
    playFrame_ = recorded_->load(playIndex_);
  } else {
    paused_ = true;  // the end of the recording
  }
}

void Viewer::restart() {
  if (live()) {
    session_->restart();
    setMessage(fmt::format("restarted at frame 0"));
  } else {
    playIndex_ = 0;
    playFrame_ = recorded_->load(0);
  }
}


void Viewer::writeCaches() {
  if (!live()) {
    setMessage("S writes a live simulation's frames; this is a recording already", true);
    return;
  }
  try {
    // These frames are not a `run`'s: the journal (manifests, checkpoints) and the frames
    // an earlier run of this scene left in the folder go first, as when `run` starts
    // afresh, so that `run --resume` and `info` cannot take the viewer's frames for that
    // run's, nor a package mix the two.
    // Not while a run writes the folder (cache::FolderLock, as `run` and `mesh` take it).
    std::optional<cache::FolderLock> lock;
    if (session_->recordedFrames() > 0) {
      lock.emplace(session_->outputDir(), "view", InputLocation{"viewer", 0, "S"},
                   "wait for it to end, or start the viewer with another --out");
      forgetEarlierRun(session_->outputDir(), session_->sceneName(), inputFiles_);
    }
    const auto written = session_->writeRecorded();
    if (written.frames == 0) {
      setMessage(options_.record == 0 ? "nothing written: --record 0 keeps no frames"
                                      : "nothing written: no frame is kept");
    } else {
      setMessage(fmt::format("wrote {} frames to {}", written.frames, written.folder.string()));
    }
  } catch (const IoError& e) {
    setMessage(e.what(), true);
    writeFailed_ = true;
  } catch (const InputError& e) {  // the folder is being written by a run
    setMessage(e.what(), true);
    writeFailed_ = true;
  }
}

void Viewer::saveScene(const std::filesystem::path& path) {
  if (!live()) {
    setMessage("only a live simulation has a scene to save", true);
    return;
  }
  try {
    session_->saveScene(path);
    setMessage(fmt::format("saved {}", path.string()));
  } catch (const IoError& e) {
    setMessage(e.what(), true);
    writeFailed_ = true;
  }
}

void Viewer::screenshot(const std::filesystem::path& path) {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  try {
    cache::writeFileAtomic(path, render::encodePng(render::readPixels(w, h)));
    setMessage(fmt::format("screenshot {}", path.string()));
  } catch (const IoError& e) {
    setMessage(e.what(), true);
    writeFailed_ = true;
  }
}

void Viewer::runScript() {
  if (waitDraws_ > 0) {
    --waitDraws_;
    return;
  }
  if (waitFrames_ > 0) {
    --waitFrames_;
    advance(true);
    return;
  }
  while (!script_.empty() && !quit_) {
    const session::ScriptCommand c = script_.front();
    script_.pop_front();
    try {
      switch (c.kind) {
        case session::ScriptCommandKind::SetFluid:
        case session::ScriptCommandKind::SetSimulation:
          if (!live())
            throw InputError({options_.script, c.line, "set"}, "a recording has no parameters to set",
                             "set commands with a .scene input");
          session::applySetCommand(c, session_->editableDesc(), options_.script);
          // An edit the scene's rules refuse (MinimumForce above MaximumForce) is this
          // line's error: said with the script's file and line (a review).
          if (std::optional<InputError> refused; applyEdits(&refused), refused)
            throw InputError(
                {options_.script, c.line, "set"},
                fmt::format("the edit is refused: {}: {}", refused->where().element, refused->problem()),
                refused->allowed());
          break;
        case session::ScriptCommandKind::Key: {
          const int key = keyOf(c.args.at(0));
          onKey(key, GLFW_PRESS, 0);
          if (key == GLFW_KEY_N) {  // a step key takes effect in the loop: let it happen
            return;
          }
          break;
        }
        case session::ScriptCommandKind::Frames:
          waitFrames_ = session::scriptCount(c);
          if (waitFrames_ > 0) {
            --waitFrames_;
            advance(true);
          }
          return;
        case session::ScriptCommandKind::Wait:
          waitDraws_ = static_cast<int>(session::scriptCount(c));
          return;
        case session::ScriptCommandKind::Save: saveScene(c.args.at(0)); break;
        case session::ScriptCommandKind::Screenshot:
          pendingShot_ = std::filesystem::path(c.args.at(0));
          return;  // taken after this UI frame is drawn
        case session::ScriptCommandKind::Quit: quit_ = true; return;
      }
    } catch (const InputError& e) {
      fmt::print(stderr, "error: {}\n", e.what());
      exitCode_ = static_cast<int>(ExitCode::BadInput);
      quit_ = true;
      return;
    }
    if (messageIsError_ && !message_.empty()) {
      // A scripted action that failed ends the run: exit 3 for a file not written (S,
      // save), 2 for anything else (an edit refused, S on a recording).
      exitCode_ = static_cast<int>(writeFailed_ ? ExitCode::IoFailure : ExitCode::BadInput);
      quit_ = true;
      return;
    }
  }
}

int Viewer::run() {
  openWindow();
  lastUiFrame_ = std::chrono::steady_clock::now();
  while (!glfwWindowShouldClose(window_) && !quit_) {
    glfwPollEvents();
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    handleInput();

    // While a script has commands left, only its `frames` simulate: `wait` draws, paused
    // or not. N steps one frame whether it was pressed or scripted (`key N` in runScript).
    const bool scripted = !script_.empty() || waitDraws_ > 0 || waitFrames_ > 0;
    if (scripted) runScript();
    if (stepOnce_) {
      advance(true);
    } else if (!scripted && !paused_) {
      advance(options_.drawPerFrame != 0);  // the seed's -drawPerFrame 0 draws every update
    }
    stepOnce_ = false;
    // A drag applies its edits a few times a second and once more on release: each apply
    // validates and recompiles the whole scene, which is quick but not free.
    if (editsPending_ && (!ImGui::IsAnyItemActive() ||
                          std::chrono::steady_clock::now() - lastApply_ > std::chrono::milliseconds(250)))
      applyEdits();

    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    if (w > 0 && h > 0) {
      glBindFramebuffer(GL_FRAMEBUFFER, 0);
      const FrameSnapshot& shown = frame();
      std::vector<render::RenderSurface> surfaces;
      try {
        if (surfaces_) surfaces = surfacesOf(shown);
      } catch (const std::invalid_argument& e) {
        // A particle size the surfaces' grid cannot take (below 4e-5 or far above any
        // scene): the particles stay drawn, and the viewer says why.
        surfaces_ = false;
        setMessage(fmt::format("no surfaces for this scene: {}", e.what()), true);
      }
      renderer_->draw(shown, camera_, w, h, {}, surfaces);
    }
    drawPanels();
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    if (pendingShot_) {
      screenshot(*pendingShot_);
      pendingShot_.reset();
      if (writeFailed_ && !options_.script.empty()) {
        exitCode_ = static_cast<int>(ExitCode::IoFailure);
        quit_ = true;
      }
    }
    glfwSwapBuffers(window_);

    const auto now = std::chrono::steady_clock::now();
    const double dt = std::chrono::duration<double>(now - lastUiFrame_).count();
    lastUiFrame_ = now;
    if (dt > 0) uiFps_ = uiFps_ == 0 ? 1 / dt : 0.9 * uiFps_ + 0.1 / dt;
  }
  return exitCode_;
}

}  // namespace softsub::app
