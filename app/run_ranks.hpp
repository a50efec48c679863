#pragma once
// `mpirun -np N regodem run SCENARIO` (issue 19): the ranks of one run. Every rank reads
// and builds the scenario the same; the domain is cut into one brick per rank and the run
// starts gathered (Simulation::gather_everywhere): each rank steps the particles of its
// brick, and between steps, where anything reads or adds particles (insertion, samples,
// measurements, snapshots, checkpoints, a static-bed stage), every rank holds them all.
// Rank 0 alone writes the outputs. Only run_ranks_mpi.cpp includes mpi.h; a regodem built
// without MPI refuses to run under mpirun (run_ranks_without_mpi.cpp).
#include <exception>
#include <memory>

namespace regodem {
class Simulation;
}

namespace regodem::app {

/// Whether a launcher (mpirun, mpiexec, srun) started this process as a rank of a job.
bool started_as_mpi_rank();
/// This process's rank as its launcher's environment gives it, before MPI starts (0 when
/// not started as a rank): what only rank 0 does before then (probing a run's lock).
int launcher_rank();

class RunRanks {
 public:
  /// Starts MPI. Throws InputError when this regodem was built without MPI.
  RunRanks();
  RunRanks(const RunRanks&) = delete;
  RunRanks& operator=(const RunRanks&) = delete;
  /// Ends MPI.
  ~RunRanks();

  int rank() const;
  int size() const;
  /// A point every rank reaches with the error it met (or none): when any rank brings one,
  /// every rank throws that of the lowest such rank, so that none waits for one that stopped.
  void agree(const std::exception_ptr& error);
  /// Ends every rank of the job now with `exit_code` (MPI_Abort): after an error that this
  /// rank alone may have met (writing an output), when the others may wait for it.
  [[noreturn]] void abort(int exit_code);
  /// From here `sim`, built the same on every rank, is stepped over the ranks: one brick
  /// of its domain each, starting gathered (every rank holds every particle; the first
  /// build keeps each brick's).
  void take(Simulation& sim);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace regodem::app
