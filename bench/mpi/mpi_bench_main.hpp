#pragma once
// The main of a benchmark run under mpirun: MPI started and ended around `run`, and an
// error on any rank ending every rank with its message.
#include <mpi.h>

#include <cstdio>
#include <exception>

namespace regodem::bench {

template <typename Run>
int mpi_bench_main(int argc, char** argv, Run run) {
  MPI_Init(&argc, &argv);
  int status = 1;
  try {
    status = run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  MPI_Finalize();
  return status;
}

}  // namespace regodem::bench
