#pragma once
/// Progress of a run on stderr: a line redrawn in place, for a terminal only (the caller
/// decides: stderr is a terminal and not --quiet).
#include <chrono>
#include <cstdint>
#include <string>

#include "solver/frame_loop.h"

namespace softsub::app {

/// Draws `frame 12/48 | 10,000 particles | 3.2 ms/frame | ETA 0:05` on stderr,
/// redrawn in place with \r, when enabled (stderr is a terminal and not --quiet).
class ProgressLine {
 public:
  /// `enabled` false makes every call a no-op.
  ProgressLine(bool enabled, std::int64_t lastFrame, std::size_t particles);
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;
  /// Ends the line if it was drawn and not ended.
  ~ProgressLine();

  /// After each completed frame (the frame loop's onProgress hook).
  void update(const solver::FrameProgress& p);
  /// Ends the line with a newline (before a summary or an error message).
  void end();
  /// Mean wall seconds per simulated frame (simulation plus writing) so far.
  [[nodiscard]] double secondsPerFrame() const;
  /// Frames completed since the start.
  [[nodiscard]] std::int64_t framesDone() const { return done_; }

 private:
  void draw(std::int64_t frame);

  bool enabled_;
  bool drawn_ = false;
  std::int64_t last_;
  std::size_t particles_;
  std::int64_t done_ = 0;
  double busySeconds_ = 0;
  std::size_t width_ = 0;
  std::chrono::steady_clock::time_point lastDraw_{};
};

/// True when stderr is a terminal.
bool stderrIsTerminal();

}  // namespace softsub::app
