#pragma once
/// The frame loop: advances a Simulation frame by frame and hands each frame's
/// snapshot to observers (cache writers, viewer). The solver never writes files.
#include <atomic>
#include <cstdint>
#include <functional>
#include <span>

#include "core/snapshot.h"
#include "solver/simulation.h"

namespace softsub::solver {

/// Timing of one completed frame, for progress reports.
struct FrameProgress {
  std::int64_t frame = 0;       ///< the frame just completed
  std::int64_t lastFrame = 0;   ///< the frame the loop runs to
  double stepSeconds = 0;       ///< wall time spent simulating this frame
  double writeSeconds = 0;      ///< wall time spent in observers for this frame
  /// Frame 0 handed to the observers before any stepping (FrameLoopHooks::emitInitial):
  /// written, not simulated.
  bool initial = false;
};

/// Optional hooks of a frame loop.
struct FrameLoopHooks {
  /// After each frame, frame 0 included when it is handed out (FrameProgress::initial).
  std::function<void(const FrameProgress&)> onProgress;
  const std::atomic<bool>* stop = nullptr;  ///< checked between frames; true = stop early
  std::int64_t recordUpTo = -1;             ///< observers see frames <= this (-1: all)
  /// Hand a simulation at frame 0 to the observers before stepping (false when it was
  /// restored from a frame the observers already had).
  bool emitInitial = true;
};

/// Runs `sim` until frame `lastFrame`. Observers get the current frame first when it
/// is frame 0 (the initial state; unless hooks.emitInitial is false), then every
/// completed frame. Returns false if
/// stopped early through hooks.stop (the last frame handed out is complete).
bool runFrames(Simulation& sim, std::int64_t lastFrame, std::span<FrameObserver* const> observers,
               const FrameLoopHooks& hooks = {});

}  // namespace softsub::solver
