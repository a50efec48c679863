#include "parallel/mpi/particle_exchange.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "core/error.hpp"
#include "parallel/particle_transfer.hpp"

namespace regodem {
namespace {

// For each rank, the particles its list names.
std::vector<std::vector<std::byte>> pack_lists(ParticleStore& from, const std::vector<std::vector<std::uint32_t>>& to_rank,
                                               ParticleTransfer kind) {
  std::vector<std::vector<std::byte>> messages(to_rank.size());
  for (std::size_t r = 0; r < to_rank.size(); ++r)
    if (!to_rank[r].empty()) pack_particles(from, to_rank[r], kind, messages[r]);
  return messages;
}

// Appends the particles of each rank's message to `into`, by sending rank.
void unpack_messages(const std::vector<std::vector<std::byte>>& received, ParticleTransfer kind, ParticleStore& into) {
  for (const std::vector<std::byte>& message : received) {
    if (message.empty()) continue;
    const std::size_t used = unpack_particles(message, kind, into);
    if (used != message.size())
      throw SimulationError(fmt::format("a particle message of {} bytes held {} more", message.size(),
                                        message.size() - used));
  }
}

}  // namespace

std::vector<std::vector<std::uint32_t>> migration_lists(const ParticleStore& local, const RecursiveBisection& bricks,
                                                        int this_rank) {
  std::vector<std::vector<std::uint32_t>> to_rank(static_cast<std::size_t>(bricks.ranks()));
  for (std::size_t p = 0; p < local.size(); ++p) {
    const int owner = bricks.rank_of(local.position_m[p]);
    if (owner != this_rank) to_rank[static_cast<std::size_t>(owner)].push_back(static_cast<std::uint32_t>(p));
  }
  return to_rank;
}

std::vector<std::vector<std::uint32_t>> ghost_lists(const ParticleStore& local, std::size_t count,
                                                    const RecursiveBisection& bricks, const GhostReach& reach,
                                                    int this_rank) {
  if (reach.bricks() != static_cast<std::size_t>(bricks.ranks()))
    throw SimulationError(fmt::format("a ghost reach for {} bricks, of {}", reach.bricks(), bricks.ranks()));
  std::vector<std::vector<std::uint32_t>> to_rank(static_cast<std::size_t>(bricks.ranks()));
  // Only the bricks near this rank's particles are asked: O(count x neighbours), not
  // O(count x ranks); the lists are the same.
  const CentresBox mine = centres_box(std::span<const Vec3>(local.position_m.data(), count),
                                      std::span<const double>(local.radius_m.data(), count));
  const std::vector<int> near = count > 0 ? reach.bricks_near(mine.box, mine.largest_radius_m, this_rank)
                                          : std::vector<int>{};
  for (std::size_t p = 0; p < count; ++p)
    for (const int r : near)
      if (reach.wanted(r, local.position_m[p], local.radius_m[p]))
        to_rank[static_cast<std::size_t>(r)].push_back(static_cast<std::uint32_t>(p));
  return to_rank;
}

GhostReach gathered_ghost_reach(const ParticleStore& local, std::size_t count, double skin_m, const Communicator& comm) {
  const auto mine = radius_bands(std::span<const Vec3>(local.position_m.data(), count),
                                 std::span<const double>(local.radius_m.data(), count));
  return GhostReach{skin_m, bands_of_values(comm.equal_counts_of_every_rank(band_values(mine)))};
}

std::size_t migrate_particles(ParticleStore& local, const RecursiveBisection& bricks, const Communicator& comm) {
  if (bricks.ranks() != comm.size())
    throw SimulationError(fmt::format("{} bricks for {} ranks", bricks.ranks(), comm.size()));
  const std::vector<std::vector<std::uint32_t>> to_rank = migration_lists(local, bricks, comm.rank());
  std::vector<char> leaves(local.size(), 0);
  std::size_t left = 0;
  for (const std::vector<std::uint32_t>& list : to_rank)
    for (const std::uint32_t p : list) leaves[p] = 1, ++left;
  const std::vector<std::vector<std::byte>> messages = pack_lists(local, to_rank, ParticleTransfer::migration);
  local.remove_if(leaves);
  unpack_messages(comm.exchange(messages), ParticleTransfer::migration, local);
  return left;
}

void exchange_ghosts(ParticleStore& local, const RecursiveBisection& bricks, double skin_m, const Communicator& comm,
                     ParticleStore& ghosts) {
  if (bricks.ranks() != comm.size())
    throw SimulationError(fmt::format("{} bricks for {} ranks", bricks.ranks(), comm.size()));
  const std::vector<std::vector<std::uint32_t>> to_rank =
      ghost_lists(local, local.size(), bricks, gathered_ghost_reach(local, local.size(), skin_m, comm), comm.rank());
  ghosts = ParticleStore{};
  unpack_messages(comm.exchange(pack_lists(local, to_rank, ParticleTransfer::ghost)), ParticleTransfer::ghost, ghosts);
}

}  // namespace regodem
