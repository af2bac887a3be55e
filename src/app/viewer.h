#pragma once
/// The viewer's window: GLFW + OpenGL 3.3 core + Dear ImGui around the shared renderer,
/// a live session or a recorded folder, the seed's keys and a scripted input.
#include <chrono>
#include <deque>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cmd_view.h"
#include "core/error.h"
#include "core/snapshot.h"
#include "render/camera.h"
#include "render/render_scene.h"
#include "session/script.h"
#include "solver/stability.h"

struct GLFWwindow;

namespace softsub::render {
class Renderer;
}
namespace softsub::session {
class LiveSession;
}

namespace softsub::app {

class RecordedFrames;

/// One viewer window. Construct, run(), done.
class Viewer {
 public:
  explicit Viewer(const ViewOptions& options);
  ~Viewer();
  Viewer(const Viewer&) = delete;
  Viewer& operator=(const Viewer&) = delete;

  /// The event loop; returns the exit code when the window closes or the script quits.
  int run();

 private:
  // viewer.cpp
  void openWindow();
  void handleInput();
  void onKey(int key, int action, int mods);
  void onScroll(double dy);
  void advance(bool wholeFrame);   // a frame or a substep (live), or the next recorded frame
  void restart();
  void writeCaches();
  void screenshot(const std::filesystem::path& path);
  void saveScene(const std::filesystem::path& path);
  void runScript();               // executes queued commands until one must wait
  void setMessage(std::string text, bool error = false);
  [[nodiscard]] bool live() const { return session_ != nullptr; }
  [[nodiscard]] const FrameSnapshot& frame() const;

  // viewer_panels.cpp
  void drawPanels();
  void drawSimulationPanel();
  void drawFluidPanels();
  void drawInteractionsPanel();
  void drawPlaybackPanel();
  void drawHelpOverlay();
  void drawTransport(const char* restartLabel);  // play/pause, step, restart buttons
  // After a widget or a script changed the scene description. A refused edit goes to
  // `refused` when given (a script's line says it), else to the message.
  void applyEdits(std::optional<InputError>* refused = nullptr);
  void refreshStability();

  ViewOptions options_;
  GLFWwindow* window_ = nullptr;
  bool imguiReady_ = false;
  std::unique_ptr<render::Renderer> renderer_;
  render::RenderScene renderScene_;
  render::Camera camera_;
  render::Camera startCamera_;

  std::unique_ptr<session::LiveSession> session_;   // live mode
  std::unique_ptr<RecordedFrames> recorded_;        // playback mode
  std::vector<std::string> playbackWarnings_;       // playback mode: printed at start, shown in the panel
  std::size_t playIndex_ = 0;
  FrameSnapshot playFrame_;
  std::string sceneName_;
  std::vector<std::filesystem::path> inputFiles_;  // the live scene's, kept when S replaces a run

  bool paused_ = false;
  bool stepOnce_ = false;
  bool showHelp_ = false;
  bool surfaces_ = false;  // draw each fluid's surface (meshed every drawn frame) instead of particles
  bool editsPending_ = false;
  bool quit_ = false;
  int exitCode_ = 0;
  std::string message_;
  bool messageIsError_ = false;
  bool writeFailed_ = false;  // a file could not be written (S, save, screenshot): a script exits 3
  std::optional<solver::StabilityReport> stability_;

  // Mouse orbit.
  bool dragging_ = false;
  double lastX_ = 0, lastY_ = 0;

  // Scripted input: commands left, and UI frames or simulation frames to wait for.
  std::deque<session::ScriptCommand> script_;
  int waitDraws_ = 0;
  std::optional<std::filesystem::path> pendingShot_;  // written after the UI frame is drawn
  std::int64_t waitFrames_ = 0;

  // Stats.
  double uiFps_ = 0;
  std::chrono::steady_clock::time_point lastUiFrame_{};
  std::chrono::steady_clock::time_point lastApply_{};
  char savePath_[512] = {};
};

}  // namespace softsub::app
