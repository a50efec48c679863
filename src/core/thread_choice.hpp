#pragma once
// How many OpenMP threads a run uses when the user does not say. On a machine whose
// cores are busy, threads that wait in barriers for a descheduled partner run slower
// than one thread would: the 20,000-particle bed with heat stepped at 6.4e6
// particle-steps/s on one thread and 3.6e6 on two while another process held one of
// the two cores (docs/benchmarks.md). So the default leaves out the cores other
// runnable processes hold. An explicit --threads is never changed. The choice is made
// once, at the start (results do not depend on the thread count; changing it during a
// run is not done yet).
#include <string>

namespace regodem {

struct ThreadChoice {
  int threads = 1;
  std::string note;  // why fewer than the cores, or empty
};

/// `available` threads (omp_get_max_threads), of which `busy_elsewhere` cores are held
/// by other runnable processes: available − busy_elsewhere, at least 1. (The caller
/// leaves an OMP_NUM_THREADS the user set alone: that is an explicit choice too.
/// procs_running counts the whole host: in a container on a busy host it undercounts
/// the threads the container could use.)
ThreadChoice choose_threads(int available, int busy_elsewhere);

/// Runnable processes other than this one, from /proc/stat's procs_running: the least of
/// a few readings 10 ms apart, so that a process that only passes by does not count.
/// 0 where /proc cannot be read.
int runnable_processes_elsewhere();

}  // namespace regodem
