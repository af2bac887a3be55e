#pragma once
/// Ctrl-C and SIGTERM: ask the frame loop to stop after the current frame.
#include <atomic>

namespace softsub::app {

/// Installs SIGINT and SIGTERM handlers that set the returned flag. A second signal
/// of the same kind gets the default action (the process ends at once; frames already
/// written stay complete because each is renamed into place).
const std::atomic<bool>& installStopHandlers();

/// The signal that set the flag (SIGINT or SIGTERM), or 0.
int stopSignal();
/// "SIGTERM" when SIGTERM set the flag, else "SIGINT" (for messages).
const char* stopSignalName();

}  // namespace softsub::app
