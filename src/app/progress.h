#pragma once
/// Progress of a run on stderr: a line redrawn in place, for a terminal only (the caller
/// decides: stderr is a terminal and not --quiet).
#include <chrono>
#include <cstdint>
#include <string>

#include "solver/frame_loop.h"

namespace softsub::app {

/// Draws `frame 12/48 | 10,000 particles | 3.2 ms/frame | ETA 0:05` on stderr,
/// redrawn in place with \r, when enabled (stderr is a terminal and not --quiet). With a
/// count of items (mesh, render: the frames of a recording, frame 0 among them), `frame
/// 2/48 (3 of 49)`, and the ETA from the items left.
class ProgressLine {
 public:
  /// `enabled` false makes every call a no-op.
  ProgressLine(bool enabled, std::int64_t lastFrame, std::size_t particles, std::size_t items = 0);
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;
  /// Ends the line if it was drawn and not ended.
  ~ProgressLine();

  /// Before the first frame: `frame F/LAST | N particles | <what>` (a run's frame 0 can
  /// take long: a million particles' surfaces, a large mesh).
  void begin(std::int64_t frame, const std::string& what);
  /// begin's line for a frame that is not an item (render: frames simulated before the
  /// range drawn), redrawn at most ten times a second.
  void note(std::int64_t frame, const std::string& what);
  /// After each completed frame (the frame loop's onProgress hook); frame 0 handed out
  /// before any stepping (FrameProgress::initial) is drawn, and counts neither in the
  /// frames nor in the rate.
  void update(const solver::FrameProgress& p);
  /// Ends the line with a newline (before a summary or an error message).
  void end();
  /// Wall seconds (simulation plus writing) per frame simulated so far, or per item with
  /// a count of items; 0 before the first.
  [[nodiscard]] double secondsPerFrame() const;
  /// Frames simulated since the start (items with a count of items).
  [[nodiscard]] std::int64_t framesDone() const { return done_; }

 private:
  void draw(std::int64_t frame);
  /// `frame F/LAST (K of N) | P particles` (without the count for item 0).
  [[nodiscard]] std::string head(std::int64_t frame, std::size_t item) const;
  /// Draws `line` over the last one, padded to clear it.
  void show(std::string line);

  bool enabled_;
  bool drawn_ = false;
  std::int64_t last_;
  std::size_t particles_;
  std::size_t items_;
  std::int64_t done_ = 0;
  double busySeconds_ = 0;
  std::size_t width_ = 0;
  std::chrono::steady_clock::time_point lastDraw_{};
};

/// A note on a terminal (`reading shots/big.scene ...`) while something slow runs
/// before the progress line can be drawn (a large mesh took 13 s to read in a review),
/// erased by clear() or when the note goes out of scope (an error unwinding past it).
class TerminalNote {
 public:
  TerminalNote(bool enabled, const std::string& text);
  TerminalNote(const TerminalNote&) = delete;
  TerminalNote& operator=(const TerminalNote&) = delete;
  ~TerminalNote();
  void clear();

 private:
  std::size_t width_ = 0;
};

/// True when stderr is a terminal.
bool stderrIsTerminal();

}  // namespace softsub::app
