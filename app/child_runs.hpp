#pragma once
// Child processes of regodem itself (`regodem calibrate` runs `regodem run` for each
// point), at most N at once, with SIGINT/SIGTERM passed on to them.
#include <atomic>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace regodem::app {

/// This program's own executable (/proc/self/exe), to start children of the same build.
std::string own_executable();

struct ChildJob {
  std::vector<std::string> arguments;  // after the program name
  std::filesystem::path log;           // stdout and stderr of the child
};

struct ChildResult {
  int exit_code = -1;  // 128 + signal when a signal ended it
  double wall_s = 0.0;
};

struct ChildEvents {
  std::function<void(std::size_t job)> started;
  std::function<void(std::size_t job, const ChildResult&)> finished;
};

/// Runs `jobs` with `program` (a path, or a name looked for on the PATH), at most
/// `processes` at once, in order. Each child gets
/// its own process group, so a Ctrl-C at the terminal reaches this process only and is
/// passed on exactly once: the first increase of `signals` (install_signal_counter)
/// sends SIGINT to the running children, which stop cleanly and write their summaries
/// and checkpoints; later signals are only reported (a child never dies of a signal).
/// After a signal, or once a job has failed (exit status not 0), no new job starts; the
/// running ones are waited for. Returns a result per job; none for a job not started.
std::vector<std::optional<ChildResult>> run_children(const std::string& program, const std::vector<ChildJob>& jobs,
                                                     int processes, const std::atomic<int>& signals,
                                                     const ChildEvents& events);

}  // namespace regodem::app
