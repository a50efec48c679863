#pragma once
// Ctrl-C (SIGINT) and SIGTERM ask a run to stop cleanly: the runner sees the flag,
// returns between steps, and the outputs are written with outcome "interrupted".
#include <atomic>

namespace regodem::app {

/// Installs the handlers and returns the flag they set. The first signal only sets
/// the flag; the handler then reverts to the default, so a second Ctrl-C ends a run
/// that does not stop at once.
const std::atomic<bool>& install_stop_request_handlers();

/// For a command that runs child processes (`regodem calibrate`): counts every SIGINT
/// and SIGTERM and stays installed, so that each one can be passed on to the children
/// (the first stops them cleanly, a second ends them at once, as for `regodem run`).
const std::atomic<int>& install_signal_counter();

/// The signal that asked to stop (SIGINT, SIGTERM), or 0 if none came.
int stop_signal();

}  // namespace regodem::app
