#include "progress.h"

#include <cstdio>

#include <fmt/format.h>
#include <unistd.h>

#include "text_format.h"

namespace softsub::app {

bool stderrIsTerminal() { return ::isatty(::fileno(stderr)) == 1; }

ProgressLine::ProgressLine(bool enabled, std::int64_t lastFrame, std::size_t particles, std::size_t items)
    : enabled_(enabled), last_(lastFrame), particles_(particles), items_(items) {}

ProgressLine::~ProgressLine() { end(); }

TerminalNote::TerminalNote(bool enabled, const std::string& text) {
  if (!enabled) return;
  fmt::print(stderr, "{}", text);
  std::fflush(stderr);
  width_ = text.size();
}

TerminalNote::~TerminalNote() { clear(); }

void TerminalNote::clear() {
  if (width_ == 0) return;
  fmt::print(stderr, "\r{}\r", std::string(width_, ' '));
  std::fflush(stderr);
  width_ = 0;
}

double ProgressLine::secondsPerFrame() const {
  return done_ > 0 ? busySeconds_ / static_cast<double>(done_) : 0.0;
}

std::string ProgressLine::head(std::int64_t frame, std::size_t item) const {
  const std::string where = item > 0 ? fmt::format("frame {}/{} ({} of {})", frame, last_, item, items_)
                                     : fmt::format("frame {}/{}", frame, last_);
  return fmt::format("{} | {}", where, countOf(particles_, "particle"));
}

void ProgressLine::show(std::string line) {
  const std::size_t len = line.size();
  if (len < width_) line.append(width_ - len, ' ');  // clear what a longer line left
  width_ = len;
  fmt::print(stderr, "\r{}", line);
  std::fflush(stderr);
  drawn_ = true;
  lastDraw_ = std::chrono::steady_clock::now();
}

void ProgressLine::begin(std::int64_t frame, const std::string& what) {
  if (enabled_) show(fmt::format("{} | {}", head(frame, items_ > 0 ? 1 : 0), what));
}

void ProgressLine::note(std::int64_t frame, const std::string& what) {
  if (!enabled_ || (drawn_ && std::chrono::steady_clock::now() - lastDraw_ < std::chrono::milliseconds(100)))
    return;
  show(fmt::format("{} | {}", head(frame, 0), what));
}

void ProgressLine::update(const solver::FrameProgress& p) {
  if (p.initial) {
    // Frame 0, written before any stepping: its own line, and not in the rate (with
    // surfaces it costs a frame's meshing, but no simulation).
    if (enabled_ && p.frame < last_) draw(p.frame);
    return;
  }
  ++done_;
  busySeconds_ += p.stepSeconds + p.writeSeconds;
  if (!enabled_) return;
  // Redraw at most ten times a second, and always for frame 0, the first frame simulated
  // (or item) and the last.
  if (p.frame < last_ && done_ > 1 && drawn_ &&
      std::chrono::steady_clock::now() - lastDraw_ < std::chrono::milliseconds(100))
    return;
  draw(p.frame);
}

void ProgressLine::draw(std::int64_t frame) {
  const double left = items_ > 0 ? static_cast<double>(items_) - static_cast<double>(done_)
                                 : static_cast<double>(last_ - frame);
  const std::string where = head(frame, items_ > 0 ? static_cast<std::size_t>(done_) : 0);
  // Frame 0 alone (nothing simulated yet): no rate to give.
  show(done_ == 0 ? where + " | simulating"
                  : fmt::format("{} | {:.1f} ms/frame | ETA {}", where, secondsPerFrame() * 1e3,
                                clockTime(left * secondsPerFrame())));
}

void ProgressLine::end() {
  if (!enabled_ || !drawn_) return;
  fmt::print(stderr, "\n");
  std::fflush(stderr);
  drawn_ = false;
}

}  // namespace softsub::app
