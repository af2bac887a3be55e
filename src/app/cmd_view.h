#pragma once
/// `softsub view`: a window that simulates a scene live (every parameter tweakable while
/// it runs) or plays back a recorded folder, drawn by the same renderer as `render`.
#include <cstdint>
#include <optional>
#include <string>

namespace CLI {
class App;
}

namespace softsub::app {

/// The options of `view`.
struct ViewOptions {
  std::string input;                     ///< .scene file or recorded folder; empty: the default scene
  std::optional<std::int64_t> substeps;  ///< --substeps / -updateNum
  std::string out;                       ///< where S writes caches (default <sceneDir>/<scene>Sim)
  int record = 1;                        ///< -record: keep frames in memory for S
  std::int64_t stopRecordingAt = -1;     ///< -stopRecordingAt: last frame kept
  int drawPerFrame = 1;                  ///< -drawPerFrame: 1 draws each frame, 0 each substep
  std::string script;                    ///< --script FILE: scripted input (tests, demos)
  int width = 1280;                      ///< window width
  int height = 800;                      ///< window height
  bool paused = false;                   ///< --paused: start paused
  std::uint64_t maxParticles = 0;        ///< as `run --max-particles`
};

/// Adds the `view` subcommand bound to `options` and returns it.
CLI::App* addViewCommand(CLI::App& root, ViewOptions& options);

/// Runs it until the window closes; returns the exit code, throws InputError/IoError.
int viewCommand(const ViewOptions& options);

}  // namespace softsub::app
