#pragma once
// Particles between the ranks' bricks (issue 19): migration, which hands each particle
// to the rank whose brick holds it, and ghosts, the copies of other ranks' particles near
// a rank's brick that its contacts read. Received particles are appended by sending rank,
// each rank's in its own order, so the result depends only on the ranks' stores.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/particle_store.hpp"
#include "parallel/ghost_reach.hpp"
#include "parallel/mpi/communicator.hpp"
#include "parallel/recursive_bisection.hpp"

namespace regodem {

/// For each rank, the indices of the particles of `local` whose positions lie in that
/// rank's brick; this rank's own list stays empty (they stay).
std::vector<std::vector<std::uint32_t>> migration_lists(const ParticleStore& local, const RecursiveBisection& bricks,
                                                        int this_rank);

/// For each other rank, the indices of the first `count` particles of `local` that rank
/// wants as ghosts (GhostReach); this rank's own list stays empty.
std::vector<std::vector<std::uint32_t>> ghost_lists(const ParticleStore& local, std::size_t count,
                                                    const RecursiveBisection& bricks, const GhostReach& reach,
                                                    int this_rank);

/// The GhostReach of a run's bricks for a pair skin of `skin_m` (2 h_max), each rank's
/// radius bands of the first `count` particles of `local` (its own) gathered from every
/// rank: one collective.
GhostReach gathered_ghost_reach(const ParticleStore& local, std::size_t count, double skin_m, const Communicator& comm);

/// Sends every particle of `local` whose position lies in another rank's brick to that
/// rank, with the fields that migrate (those the next pass computes start at 0), and
/// appends those sent here. Returns how many left this rank.
std::size_t migrate_particles(ParticleStore& local, const RecursiveBisection& bricks, const Communicator& comm);

/// Replaces `ghosts` by copies (the fields ghosts need) of the other ranks' particles
/// that this rank's brick wants (gathered_ghost_reach for a pair skin of skin_m).
void exchange_ghosts(ParticleStore& local, const RecursiveBisection& bricks, double skin_m, const Communicator& comm,
                     ParticleStore& ghosts);

}  // namespace regodem
