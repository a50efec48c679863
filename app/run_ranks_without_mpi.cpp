// A regodem built without MPI (REGODEM_BUILD_MPI=OFF, run_ranks.hpp): it says so when
// started by mpirun, instead of running the whole scenario once on every rank.
#include "run_ranks.hpp"

#include <cstdlib>

#include "core/error.hpp"

namespace regodem::app {

struct RunRanks::Impl {};

RunRanks::RunRanks() {
  throw InputError(
      "this regodem was built without MPI (REGODEM_BUILD_MPI=OFF), so it cannot run over mpirun's ranks: build it "
      "with MPI, or run it without mpirun");
}
RunRanks::~RunRanks() = default;
int RunRanks::rank() const { return 0; }
int RunRanks::size() const { return 1; }
void RunRanks::agree(const std::exception_ptr& error) {
  if (error) std::rethrow_exception(error);
}
void RunRanks::abort(int exit_code) { std::exit(exit_code); }
void RunRanks::take(Simulation&) {}

}  // namespace regodem::app
