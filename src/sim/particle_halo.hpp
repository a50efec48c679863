#pragma once
// The other ranks of a run split over MPI (issue 19), as the step sees them. Each rank
// steps its own particles, those in its brick, with copies of the other ranks' particles
// near its brick (ghosts) as their contact partners. The neighbour lists are rebuilt on
// every rank at the same step, and then particles move to the rank of their brick with
// the contact history they own. The step knows nothing of MPI: src/parallel/mpi/
// implements this (HaloExchange).
#include <cstddef>
#include <cstdint>
#include <exception>
#include <span>
#include <vector>

#include "contact/bond_store.hpp"
#include "contact/neighbor_list.hpp"
#include "core/particle_store.hpp"

namespace regodem {

class ParticleHalo {
 public:
  virtual ~ParticleHalo() = default;
  /// True when any rank's `mine` is (one decision for all ranks). When a rank brings an
  /// error, every rank throws the error of the lowest such rank (Communicator::agree), so
  /// that no rank waits for one that has stopped.
  virtual bool any_rank(bool mine, const std::exception_ptr& error) = 0;
  /// The same for an error alone.
  virtual void agree(const std::exception_ptr& error) = 0;
  /// The sum over the ranks.
  virtual std::size_t sum_over_ranks(std::size_t mine) = 0;
  /// Replaces each value by its sum over the ranks, added in rank order, the same bits on
  /// every rank (the walls' forces and heat, the contact totals).
  virtual void sum_in_rank_order(std::span<double> values) = 0;
  /// The largest value over the ranks.
  virtual double max_over_ranks(double mine) = 0;
  /// At a neighbour build. `particles` holds this rank's own particles, `history` their
  /// contact history and `work` what each costs a step (its list entries), particle for
  /// particle; `bonds` the bonds with an end among them. Cuts the domain again where the
  /// work is uneven over the ranks, sends the particles outside this rank's brick to their
  /// ranks with their history and bonds and appends those that arrive, then appends copies
  /// of the other ranks' particles within reach with the history they own; `is_ghost` gets
  /// one flag per particle, and `bonds` holds those with an end among this rank's own
  /// particles, in sequence order (their local indices to be found again).
  virtual void redistribute(ParticleStore& particles, ContactHistoryByOwner& history, const std::vector<double>& work,
                            std::vector<std::uint8_t>& is_ghost, BondStore& bonds) = 0;
  /// The build sorted the particles: the one now at index i was at order[i].
  virtual void follow_sort(const std::vector<std::uint32_t>& order) = 0;
  /// Between builds, after the particles moved: each ghost's changing fields from its rank.
  virtual void refresh_ghosts(ParticleStore& particles) = 0;
  /// Between steps: replaces `particles` (this rank's own, no ghosts) and `history` (theirs)
  /// by every rank's, on every rank, in id order, with every field (forces included); the
  /// next redistribute() then keeps this rank's brick and sends nothing.
  /// `bonds` likewise become every rank's, each once, in sequence order (local indices stale).
  virtual void gather_everywhere(ParticleStore& particles, ContactHistoryByOwner& history, BondStore& bonds) = 0;
  /// Every rank's `mine` (any count on each) on every rank, one after another by rank.
  virtual std::vector<double> values_of_every_rank(std::span<const double> mine) = 0;
  /// The bitwise or of `mine` over the ranks.
  virtual std::uint32_t bits_over_ranks(std::uint32_t mine) = 0;
};

}  // namespace regodem
