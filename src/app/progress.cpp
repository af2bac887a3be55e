#include "progress.h"

#include <cstdio>

#include <fmt/format.h>
#include <unistd.h>

#include "text_format.h"

namespace softsub::app {

bool stderrIsTerminal() { return ::isatty(::fileno(stderr)) == 1; }

ProgressLine::ProgressLine(bool enabled, std::int64_t lastFrame, std::size_t particles)
    : enabled_(enabled), last_(lastFrame), particles_(particles) {}

ProgressLine::~ProgressLine() { end(); }

double ProgressLine::secondsPerFrame() const {
  return done_ > 0 ? busySeconds_ / static_cast<double>(done_) : 0.0;
}

void ProgressLine::update(const solver::FrameProgress& p) {
  ++done_;
  busySeconds_ += p.stepSeconds + p.writeSeconds;
  if (!enabled_) return;
  // Redraw at most ten times a second, and always for the last frame.
  const auto now = std::chrono::steady_clock::now();
  if (p.frame < last_ && drawn_ && now - lastDraw_ < std::chrono::milliseconds(100)) return;
  lastDraw_ = now;
  draw(p.frame);
}

void ProgressLine::draw(std::int64_t frame) {
  const double remaining = static_cast<double>(last_ - frame) * secondsPerFrame();
  std::string line = fmt::format("frame {}/{} | {} | {:.1f} ms/frame | ETA {}", frame, last_,
                                 countOf(particles_, "particle"), secondsPerFrame() * 1e3,
                                 clockTime(remaining));
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
