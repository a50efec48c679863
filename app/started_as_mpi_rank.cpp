// Whether a launcher started this process as a rank of a job, and which (run_ranks.hpp):
// OpenMPI's mpirun or a PMI launcher (MPICH's Hydra, Slurm's srun) set these.
#include <cstdlib>
#include <string>

#include "run_ranks.hpp"

namespace regodem::app {

bool started_as_mpi_rank() {
  // OpenMPI's mpirun, on any count (-np 1 included); a PMI launcher only for a job of
  // several tasks (srun sets PMI_SIZE=1 around any single program).
  if (std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr) return true;
  if (const char* size = std::getenv("PMI_SIZE")) {
    try {
      return std::stoi(size) > 1;
    } catch (const std::exception&) {
      return false;
    }
  }
  return false;
}

int launcher_rank() {
  for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMI_RANK"})
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
