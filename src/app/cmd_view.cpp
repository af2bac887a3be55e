#include "cmd_view.h"
#include "number_checks.h"

#include <CLI/CLI.hpp>

#include "viewer.h"

namespace softsub::app {

namespace {
constexpr const char* kSeedGroup = "Seed flags (also accepted with one dash, as in the seed)";
}

CLI::App* addViewCommand(CLI::App& root, ViewOptions& o) {
  CLI::App* cmd = root.add_subcommand(
      "view", "Open a window that simulates a scene live, with every parameter tweakable while it runs, or plays "
              "back a recorded <scene>Sim folder (press H in the window for the keys)");
  cmd->add_option("INPUT,-f,--scene", o.input,
                  ".scene file or recorded folder (default: the embedded default scene; seed: -f FILE)")
      ->check(nonEmptyPath());
  cmd->add_option("--substeps", o.substeps,
                  "Overrides <Simulation><Substeps> (a scene only; seed: -updateNum N)")
      ->transform(wholeNumberIn(1, 10000));
  cmd->add_option("--out", o.out, "Where S writes the recorded frames (default: <sceneDir>/<sceneName>Sim)")
      ->check(nonEmptyPath());
  cmd->add_option("--script", o.script,
                  "Scripted input, one command a line: set fluid NAME TAG VALUE, set simulation TAG VALUE, "
                  "key K, frames N, wait N, save FILE.scene, screenshot FILE.png, quit (docs/cli.md)");
  cmd->add_option("--width", o.width, "Window width")->transform(wholeNumberIn(200, 16384))->capture_default_str();
  cmd->add_option("--height", o.height, "Window height")->transform(wholeNumberIn(150, 16384))->capture_default_str();
  cmd->add_flag("--paused", o.paused, "Start paused (Space plays, N steps)");
  cmd->add_option("--max-particles", o.maxParticles,
                  "Refuse scenes with more particles than this (a scene only; default: the reader's limit)")
      ->transform(particleCap());
  cmd->add_option("--record", o.record, "1: keep every frame in memory so S can write them; 0: do not")
      ->transform(wholeNumberIn(0, 1))
      ->capture_default_str()
      ->group(kSeedGroup);
  cmd->add_option("--stop-recording-at", o.stopRecordingAt, "Last frame kept for S (-1: no limit)")
      ->transform(wholeNumberIn(-1, std::numeric_limits<std::int64_t>::max()))
      ->capture_default_str()
      ->group(kSeedGroup);
  cmd->add_option("--draw-per-frame", o.drawPerFrame, "1: draw every frame; 0: draw every substep")
      ->transform(wholeNumberIn(0, 1))
      ->capture_default_str()
      ->group(kSeedGroup);
  return cmd;
}

int viewCommand(const ViewOptions& options) {
  Viewer viewer(options);
  return viewer.run();
}

}  // namespace softsub::app
