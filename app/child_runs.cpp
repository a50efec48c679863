#include "child_runs.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <thread>

#include <fmt/format.h>

#include "core/error.hpp"
#include "run_ranks.hpp"

extern char** environ;

namespace regodem::app {
namespace {

using Clock = std::chrono::steady_clock;

pid_t spawn_child(const std::string& program, const ChildJob& job) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, job.log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
  posix_spawnattr_setpgroup(&attributes, 0);  // its own group: see run_children
  std::vector<std::string> all{program};
  all.insert(all.end(), job.arguments.begin(), job.arguments.end());
  std::vector<char*> argv;
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  // A child is a run (or an mpirun) of its own. Where this process is itself a rank of an
  // MPI job, the launcher's variables stay behind (the child would take itself for a rank of
  // that job); otherwise the environment is passed on whole (MPI settings included).
  const bool a_rank = started_as_mpi_rank();
  std::vector<char*> environment;
  for (char** variable = environ; *variable != nullptr; ++variable) {
    const std::string_view text(*variable);
    if (a_rank && (text.starts_with("OMPI_") || text.starts_with("PMI_") || text.starts_with("PMIX_"))) continue;
    environment.push_back(*variable);
  }
  environment.push_back(nullptr);
  pid_t pid = -1;
  // A program named without a folder (mpirun) is looked for on the PATH.
  const int error = posix_spawnp(&pid, program.c_str(), &actions, &attributes, argv.data(), environment.data());
  posix_spawnattr_destroy(&attributes);
  posix_spawn_file_actions_destroy(&actions);
  if (error != 0) throw std::runtime_error(fmt::format("cannot start {}: {}", program, std::strerror(error)));
  return pid;
}

struct Running {
  pid_t pid;
  std::size_t job;
  Clock::time_point started;
};

}  // namespace

std::string own_executable() {
  std::error_code error;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) throw std::runtime_error("cannot find this program's own file (/proc/self/exe) to start runs with");
  return self.string();
}

std::vector<std::optional<ChildResult>> run_children(const std::string& program, const std::vector<ChildJob>& jobs,
                                                     int processes, const std::atomic<int>& signals,
                                                     const ChildEvents& events) {
  std::vector<std::optional<ChildResult>> results(jobs.size());
  std::vector<Running> running;
  std::size_t next = 0;
  int signals_passed_on = signals.load();
  bool failed = false;
  while (true) {
    while (signals.load() > signals_passed_on) {
      ++signals_passed_on;
      if (running.empty()) continue;
      if (signals_passed_on == 1) {
        fmt::print(stderr, "regodem: stopping the {} running run{} cleanly (each writes its summary and a checkpoint)\n",
                   running.size(), running.size() == 1 ? "" : "s");
        for (const Running& r : running) ::kill(r.pid, SIGINT);
      } else {
        fmt::print(stderr, "regodem: already stopping the {} running run{}\n", running.size(),
                   running.size() == 1 ? "" : "s");
      }
    }
    const bool may_start = signals_passed_on == 0 && !failed;
    while (may_start && next < jobs.size() && static_cast<int>(running.size()) < processes) {
      running.push_back({spawn_child(program, jobs[next]), next, Clock::now()});
      if (events.started) events.started(next);
      ++next;
    }
    if (running.empty()) break;
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, WNOHANG);
    if (pid <= 0) {
      // Polling keeps a signal that arrives at any moment from waiting on a child.
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      continue;
    }
    for (auto r = running.begin(); r != running.end(); ++r) {
      if (r->pid != pid) continue;
      ChildResult result;
      result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      result.wall_s = std::chrono::duration<double>(Clock::now() - r->started).count();
      results[r->job] = result;
      failed = failed || result.exit_code != 0;
      const std::size_t job = r->job;
      running.erase(r);
      if (events.finished) events.finished(job, result);
      break;
    }
  }
  return results;
}

}  // namespace regodem::app
