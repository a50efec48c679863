#include "parallel/mpi/gather_by_id.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <numeric>

#include "core/error.hpp"
#include "parallel/particle_transfer.hpp"

namespace regodem {

ParticleStore gather_particles(ParticleStore& local, const Communicator& comm, int root) {
  std::vector<std::uint32_t> all(local.size());
  std::iota(all.begin(), all.end(), 0u);
  std::vector<std::byte> mine;
  pack_particles(local, all, ParticleTransfer::migration, mine);
  ParticleStore whole;
  for (const std::vector<std::byte>& message : comm.gather(mine, root))
    if (!message.empty()) unpack_particles(message, ParticleTransfer::migration, whole);
  std::vector<std::uint32_t> by_id(whole.size());
  std::iota(by_id.begin(), by_id.end(), 0u);
  std::sort(by_id.begin(), by_id.end(), [&](std::uint32_t a, std::uint32_t b) { return whole.id[a] < whole.id[b]; });
  whole.permute(by_id);
  return whole;
}

double sum_by_id(std::span<const ParticleId> ids, std::span<const double> values, const Communicator& comm) {
  if (ids.size() != values.size())
    throw SimulationError(fmt::format("{} ids for {} values to sum", ids.size(), values.size()));
  // A value and its id, without padding of unknown bytes.
  struct Pair {
    ParticleId id;
    std::uint32_t zero = 0;
    double value;
  };
  static_assert(sizeof(Pair) == 16);
  std::vector<std::byte> mine(ids.size() * sizeof(Pair));
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const Pair pair{ids[k], 0, values[k]};
    std::memcpy(mine.data() + k * sizeof(Pair), &pair, sizeof(Pair));
  }
  double total = 0.0;
  const std::vector<std::vector<std::byte>> gathered = comm.gather(mine, 0);
  if (comm.rank() == 0) {
    std::vector<Pair> pairs;
    for (const std::vector<std::byte>& message : gathered) {
      const std::size_t at = pairs.size();
      pairs.resize(at + message.size() / sizeof(Pair));
      std::memcpy(pairs.data() + at, message.data(), message.size());
    }
    // By id (then value, should an id come twice).
    std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) {
      return a.id != b.id ? a.id < b.id : a.value < b.value;
    });
    for (const Pair& pair : pairs) total += pair.value;
  }
  return comm.broadcast(total, 0);
}

}  // namespace regodem
