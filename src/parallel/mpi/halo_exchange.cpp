#include "parallel/mpi/halo_exchange.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>

#include "core/error.hpp"
#include "parallel/mpi/particle_exchange.hpp"
#include "parallel/bond_transfer.hpp"
#include "parallel/particle_transfer.hpp"

namespace regodem {
namespace {

// A message: the particles (pack_particles), then each one's contact count and contacts,
// then (migration, a gather) the bonds given.
std::vector<std::byte> pack_with_history(ParticleStore& particles, const ContactHistoryByOwner& history,
                                         const std::vector<std::uint32_t>& indices, ParticleTransfer kind,
                                         const BondStore* bonds = nullptr,
                                         const std::vector<std::uint32_t>& bond_indices = {}) {
  std::vector<std::byte> bytes;
  pack_particles(particles, indices, kind, bytes);
  const auto append = [&](const void* data, std::size_t size) {
    const std::size_t at = bytes.size();
    bytes.resize(at + size);
    if (size > 0) std::memcpy(bytes.data() + at, data, size);
  };
  for (const std::uint32_t p : indices) {
    const std::uint32_t count = history.begin[p + 1] - history.begin[p];
    append(&count, sizeof count);
    append(history.contacts.data() + history.begin[p], count * sizeof(SavedContact));
  }
  if (bonds) pack_bonds(*bonds, bond_indices, bytes);
  return bytes;
}

// Appends each message's particles to `particles` and their contacts to `history`; returns
// the index range each message's particles took.
std::vector<std::pair<std::uint32_t, std::uint32_t>> unpack_with_history(
    const std::vector<std::vector<std::byte>>& messages, ParticleTransfer kind, ParticleStore& particles,
    ContactHistoryByOwner& history, BondStore* bonds = nullptr) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> ranges(messages.size());
  for (std::size_t r = 0; r < messages.size(); ++r) {
    const std::vector<std::byte>& message = messages[r];
    const auto first = static_cast<std::uint32_t>(particles.size());
    ranges[r] = {first, first};
    if (message.empty()) continue;
    std::size_t at = unpack_particles(message, kind, particles);
    const auto take = [&](void* data, std::size_t size) {
      if (at + size > message.size())
        throw SimulationError(fmt::format("a particle message of {} bytes ends early in its contact history",
                                          message.size()));
      if (size > 0) std::memcpy(data, message.data() + at, size);
      at += size;
    };
    for (std::size_t p = first; p < particles.size(); ++p) {
      std::uint32_t count = 0;
      take(&count, sizeof count);
      const std::size_t from = history.contacts.size();
      history.contacts.resize(from + count);
      take(history.contacts.data() + from, count * sizeof(SavedContact));
      history.begin.push_back(static_cast<std::uint32_t>(history.contacts.size()));
    }
    if (bonds) at += unpack_bonds(std::span<const std::byte>(message).subspan(at), *bonds);
    if (at != message.size())
      throw SimulationError(fmt::format("a particle message of {} bytes held {} more", message.size(),
                                        message.size() - at));
    ranges[r].second = static_cast<std::uint32_t>(particles.size());
  }
  return ranges;
}

// Keeps the history of the owners not flagged.
void remove_history(ContactHistoryByOwner& history, const std::vector<char>& removed) {
  ContactHistoryByOwner kept;
  kept.contacts.reserve(history.contacts.size());
  for (std::size_t p = 0; p < history.owners(); ++p) {
    if (removed[p]) continue;
    kept.contacts.insert(kept.contacts.end(), history.contacts.begin() + history.begin[p],
                         history.contacts.begin() + history.begin[p + 1]);
    kept.begin.push_back(static_cast<std::uint32_t>(kept.contacts.size()));
  }
  history = std::move(kept);
}

// Keeps the bonds with an end among the first `own` particles, once each, in sequence order.
void keep_bonds_of_own(BondStore& bonds, const ParticleStore& particles, std::size_t own) {
  if (bonds.empty()) return;
  std::vector<ParticleId> ids(particles.id.begin(), particles.id.begin() + static_cast<std::ptrdiff_t>(own));
  std::sort(ids.begin(), ids.end());
  std::vector<char> keep(bonds.size(), 0);
  for (std::size_t b = 0; b < bonds.size(); ++b)
    keep[b] = std::binary_search(ids.begin(), ids.end(), bonds.id_i[b]) ||
              std::binary_search(ids.begin(), ids.end(), bonds.id_j[b]);
  bonds.keep_in_sequence_order(keep);
}

// For each rank, the bonds of the particles leaving for it (a bond whose two ends leave
// for the same rank once).
std::vector<std::vector<std::uint32_t>> bonds_leaving(const BondStore& bonds, const ParticleStore& particles,
                                                      const std::vector<std::vector<std::uint32_t>>& to_rank) {
  std::vector<std::vector<std::uint32_t>> by_rank(to_rank.size());
  if (bonds.empty()) return by_rank;
  std::vector<std::pair<ParticleId, int>> leaving;
  for (std::size_t r = 0; r < to_rank.size(); ++r)
    for (const std::uint32_t p : to_rank[r]) leaving.emplace_back(particles.id[p], static_cast<int>(r));
  std::sort(leaving.begin(), leaving.end());
  const auto rank_of = [&](ParticleId id) {
    const auto it = std::lower_bound(leaving.begin(), leaving.end(), std::pair<ParticleId, int>{id, -1});
    return it != leaving.end() && it->first == id ? it->second : -1;
  };
  for (std::size_t b = 0; b < bonds.size(); ++b) {
    const int ri = rank_of(bonds.id_i[b]), rj = rank_of(bonds.id_j[b]);
    if (ri >= 0) by_rank[static_cast<std::size_t>(ri)].push_back(static_cast<std::uint32_t>(b));
    if (rj >= 0 && rj != ri) by_rank[static_cast<std::size_t>(rj)].push_back(static_cast<std::uint32_t>(b));
  }
  return by_rank;
}

}  // namespace

HaloExchange::HaloExchange(const Communicator& comm, RecursiveBisection bricks, double skin_m, Start start,
                           double imbalance)
    : comm_(comm),
      bricks_(std::move(bricks)),
      domain_(bricks_.brick(0)),
      skin_m_(skin_m),
      imbalance_(imbalance),
      replicated_(start == Start::replicated) {
  if (bricks_.ranks() != comm_.size())
    throw SimulationError(fmt::format("{} bricks for {} ranks", bricks_.ranks(), comm_.size()));
  if (!(skin_m_ >= 0.0)) throw SimulationError(fmt::format("a ghost skin of {} m", skin_m_));
  if (!(imbalance_ >= 0.0)) throw SimulationError(fmt::format("an allowed imbalance of {}", imbalance_));
  for (int r = 1; r < bricks_.ranks(); ++r) {
    const Brick& b = bricks_.brick(r);
    domain_.lo_m = {std::min(domain_.lo_m.x, b.lo_m.x), std::min(domain_.lo_m.y, b.lo_m.y),
                    std::min(domain_.lo_m.z, b.lo_m.z)};
    domain_.hi_m = {std::max(domain_.hi_m.x, b.hi_m.x), std::max(domain_.hi_m.y, b.hi_m.y),
                    std::max(domain_.hi_m.z, b.hi_m.z)};
  }
}

bool HaloExchange::uneven(double busiest, double total) const {
  return busiest > (1.0 + imbalance_) * total / comm_.size();
}

void HaloExchange::rebalance_replicated(const ParticleStore& particles, const std::vector<double>& work) {
  if (comm_.size() == 1) return;
  // Every rank holds the same particles with the same work (one process's lists, after a
  // gather or at the start): each weighs the bricks and cuts them alone, alike, unsent.
  std::vector<double> per_rank(static_cast<std::size_t>(comm_.size()), 0.0);
  double total = 0.0;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    per_rank[static_cast<std::size_t>(bricks_.rank_of(particles.position_m[i]))] += work[i];
    total += work[i];
  }
  if (!uneven(*std::max_element(per_rank.begin(), per_rank.end()), total)) return;
  bricks_ = RecursiveBisection(domain_, std::span<const Vec3>(particles.position_m.data(), particles.size()), work,
                               comm_.size());
  ++rebalances_;
}

void HaloExchange::rebalance(const ParticleStore& particles, const std::vector<double>& work) {
  if (comm_.size() == 1) return;
  double mine = 0.0;
  for (const double w : work) mine += w;
  double total = mine;
  comm_.sum_in_rank_order(std::span<double>(&total, 1));
  const double busiest = comm_.max(mine);
  if (!uneven(busiest, total)) return;
  // Every rank's particles and work on every rank, by rank: the same cuts everywhere.
  std::vector<std::byte> bytes(particles.size() * (sizeof(Vec3) + sizeof(double)));
  std::memcpy(bytes.data(), particles.position_m.data(), particles.size() * sizeof(Vec3));
  std::memcpy(bytes.data() + particles.size() * sizeof(Vec3), work.data(), work.size() * sizeof(double));
  std::vector<Vec3> points;
  std::vector<double> weights;
  for (const std::vector<std::byte>& from : comm_.gather_to_all(bytes)) {
    const std::size_t count = from.size() / (sizeof(Vec3) + sizeof(double));
    const std::size_t first = points.size();
    points.resize(first + count);
    weights.resize(first + count);
    std::memcpy(points.data() + first, from.data(), count * sizeof(Vec3));
    std::memcpy(weights.data() + first, from.data() + count * sizeof(Vec3), count * sizeof(double));
  }
  bricks_ = RecursiveBisection(domain_, points, weights, comm_.size());
  ++rebalances_;
}

std::size_t HaloExchange::sum_over_ranks(std::size_t mine) { return comm_.sum(mine); }

std::size_t HaloExchange::ghost_count() const {
  std::size_t count = 0;
  for (const std::vector<std::uint32_t>& from : received_from_) count += from.size();
  return count;
}

void HaloExchange::redistribute(ParticleStore& particles, ContactHistoryByOwner& history,
                                const std::vector<double>& work, std::vector<std::uint8_t>& is_ghost,
                                BondStore& bonds) {
  const auto ranks = static_cast<std::size_t>(comm_.size());
  const int me = comm_.rank();
  if (history.owners() != particles.size() || work.size() != particles.size())
    throw SimulationError(fmt::format("{} particles with {} contact histories and {} costs", particles.size(),
                                      history.owners(), work.size()));
  if (replicated_)
    rebalance_replicated(particles, work);
  else
    rebalance(particles, work);

  // Each particle to the rank of its brick, with the contact history it owns.
  const std::vector<std::vector<std::uint32_t>> to_rank = migration_lists(particles, bricks_, me);
  std::vector<char> leaves(particles.size(), 0);
  for (const std::vector<std::uint32_t>& list : to_rank)
    for (const std::uint32_t p : list) {
      leaves[p] = 1;
      ++migrated_;
      migrated_contacts_ += history.begin[p + 1] - history.begin[p];
    }
  std::vector<std::vector<std::byte>> messages(ranks);
  if (replicated_) {  // the other ranks hold the same particles: keep this brick's
    migrated_ = migrated_contacts_ = 0;
    particles.remove_if(leaves);
    remove_history(history, leaves);
    replicated_ = false;
  } else {
    // A bond goes with each of its ends that moves; the ranks of its ends keep it.
    const std::vector<std::vector<std::uint32_t>> bonds_to = bonds_leaving(bonds, particles, to_rank);
    for (std::size_t r = 0; r < ranks; ++r)
      if (!to_rank[r].empty())
        messages[r] = pack_with_history(particles, history, to_rank[r], ParticleTransfer::migration, &bonds, bonds_to[r]);
    particles.remove_if(leaves);
    remove_history(history, leaves);
    unpack_with_history(comm_.exchange(messages), ParticleTransfer::migration, particles, history, &bonds);
  }
  keep_bonds_of_own(bonds, particles, particles.size());
  const std::size_t own = particles.size();
  // A particle outside every brick (the bricks do not tile the domain) would miss partners;
  // the error stops every rank.
  std::exception_ptr outside;
  for (std::size_t p = 0; p < own && !outside; ++p)
    if (bricks_.brick(me).distance_m(particles.position_m[p]) > 0.0)
      outside = std::make_exception_ptr(SimulationError(fmt::format(
          "particle {} at ({:.6g}, {:.6g}, {:.6g}) m lies outside every rank's brick: the bricks must tile the run's "
          "domain",
          particles.id[p], particles.position_m[p].x, particles.position_m[p].y, particles.position_m[p].z)));
  comm_.agree(outside);

  // Ghosts: copies of each particle another rank's brick wants (GhostReach: its own
  // radius, the largest of one of that brick's size bands and the skin, from the band's centres).
  sent_to_ = ghost_lists(particles, own, bricks_, gathered_ghost_reach(particles, own, skin_m_, comm_), me);
  for (std::size_t r = 0; r < ranks; ++r)
    messages[r] = sent_to_[r].empty() ? std::vector<std::byte>{}
                                      : pack_with_history(particles, history, sent_to_[r], ParticleTransfer::ghost);
  const auto ranges = unpack_with_history(comm_.exchange(messages), ParticleTransfer::ghost, particles, history);
  received_from_.assign(ranks, {});
  for (std::size_t r = 0; r < ranks; ++r)
    for (std::uint32_t i = ranges[r].first; i < ranges[r].second; ++i) received_from_[r].push_back(i);
  is_ghost.assign(particles.size(), 0);
  std::fill(is_ghost.begin() + static_cast<std::ptrdiff_t>(own), is_ghost.end(), std::uint8_t{1});
}

void HaloExchange::follow_sort(const std::vector<std::uint32_t>& order) {
  std::vector<std::uint32_t> new_of_old(order.size());
  for (std::size_t i = 0; i < order.size(); ++i) new_of_old[order[i]] = static_cast<std::uint32_t>(i);
  for (auto* lists : {&sent_to_, &received_from_})
    for (std::vector<std::uint32_t>& list : *lists)
      for (std::uint32_t& i : list) i = new_of_old[i];
}

void HaloExchange::refresh_ghosts(ParticleStore& particles) {
  const auto ranks = static_cast<std::size_t>(comm_.size());
  std::vector<std::vector<std::byte>> messages(ranks);
  for (std::size_t r = 0; r < ranks; ++r)
    if (!sent_to_[r].empty()) pack_particles(particles, sent_to_[r], ParticleTransfer::ghost_refresh, messages[r]);
  const std::vector<std::vector<std::byte>> received = comm_.exchange(messages);
  for (std::size_t r = 0; r < ranks; ++r) {
    if (received_from_[r].empty() && received[r].empty()) continue;
    const std::size_t used = unpack_particles_at(received[r], ParticleTransfer::ghost_refresh, particles, received_from_[r]);
    if (used != received[r].size())
      throw SimulationError(fmt::format("a ghost update of {} bytes held {} more", received[r].size(),
                                        received[r].size() - used));
  }
}

void HaloExchange::gather_everywhere(ParticleStore& particles, ContactHistoryByOwner& history, BondStore& bonds) {
  if (history.owners() != particles.size())
    throw SimulationError(
        fmt::format("{} particles with {} contact histories to gather", particles.size(), history.owners()));
  std::vector<std::uint32_t> every(particles.size());
  for (std::size_t i = 0; i < every.size(); ++i) every[i] = static_cast<std::uint32_t>(i);
  std::vector<std::uint32_t> every_bond(bonds.size());
  for (std::size_t b = 0; b < every_bond.size(); ++b) every_bond[b] = static_cast<std::uint32_t>(b);
  const std::vector<std::byte> mine =
      pack_with_history(particles, history, every, ParticleTransfer::whole, &bonds, every_bond);
  ParticleStore all;
  ContactHistoryByOwner all_history;
  BondStore all_bonds;
  unpack_with_history(comm_.gather_to_all(mine), ParticleTransfer::whole, all, all_history, &all_bonds);
  // A bond between two ranks' particles came from both: once each, in the run's order.
  all_bonds.keep_in_sequence_order(std::vector<char>(all_bonds.size(), 1));
  bonds = std::move(all_bonds);
  all.set_next_id(particles.next_id());  // every rank's: insertion takes the same ids everywhere
  // In id order: the same store on every rank, whatever the split.
  std::vector<std::uint32_t> order(all.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<std::uint32_t>(i);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return all.id[a] < all.id[b]; });
  all.permute(order);
  history = ContactHistoryByOwner{};
  history.contacts.reserve(all_history.contacts.size());
  for (const std::uint32_t p : order) {
    history.contacts.insert(history.contacts.end(), all_history.contacts.begin() + all_history.begin[p],
                            all_history.contacts.begin() + all_history.begin[p + 1]);
    history.begin.push_back(static_cast<std::uint32_t>(history.contacts.size()));
  }
  particles = std::move(all);
  sent_to_.assign(static_cast<std::size_t>(comm_.size()), {});
  received_from_.assign(static_cast<std::size_t>(comm_.size()), {});
  replicated_ = true;
}

std::vector<double> HaloExchange::values_of_every_rank(std::span<const double> mine) {
  std::vector<std::byte> bytes(mine.size_bytes());
  if (!mine.empty()) std::memcpy(bytes.data(), mine.data(), mine.size_bytes());
  std::vector<double> all;
  for (const std::vector<std::byte>& from : comm_.gather_to_all(bytes)) {
    const std::size_t first = all.size();
    all.resize(first + from.size() / sizeof(double));
    if (!from.empty()) std::memcpy(all.data() + first, from.data(), from.size());
  }
  return all;
}

}  // namespace regodem
