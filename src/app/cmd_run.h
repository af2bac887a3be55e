#pragma once
/// `softsub run`: simulate a scene (or the embedded default scene) into frame caches.
#include <cstdint>
#include <optional>
#include <string>

#include "surface/surface.h"

namespace CLI {
class App;
}

namespace softsub::app {

/// The options of `run` as given on the command line; unset (nullopt or empty) values
/// mean "take the scene's".
struct RunOptions {
  std::string scene;                  ///< .scene file; empty: the embedded default scene
  std::optional<std::int64_t> frames;    ///< --frames; unset: the scene's Frames
  std::optional<std::int64_t> substeps;  ///< --substeps / -updateNum; unset: the scene's Substeps
  std::string out;                    ///< --out; empty: <sceneDir>/<sceneName>Sim
  std::string formats = "all";        ///< --formats
  std::string integrator;             ///< --integrator; empty: the scene's
  bool quiet = false;                 ///< --quiet: nothing on stderr but errors
  std::uint64_t maxParticles = 0;     ///< --max-particles; 0: the reader's default limit
  bool printScene = false;            ///< --print-scene: print SCENE's text (or the default's) and exit
  int record = -1;                    ///< -record 0|1; 0 means --formats none
  std::int64_t stopRecordingAt = -1;  ///< -stopRecordingAt F; -1: no limit
  std::string drawPerFrame;           ///< -drawPerFrame X; accepted and ignored (viewer)
  bool preview = false;               ///< --preview: a PNG of the last frame in the output folder
  surface::SurfaceSettings surface;   ///< --voxel-size, --blob-radius for mesh/vdb
  bool stats = false;                 ///< --stats: per-frame energies on stdout
  bool resume = false;                ///< --resume: continue after the last complete frame
  int checkpointEvery = 1;            ///< --checkpoint-every K (0: no checkpoints)
  bool adaptive = false;              ///< --adaptive: substeps chosen per frame
  int maxSubsteps = 10000;            ///< --max-substeps: the most --adaptive may choose
  double speedLimit = 10;             ///< --speed-limit: interaction distances per substep (0: off)
};

/// Adds the `run` subcommand bound to `options` and returns it.
CLI::App* addRunCommand(CLI::App& root, RunOptions& options);

/// Runs it. Returns the exit code (0, or 130 when interrupted); throws InputError,
/// IoError or BlowUpError on failure.
int runCommand(const RunOptions& options);

}  // namespace softsub::app
