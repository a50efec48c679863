// Particle-steps per second of the settled paper bed with heat (bench_settled_bed's
// particles:20000/heat:1 bed: 0.6 mm grains at the real modulus on a 700 degC plate) stepped
// over MPI ranks (issue 19): every rank reads the same stiffened bed, keeps the grains of its
// brick (Simulation::distribute, HaloExchange), steps 1,000 steps to settle in, then times
// `steps` steps between two barriers. One thread per rank. `plain` (one rank only) steps the
// same bed without the halo, for the halo's own cost.
//
// Each rank's own grains, ghosts, compute and communication time per step and what it sent
// (the Communicator's tally) are printed; with `project RATE L B` (RATE: the particle-steps
// per second of `plain` on the same machine; L, B: bench_ping_pong's latency in us and
// bandwidth in GB/s) the cost model (src/parallel/rank_cost_model.hpp) predicts this run's
// step from RATE for a check, then projects weak scaling to 16-1,024 ranks of a cluster
// (2 us, 10 GB/s), each rank with this run's grains per rank in a cubic brick.
//
//   mpirun -np 2 --bind-to core build/release/bench/bench_settled_bed_ranks [particles] [steps] [plain]
//   mpirun -np 2 --bind-to core build/release/bench/bench_settled_bed_ranks 20000 1000 project 4.2e6 0.3 5
// (REGODEM_BENCH_CACHE: where the poured and stiffened beds are kept; rank 0 writes them once.)
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../paper_bed.hpp"
#include "mpi_bench_main.hpp"
#include "parallel/mpi/halo_exchange.hpp"
#include "parallel/rank_cost_model.hpp"

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
  const bool project = argc > 3 && std::string(argv[3]) == "project";
  if (project && argc < 7) {
    if (comm.rank() == 0) std::fprintf(stderr, "project needs RATE LATENCY_US BANDWIDTH_GB_PER_S\n");
    return 2;
  }
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
        sim.ghost_skin_m(), HaloExchange::Start::replicated);
    sim.distribute(halo.get());
  }
  sim.advance(1000);
  const std::uint64_t rebuilds_before = sim.neighbor_list().rebuild_count();
  MPI_Barrier(MPI_COMM_WORLD);
  const CommunicationTally before = comm.tally();
  const double start_s = MPI_Wtime();
  sim.advance(steps);
  const double own_wall_s = MPI_Wtime() - start_s;
  const CommunicationTally after = comm.tally();
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
  if (plain) return 0;
  // Each rank: what it held, where its time went, what it sent, per step.
  const double per_step = 1.0 / static_cast<double>(steps);
  const double mine[7] = {static_cast<double>(own), static_cast<double>(ghosts),
                          (own_wall_s - (after.seconds - before.seconds)) * per_step,
                          (after.seconds - before.seconds) * per_step,
                          static_cast<double>(after.collectives - before.collectives) * per_step,
                          static_cast<double>(after.exchanges - before.exchanges) * per_step,
                          static_cast<double>(after.exchange_bytes - before.exchange_bytes) * per_step};
  std::vector<double> every(comm.rank() == 0 ? 7 * static_cast<std::size_t>(comm.size()) : 0);
  MPI_Gather(mine, 7, MPI_DOUBLE, every.data(), 7, MPI_DOUBLE, 0, MPI_COMM_WORLD);
  if (comm.rank() != 0) return 0;
  for (int r = 0; r < comm.size(); ++r) {
    const double* v = &every[7 * static_cast<std::size_t>(r)];
    std::printf("  rank %d: own %.0f ghosts %.0f  compute %.1f us/step  in MPI %.1f us/step  per step: %.2f "
                "collectives, %.2f exchanges, %.0f bytes sent\n",
                r, v[0], v[1], v[2] * 1e6, v[3] * 1e6, v[4], v[5], v[6]);
  }
  if (!project) return 0;
  const double one_rate = std::stod(argv[4]);
  NetworkModel here;
  here.latency_s = std::stod(argv[5]) * 1e-6;
  here.bandwidth_bytes_per_s = std::stod(argv[6]) * 1e9;
  const CodeTraffic traffic = code_traffic();
  const double particles = static_cast<double>(total);
  const double builds_per_step = static_cast<double>(rebuilds) * per_step;
  const double skin_m = sim.ghost_skin_m(), reach_m = 2.0 * kRadius + skin_m;  // one size: every grain's reach
  // The check: this run's step predicted from one process's rate, the bricks cut as the
  // run cut them (on the bed it read, unweighted).
  std::vector<Vec3> points;
  std::vector<double> radii;
  double low_m = bed.front().position_m.z, high_m = low_m;
  for (const ParticleRecord& r : bed) {
    points.push_back(r.position_m);
    radii.push_back(r.radius_m);
    low_m = std::min(low_m, r.position_m.z);
    high_m = std::max(high_m, r.position_m.z);
  }
  const Domain& domain = sim.settings().domain;
  const RankStepCost check =
      project_step(cut_into_bricks(Brick{domain.min_m, domain.max_m}, points, radii, {}, skin_m, comm.size()),
                   OneProcessStep{particles, particles / one_rate, builds_per_step}, here, traffic);
  std::printf("model, %d ranks here (one process %.4g particle-steps/s, latency %.3g us, %.3g GB/s): step %.1f us "
              "(compute %.1f, halo %.2f, builds %.2f, collectives %.2f), %.4g particle-steps/s; measured %.1f us, "
              "%.4g\n",
              comm.size(), one_rate, here.latency_s * 1e6, here.bandwidth_bytes_per_s / 1e9, check.step_s * 1e6,
              check.compute_s * 1e6, check.halo_s * 1e6, check.build_s * 1e6, check.collectives_s * 1e6,
              particles / check.step_s, wall_s * per_step * 1e6, particles * static_cast<double>(steps) / wall_s);
  // Weak scaling: every rank an interior cubic brick of this bed's density holding this
  // run's grains per rank, on a cluster's network.
  const NetworkModel cluster;
  // The bed fills the cup from its floor to the top grains' centres (+ a radius).
  const double per_m3 =
      particles / (std::acos(-1.0) * kCylinderRadius * kCylinderRadius * (high_m - low_m + 2.0 * kRadius));
  // The run's contacts (summed over the ranks by the step), each a history entry gathered.
  const double contacts =
      static_cast<double>(sim.contact_statistics().particle_contacts + sim.contact_statistics().wall_contacts);
  const std::size_t own_per_rank = total / static_cast<std::size_t>(comm.size());
  const auto ghost_count =
      static_cast<std::size_t>(std::llround(cubic_brick_ghosts(static_cast<double>(own_per_rank), per_m3, reach_m)));
  std::printf("weak scaling, %zu grains per rank, %zu ghosts each (cubic bricks, %.3g grains/m3, reach %.3g mm), "
              "cluster %.3g us, %.3g GB/s:\n",
              own_per_rank, ghost_count, per_m3, reach_m * 1e3, cluster.latency_s * 1e6,
              cluster.bandwidth_bytes_per_s / 1e9);
  std::printf("%6s %12s %10s %9s %9s %9s %11s %6s %10s %16s %12s\n", "ranks", "grains", "step us", "compute",
              "halo", "builds", "collectives", "eff.", "gather s", "steps/gather@10%", "gathered GB");
  for (const int ranks : {2, 16, 64, 256, 1024}) {
    const double all = static_cast<double>(own_per_rank) * ranks;
    const RankStepCost cost = project_step(uniform_shares(ranks, own_per_rank, ghost_count),
                                           OneProcessStep{all, all / one_rate, builds_per_step}, cluster, traffic);
    const double gather_s = project_gather_s(
        all,
        static_cast<double>(traffic.gathered_bytes_per_particle + 4) +
            contacts / particles * static_cast<double>(traffic.bytes_per_history_entry),
        ranks, all / one_rate, cluster);
    std::printf("%6d %12.0f %10.1f %9.1f %9.2f %9.2f %11.2f %6.2f %10.3g %16.0f %12.3g\n", ranks, all,
                cost.step_s * 1e6, cost.compute_s * 1e6, cost.halo_s * 1e6, cost.build_s * 1e6,
                cost.collectives_s * 1e6, cost.efficiency, gather_s, 9.0 * gather_s / cost.step_s,
                all * static_cast<double>(traffic.gathered_bytes_per_particle) / 1e9);  // the fields alone
  }
  return 0;
}

}  // namespace
}  // namespace regodem::bench

int main(int argc, char** argv) { return regodem::bench::mpi_bench_main(argc, argv, regodem::bench::run); }
