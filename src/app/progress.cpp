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

void ProgressLine::begin(std::int64_t frame, const std::string& what) {
  if (!enabled_) return;
  const std::string where = items_ > 0 ? fmt::format("frame {}/{} (1 of {})", frame, last_, items_)
                                       : fmt::format("frame {}/{}", frame, last_);
  std::string line = fmt::format("{} | {} | {}", where, countOf(particles_, "particle"), what);
  width_ = line.size();
  fmt::print(stderr, "\r{}", line);
  std::fflush(stderr);
  drawn_ = true;
  lastDraw_ = std::chrono::steady_clock::now();
}

void ProgressLine::note(std::int64_t frame, const std::string& what) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (drawn_ && now - lastDraw_ < std::chrono::milliseconds(100)) return;
  std::string line =
      fmt::format("frame {}/{} | {} | {}", frame, last_, countOf(particles_, "particle"), what);
  const std::size_t len = line.size();
  if (len < width_) line.append(width_ - len, ' ');
  width_ = len;
  fmt::print(stderr, "\r{}", line);
  std::fflush(stderr);
  drawn_ = true;
  lastDraw_ = now;
}

void ProgressLine::update(const solver::FrameProgress& p) {
  if (p.initial) {
    // Frame 0, written before any stepping: its own line, and not in the rate (with
    // surfaces it costs a frame's meshing, but no simulation).
    if (enabled_ && p.frame < last_) {
      lastDraw_ = std::chrono::steady_clock::now();
      draw(p.frame);
    }
    return;
  }
  ++done_;
  busySeconds_ += p.stepSeconds + p.writeSeconds;
  if (!enabled_) return;
  // Redraw at most ten times a second, and always for frame 0, the first frame simulated
  // (or item) and the last.
  const auto now = std::chrono::steady_clock::now();
  if (p.frame < last_ && !p.initial && done_ > 1 && drawn_ &&
      now - lastDraw_ < std::chrono::milliseconds(100))
    return;
  lastDraw_ = now;
  draw(p.frame);
}

void ProgressLine::draw(std::int64_t frame) {
  const double left = items_ > 0 ? static_cast<double>(items_) - static_cast<double>(done_)
                                 : static_cast<double>(last_ - frame);
  const std::string where = items_ > 0 ? fmt::format("frame {}/{} ({} of {})", frame, last_, done_, items_)
                                       : fmt::format("frame {}/{}", frame, last_);
  // Frame 0 alone (nothing simulated yet): no rate to give.
  std::string line =
      done_ == 0 ? fmt::format("{} | {} | simulating", where, countOf(particles_, "particle"))
                 : fmt::format("{} | {} | {:.1f} ms/frame | ETA {}", where, countOf(particles_, "particle"),
                               secondsPerFrame() * 1e3, clockTime(left * secondsPerFrame()));
  const std::size_t len = line.size();
  if (len < width_) line.append(width_ - len, ' ');  // clear what a longer line left
  width_ = len;
  fmt::print(stderr, "\r{}", line);
  std::fflush(stderr);
  drawn_ = true;
}

void ProgressLine::end() {
  if (!enabled_ || !drawn_) return;
  fmt::print(stderr, "\n");
  std::fflush(stderr);
  drawn_ = false;
}

}  // namespace softsub::app
