#pragma once
// What a run over MPI reports as one: the particles of every rank in one store, and sums
// over particles, both taken in particle-id order on one rank so that the result is the
// same, bit for bit, on any rank count and any split of the particles (issue 19; the
// same rule as the thread-count-independent sums of the step, docs/architecture.md).
#include <span>

#include "core/particle_store.hpp"
#include "parallel/mpi/communicator.hpp"

namespace regodem {

/// Every rank's particles on rank `root`, sorted by id, with the fields that migrate (the
/// others 0): what a checkpoint or snapshot of the whole run is written from. The other
/// ranks get an empty store.
ParticleStore gather_particles(ParticleStore& local, const Communicator& comm, int root = 0);

/// The sum over all ranks of values keyed by particle id (ids[k] has values[k]), added
/// in id order on rank 0 and sent to every rank.
double sum_by_id(std::span<const ParticleId> ids, std::span<const double> values, const Communicator& comm);

}  // namespace regodem
