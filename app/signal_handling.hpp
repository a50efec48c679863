#pragma once
// Ctrl-C (SIGINT) and SIGTERM ask a run to stop cleanly: the runner sees the flag,
// returns between steps, and the outputs are written with outcome "interrupted".
// Every such signal only asks; none ends the process, because tools send them in
// bursts (coreutils `timeout` signals the child and then its process group), and a
// second signal that killed the run would lose its summary and checkpoint. SIGQUIT
// (Ctrl-\ at a terminal) keeps its default action, to end a run at once.
#include <atomic>

namespace regodem::app {

/// Installs the handlers and returns the flag they set. Every SIGINT and SIGTERM sets
/// it, however many come; system calls they interrupt are restarted (SA_RESTART), so
/// a write in progress is not cut short.
const std::atomic<bool>& install_stop_request_handlers();

/// For a command that runs child processes (`regodem calibrate`): counts every SIGINT
/// and SIGTERM and stays installed, so that each one can be passed on to the children
/// (each of which then stops cleanly, as `regodem run` does).
const std::atomic<int>& install_signal_counter();

/// The signal that asked to stop (SIGINT, SIGTERM), or 0 if none came.
int stop_signal();

}  // namespace regodem::app
