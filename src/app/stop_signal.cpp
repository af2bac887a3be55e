#include "stop_signal.h"

#include <csignal>

namespace softsub::app {

namespace {

// Written from the signal handler: lock-free atomics only.
std::atomic<bool> gStop{false};
std::atomic<int> gSignal{0};
static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<int>::is_always_lock_free);

extern "C" void onStopSignal(int sig) {
  gSignal.store(sig);
  gStop.store(true);
  std::signal(sig, SIG_DFL);  // a second Ctrl-C ends the process at once
}

}  // namespace

const std::atomic<bool>& installStopHandlers() {
  std::signal(SIGINT, onStopSignal);
  std::signal(SIGTERM, onStopSignal);
  return gStop;
}

int stopSignal() { return gSignal.load(); }

const char* stopSignalName() { return stopSignal() == SIGTERM ? "SIGTERM" : "SIGINT"; }

}  // namespace softsub::app
