#include "solver/frame_loop.h"

#include <chrono>

namespace softsub::solver {

bool runFrames(Simulation& sim, std::int64_t lastFrame, std::span<FrameObserver* const> observers,
               const FrameLoopHooks& hooks) {
  using Clock = std::chrono::steady_clock;
  FrameSnapshot snap;
  auto emit = [&]() {
    if (hooks.recordUpTo >= 0 && sim.state().frame > hooks.recordUpTo) return;
    if (observers.empty()) return;
    sim.snapshot(snap);
    for (FrameObserver* o : observers) o->onFrame(snap);
  };
  if (sim.state().frame == 0 && hooks.emitInitial) {
    const auto t0 = Clock::now();
    emit();
    if (hooks.onProgress) {
      FrameProgress p{0, lastFrame, 0, std::chrono::duration<double>(Clock::now() - t0).count()};
      p.initial = true;
      hooks.onProgress(p);
    }
  }
  while (sim.state().frame < lastFrame) {
    if (hooks.stop && hooks.stop->load()) return false;
    const auto t0 = Clock::now();
    sim.advanceFrame();
    const auto t1 = Clock::now();
    emit();
    const auto t2 = Clock::now();
    if (hooks.onProgress)
      hooks.onProgress({sim.state().frame, lastFrame, std::chrono::duration<double>(t1 - t0).count(),
                        std::chrono::duration<double>(t2 - t1).count()});
  }
  return true;
}

}  // namespace softsub::solver
