// Whether a launcher started this process as a rank of a job, and which (run_ranks.hpp):
// OpenMPI's mpirun, a PMI launcher (MPICH's Hydra, Slurm's srun) or PMIx set these.
#include <cstdlib>
#include <string>

#include "run_ranks.hpp"

namespace regodem::app {

bool started_as_mpi_rank() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(name) != nullptr) return true;
  return false;
}

int launcher_rank() {
  for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK"})
    if (const char* value = std::getenv(name)) {
      try {
        return std::stoi(value);
      } catch (const std::exception&) {
        return 0;
      }
    }
  return 0;
}

}  // namespace regodem::app
