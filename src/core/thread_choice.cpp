#include "core/thread_choice.hpp"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <sstream>
#include <thread>

#include <fmt/format.h>

namespace regodem {
namespace {

/// procs_running of /proc/stat: the tasks running or ready to run now; -1 if unreadable.
int procs_running() {
  std::ifstream stat("/proc/stat");
  std::string line;
  while (std::getline(stat, line)) {
    if (line.rfind("procs_running ", 0) != 0) continue;
    std::istringstream in(line.substr(14));
    int count = -1;
    in >> count;
    return count;
  }
  return -1;
}

}  // namespace

ThreadChoice choose_threads(int available, int busy_elsewhere) {
  ThreadChoice choice;
  choice.threads = std::max(1, available - std::max(0, busy_elsewhere));
  if (choice.threads < available)
    choice.note = fmt::format(
        "the machine is busy ({} other runnable process{} on {} thread{}): running on {} thread{}, since threads "
        "that share busy cores run slower than fewer threads; --threads N chooses",
        busy_elsewhere, busy_elsewhere == 1 ? "" : "es", available, available == 1 ? "" : "s", choice.threads,
        choice.threads == 1 ? "" : "s");
  return choice;
}

int runnable_processes_elsewhere() {
  int least = -1;
  for (int reading = 0; reading < 5; ++reading) {
    if (reading > 0) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    const int running = procs_running();
    if (running < 0) return 0;
    least = least < 0 ? running : std::min(least, running);
  }
  return std::max(0, least - 1);  // this process's own thread is running as it reads
}

}  // namespace regodem
