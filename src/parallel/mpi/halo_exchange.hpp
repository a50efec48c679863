#pragma once
// The ParticleHalo of a run over MPI ranks (issue 19): at each neighbour build, the
// particles that left this rank's brick go to the rank of theirs with the contact history
// they own, and each rank receives copies (ghosts) of the other ranks' particles within
// the reach of its brick, with their history; between builds the same ghosts are brought
// up to date every step (positions, velocities, spins, temperatures), in the order of
// the build.
#include <cstdint>
#include <vector>

#include "parallel/mpi/communicator.hpp"
#include "parallel/recursive_bisection.hpp"
#include "sim/particle_halo.hpp"

namespace regodem {

class HaloExchange final : public ParticleHalo {
 public:
  /// How the particles are spread at the first build: each rank holds its own (a rank may
  /// hold any, they migrate), or every rank holds all of them, the same (each then keeps
  /// those of its brick with the contact history they own, and nothing is sent).
  enum class Start { spread, replicated };
  /// skin_m: Simulation::ghost_skin_m, the most a pair's skin adds to its two radii (the
  /// ghosts each brick wants: GhostReach). `comm` must outlive it.
  /// The bricks must tile the run's domain. At a build where the busiest rank has more
  /// than (1 + imbalance) x the mean work, the domain is cut again by everyone's particles
  /// weighted by their work (the same bricks on every rank: the cuts do not depend on the
  /// points' order); the bricks change where each particle is stepped, not its result.
  HaloExchange(const Communicator& comm, RecursiveBisection bricks, double skin_m, Start start = Start::spread,
               double imbalance = 0.1);

  bool any_rank(bool mine, const std::exception_ptr& error) override { return comm_.any_rank(mine, error); }
  void agree(const std::exception_ptr& error) override { comm_.agree(error); }
  std::size_t sum_over_ranks(std::size_t mine) override;
  void sum_in_rank_order(std::span<double> values) override { comm_.sum_in_rank_order(values); }
  double max_over_ranks(double mine) override { return comm_.max(mine); }
  void redistribute(ParticleStore& particles, ContactHistoryByOwner& history, const std::vector<double>& work,
                    std::vector<std::uint8_t>& is_ghost, BondStore& bonds) override;
  void follow_sort(const std::vector<std::uint32_t>& order) override;
  void refresh_ghosts(ParticleStore& particles) override;
  void gather_everywhere(ParticleStore& particles, ContactHistoryByOwner& history, BondStore& bonds) override;
  std::vector<double> values_of_every_rank(std::span<const double> mine) override;
  std::uint32_t bits_over_ranks(std::uint32_t mine) override { return comm_.bits_or(mine); }

  const RecursiveBisection& bricks() const { return bricks_; }
  /// Particles that left this rank since the start, the contact histories they took
  /// with them, and this rank's ghosts now.
  std::uint64_t migrated_count() const { return migrated_; }
  std::uint64_t migrated_contact_count() const { return migrated_contacts_; }
  std::size_t ghost_count() const;
  /// How often the domain was cut again.
  std::uint64_t rebalance_count() const { return rebalances_; }

 private:
  const Communicator& comm_;
  /// Cuts the domain again when the work is uneven (see the constructor): from every
  /// rank's particles and work, or, where every rank holds them all, from its own.
  void rebalance(const ParticleStore& particles, const std::vector<double>& work);
  void rebalance_replicated(const ParticleStore& particles, const std::vector<double>& work);
  /// Whether the busiest rank's work is over (1 + imbalance) x the mean.
  bool uneven(double busiest, double total) const;

  RecursiveBisection bricks_;
  Brick domain_;  // what the bricks tile
  double skin_m_;
  double imbalance_;
  std::uint64_t rebalances_ = 0;
  // Since the last build, by rank: the indices of this rank's particles it sent that rank
  // as ghosts, and of the ghosts that rank sent here, each in the order sent.
  std::vector<std::vector<std::uint32_t>> sent_to_;
  std::vector<std::vector<std::uint32_t>> received_from_;
  std::uint64_t migrated_ = 0, migrated_contacts_ = 0;
  bool replicated_ = false;  // until the first build
};

}  // namespace regodem
