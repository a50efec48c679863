// The ranks of a run under mpirun (run_ranks.hpp): MPI started and ended, one brick of the
// domain per rank, and the halo that carries particles between them (HaloExchange).
#include <mpi.h>

#include <algorithm>
#include <cstdlib>
#include <optional>

#include "core/error.hpp"
#include "parallel/mpi/communicator.hpp"
#include "parallel/mpi/halo_exchange.hpp"
#include "parallel/recursive_bisection.hpp"
#include "run_ranks.hpp"
#include "sim/simulation.hpp"

namespace regodem::app {

struct RunRanks::Impl {
  std::optional<Communicator> comm;
  std::optional<HaloExchange> halo;
};

RunRanks::RunRanks() : impl_(std::make_unique<Impl>()) {
  int provided = 0;
  // Only the thread that steps talks to the other ranks (OpenMP threads never do).
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  impl_->comm.emplace(MPI_COMM_WORLD);
}

RunRanks::~RunRanks() {
  impl_->halo.reset();
  impl_->comm.reset();
  MPI_Finalize();
}

int RunRanks::rank() const { return impl_->comm->rank(); }
int RunRanks::size() const { return impl_->comm->size(); }

void RunRanks::agree(const std::exception_ptr& error) { impl_->comm->agree(error); }

void RunRanks::abort(int exit_code) {
  MPI_Abort(MPI_COMM_WORLD, exit_code);
  std::exit(exit_code);  // MPI_Abort does not return
}

void RunRanks::take(Simulation& sim) {
  const SimulationSettings& settings = sim.settings();
  const Brick domain{settings.domain.min_m, settings.domain.max_m};
  // Every rank holds the same particles (none yet, or a checkpoint's): the first build
  // keeps each brick's, and the bricks follow the work from the next.
  impl_->halo.emplace(*impl_->comm, RecursiveBisection(domain, {}, {}, size()), sim.ghost_skin_m(),
                      HaloExchange::Start::replicated);
  sim.start_gathered(&*impl_->halo);
}

}  // namespace regodem::app
