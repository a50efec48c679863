// Particle-steps per second of the settled paper bed with heat (bench_settled_bed's
// particles:20000/heat:1 bed: 0.6 mm grains at the real modulus on a 700 degC plate) stepped
// over MPI ranks (issue 19): every rank reads the same stiffened bed, keeps the grains of its
// brick (Simulation::distribute, HaloExchange), steps 1,000 steps to settle in, then times
// `steps` steps between two barriers. One thread per rank. `plain` (one rank only) steps the
// same bed without the halo, for the halo's own cost.
//
//   mpirun -np 2 --bind-to core build/release/bench/bench_settled_bed_ranks [particles] [steps] [plain]
// (REGODEM_BENCH_CACHE: where the poured and stiffened beds are kept; rank 0 writes them once.)
#include <mpi.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "../paper_bed.hpp"
#include "mpi_bench_main.hpp"
#include "parallel/mpi/halo_exchange.hpp"

namespace regodem::bench {
namespace {

std::vector<ParticleRecord> stiffened_bed_cached(std::size_t count, const Communicator& comm) {
  const char* dir = std::getenv("REGODEM_BENCH_CACHE");
  const std::filesystem::path path =
      std::filesystem::path(dir ? dir : ".") / ("regodem-bench-bed-" + std::to_string(count) + "-stiffened.csv");
  if (comm.rank() == 0 && !std::filesystem::exists(path)) {
    const std::vector<ParticleRecord> bed = stiffened_bed(settled_bed(count), 2);
    std::ofstream out(path);
    out.precision(17);
    out << "x,y,z,radius\n";
    for (const ParticleRecord& r : bed)
      out << r.position_m.x << ',' << r.position_m.y << ',' << r.position_m.z << ',' << kRadius << '\n';
  }
  MPI_Barrier(MPI_COMM_WORLD);
  return read_particle_csv(path.string());
}

int run(int argc, char** argv) {
  const Communicator comm;
  const std::size_t count = argc > 1 ? std::stoul(argv[1]) : 20000;
  const std::uint64_t steps = argc > 2 ? std::stoull(argv[2]) : 1000;
  const bool plain = argc > 3 && std::string(argv[3]) == "plain";
  if (plain && comm.size() != 1) {
    std::fprintf(stderr, "plain runs on one rank\n");
    return 2;
  }
  const std::vector<ParticleRecord> bed = stiffened_bed_cached(count, comm);
  BedOptions options;
  options.threads = 1;
  options.heat = true;
  Simulation sim = paper_bed_simulation(bed, options);
  std::unique_ptr<HaloExchange> halo;
  if (!plain) {
    const Domain& domain = sim.settings().domain;
    halo = std::make_unique<HaloExchange>(
        comm, RecursiveBisection(Brick{domain.min_m, domain.max_m}, sim.particles.position_m, {}, comm.size()),
        sim.ghost_reach_m(kRadius), HaloExchange::Start::replicated);
    sim.distribute(halo.get());
  }
  sim.advance(1000);
  const std::uint64_t rebuilds_before = sim.neighbor_list().rebuild_count();
  MPI_Barrier(MPI_COMM_WORLD);
  const double start_s = MPI_Wtime();
  sim.advance(steps);
  MPI_Barrier(MPI_COMM_WORLD);
  const double wall_s = MPI_Wtime() - start_s;
  const std::size_t own = sim.own_particle_count(), ghosts = sim.particles.size() - own;
  const std::uint64_t total = comm.sum(own), all_ghosts = comm.sum(ghosts);
  const std::uint64_t rebuilds = sim.neighbor_list().rebuild_count() - rebuilds_before;
  if (comm.rank() == 0)
    std::printf("ranks %d%s  particles %llu  ghosts %llu  steps %llu  rebuilds %llu  %.3f s  %.4g particle-steps/s\n",
                comm.size(), plain ? " (plain)" : "", static_cast<unsigned long long>(total),
                static_cast<unsigned long long>(all_ghosts), static_cast<unsigned long long>(steps),
                static_cast<unsigned long long>(rebuilds), wall_s,
                static_cast<double>(total) * static_cast<double>(steps) / wall_s);
  return 0;
}

}  // namespace
}  // namespace regodem::bench

int main(int argc, char** argv) { return regodem::bench::mpi_bench_main(argc, argv, regodem::bench::run); }
