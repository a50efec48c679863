// The network between two MPI ranks, as the cost model of a run over ranks
// (src/parallel/rank_cost_model.hpp) sees it: the one-way latency of a small message
// (half a round trip of 8 bytes), the bandwidth of a large one (4 MiB each way), and the
// time of one small allreduce (one collective round on two ranks). Run it where the ranks
// of a real run would be (one machine's shared memory, or two nodes of a cluster) and give
// its figures to `regodem estimate --ranks N --latency-us L --bandwidth-gb-per-s B`.
//
//   mpirun -np 2 build/release/bench/bench_ping_pong
#include <mpi.h>

#include <cstdio>
#include <vector>

#include "mpi_bench_main.hpp"

namespace regodem::bench {
namespace {

/// Seconds per round trip of `bytes` between ranks 0 and 1, over `trips`.
double round_trip_s(std::vector<char>& buffer, int trips, int rank) {
  const int bytes = static_cast<int>(buffer.size());
  MPI_Barrier(MPI_COMM_WORLD);
  const double start_s = MPI_Wtime();
  for (int t = 0; t < trips; ++t) {
    if (rank == 0) {
      MPI_Send(buffer.data(), bytes, MPI_CHAR, 1, 0, MPI_COMM_WORLD);
      MPI_Recv(buffer.data(), bytes, MPI_CHAR, 1, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    } else if (rank == 1) {
      MPI_Recv(buffer.data(), bytes, MPI_CHAR, 0, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      MPI_Send(buffer.data(), bytes, MPI_CHAR, 0, 0, MPI_COMM_WORLD);
    }
  }
  return (MPI_Wtime() - start_s) / trips;
}

int run(int, char**) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (size != 2) {
    if (rank == 0) std::fprintf(stderr, "bench_ping_pong runs on 2 ranks\n");
    return 2;
  }
  std::vector<char> small(8), large(4 << 20);
  round_trip_s(small, 1000, rank);  // warm up
  const double small_s = round_trip_s(small, 20000, rank);
  round_trip_s(large, 5, rank);
  const double large_s = round_trip_s(large, 100, rank);
  int values[2] = {rank, rank};
  MPI_Barrier(MPI_COMM_WORLD);
  const double start_s = MPI_Wtime();
  constexpr int kReductions = 20000;
  for (int k = 0; k < kReductions; ++k) MPI_Allreduce(MPI_IN_PLACE, values, 2, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  const double allreduce_s = (MPI_Wtime() - start_s) / kReductions;
  if (rank == 0)
    std::printf("latency %.3g us (half a round trip of 8 B)  bandwidth %.3g GB/s (4 MiB each way)  "
                "allreduce %.3g us (2 ints)\n",
                0.5 * small_s * 1e6, 2.0 * static_cast<double>(large.size()) / large_s / 1e9, allreduce_s * 1e6);
  return 0;
}

}  // namespace
}  // namespace regodem::bench

int main(int argc, char** argv) { return regodem::bench::mpi_bench_main(argc, argv, regodem::bench::run); }
