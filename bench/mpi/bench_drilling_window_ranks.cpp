// Particle-steps per second of the real drilling workload over MPI ranks (issue 19): the
// window of bench_drilling_window (the reduced sieve model with the drill 25 mm down: 11,600
// grains with ice bonds, the auger turning and feeding, the sieve, heat on), restored on
// every rank and split over the ranks (Simulation::distribute, HaloExchange, bricks cut by
// the grains), then `steps` steps timed between two barriers. One thread per rank. `plain`
// (one rank only) steps it without the halo. Rank 0 prints the rate, the window's neighbour
// builds, migrations and rebalancings, and a hash of every grain's state after the window
// (gathered in id order: the same on any rank count with the halo).
//
//   bench/make_drilling_window.sh build/release/regodem /work/bench-cache   # once
//   mpirun -np 2 --bind-to core build/release/bench/bench_drilling_window_ranks [steps] [plain]
#include <mpi.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>

#include "../drilling_window.hpp"
#include "../state_hash.hpp"
#include "io/checkpoint_file.hpp"
#include "mpi_bench_main.hpp"
#include "parallel/mpi/halo_exchange.hpp"
#include "scenario/scenario_builder.hpp"
#include "scenario/scenario_reader.hpp"
#include "sim/simulation.hpp"

namespace regodem::bench {
namespace {

int run(int argc, char** argv) {
  const Communicator comm;
  const std::uint64_t steps = argc > 1 ? std::stoull(argv[1]) : kWindowSteps;
  const bool plain = argc > 2 && std::string(argv[2]) == "plain";
  if (plain && comm.size() != 1) {
    std::fprintf(stderr, "plain runs on one rank\n");
    return 2;
  }
  const std::string checkpoint_path = window_checkpoint_path();
  if (checkpoint_path.empty() || !std::filesystem::is_regular_file(checkpoint_path)) {
    std::fprintf(stderr, "no drilling window: run bench/make_drilling_window.sh (or set REGODEM_DRILLING_WINDOW)\n");
    return 2;
  }
  const ScenarioSpec spec =
      read_scenario_file(window_scenario_path(REGODEM_SOURCE_DIR), {"initial_state.checkpoint=" + checkpoint_path});
  PreparedRun prepared = PreparedRun::build(spec, 1);
  Simulation& sim = prepared.simulation();
  sim.restore_state(read_checkpoint_file(checkpoint_path));
  std::unique_ptr<HaloExchange> halo;
  if (!plain) {
    const SimulationSettings& settings = sim.settings();
    halo = std::make_unique<HaloExchange>(
        comm,
        RecursiveBisection(Brick{settings.domain.min_m, settings.domain.max_m}, sim.particles.position_m, {},
                           comm.size()),
        sim.ghost_skin_m(), HaloExchange::Start::replicated);
    sim.distribute(halo.get());
  }
  const std::uint64_t rebuilds_before = sim.neighbor_list().rebuild_count();
  MPI_Barrier(MPI_COMM_WORLD);
  const double start_s = MPI_Wtime();
  sim.advance(steps);
  MPI_Barrier(MPI_COMM_WORLD);
  const double wall_s = MPI_Wtime() - start_s;
  const std::uint64_t rebuilds = sim.neighbor_list().rebuild_count() - rebuilds_before;
  const std::uint64_t total = comm.sum(sim.own_particle_count());
  const std::uint64_t migrated = halo ? comm.sum(halo->migrated_count()) : 0;
  const std::uint64_t rebalances = halo ? halo->rebalance_count() : 0;
  sim.gather_everywhere();
  const std::uint32_t hash = state_hash(sim.particles);
  if (comm.rank() == 0)
    std::printf("ranks %d%s  particles %llu  bonds %zu  steps %llu  rebuilds %llu  migrated %llu  rebalanced %llu  "
                "%.3f s  %.4g particle-steps/s  state %08x\n",
                comm.size(), plain ? " (plain)" : "", static_cast<unsigned long long>(total), sim.bonds().size(),
                static_cast<unsigned long long>(steps), static_cast<unsigned long long>(rebuilds),
                static_cast<unsigned long long>(migrated), static_cast<unsigned long long>(rebalances), wall_s,
                static_cast<double>(total) * static_cast<double>(steps) / wall_s, hash);
  return 0;
}

}  // namespace
}  // namespace regodem::bench

int main(int argc, char** argv) { return regodem::bench::mpi_bench_main(argc, argv, regodem::bench::run); }
