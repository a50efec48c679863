#pragma once
// What a step would cost on N ranks (issue 19; `regodem estimate --ranks N`, the weak-
// scaling projection of docs/benchmarks.md), from what one process measured and from
// what the code sends. The bed is cut as a run cuts it (RecursiveBisection, weighted by
// work); each brick's own particles and ghosts (the other bricks' particles within the
// ghost reach, as HaloExchange sends them: GhostReach) give its compute; its ghosts' bytes and the
// ranks it hears from give its messages; the collectives every step takes give the
// latency that grows with log2 N. A step lasts as long as its slowest rank, since every
// step ends in a collective.
//
// The network is the latency-bandwidth (Hockney) model: a message or one round of a
// collective waits `latency_s`, and a rank moves bytes at `bandwidth_bytes_per_s`. A
// collective over N ranks takes ceil(log2 N) rounds (recursive doubling, tree
// reduce/broadcast).
#include <cstddef>
#include <span>
#include <vector>

#include "core/vec3.hpp"
#include "parallel/recursive_bisection.hpp"

namespace regodem {

struct NetworkModel {
  double latency_s = 2e-6;                // a cluster's InfiniBand, MPI point to point
  double bandwidth_bytes_per_s = 1.0e10;  // per rank
};

/// What the code sends besides the ghosts' bytes, per step and per neighbour-list build
/// (tests/mpi/test_distributed_step.cpp, AStepSendsWhatTheCostModelCounts, holds a run's
/// Communicator tally to these, without bonds and lost grains).
struct CodeTraffic {
  int collectives_per_step = 0;   // latency-bound rounds over all ranks (agreements, sums)
  int exchanges_per_step = 0;     // ghost refreshes: an all-to-all of counts, then one message per partner
  int collectives_per_build = 0;  // besides a step's
  int exchanges_per_build = 0;    // migration and the new ghosts, in place of the step's refresh
  std::size_t refresh_bytes_per_ghost = 0;  // positions, velocities, spins, temperatures, conductivities
  std::size_t new_ghost_bytes = 0;          // a ghost's fields sent at a build (its contact history besides)
  std::size_t gathered_bytes_per_particle = 0;  // a particle's fields handed to every rank at a gather
  std::size_t bytes_per_history_entry = 0;      // a contact's history, sent with its owner
  std::size_t bytes_per_bond = 0;               // a bond, sent with its ends
  // A time-series sample and a measurement merge each rank's sums over its own particles
  // (Simulation::merge_over_ranks): latency-bound all-gathers of small messages.
  int collectives_per_sample = 0;
  int collectives_per_measurement = 0;
  std::size_t merged_bytes_per_sample = 0;       // what one rank sends
  std::size_t merged_bytes_per_statistic = 0;    // a region's, or a profile bin's, sums
};
/// The traffic of this build of RegoDEM, for a run with bonds or not and removing the
/// grains that leave its domain or not (each adds agreements to a build).
CodeTraffic code_traffic(bool bonds = false, bool removes_lost_particles = false);

/// The bed cut into `ranks` bricks: what each rank holds.
struct RankShares {
  int ranks = 1;
  double total_work = 0.0;
  std::vector<std::size_t> own, ghosts;    // particles, by rank
  std::vector<double> own_work, ghost_work;
  std::vector<int> partners;               // the ranks whose particles it holds as ghosts
};

/// Cuts `domain` over `points` (of radii `radii_m`) weighted by `weights` (empty: 1 each)
/// as a run does, and counts each rank's own particles and ghosts (the other bricks'
/// particles its brick wants: GhostReach, for a pair skin of `skin_m`).
RankShares cut_into_bricks(const Brick& domain, std::span<const Vec3> points, std::span<const double> radii_m,
                           std::span<const double> weights, double skin_m, int ranks);

/// What one process measured of the stepping to project.
struct OneProcessStep {
  double particles = 0.0;    // of the run (the cut's counts are scaled to it)
  double step_s = 0.0;       // wall time of one step of all of them in one process
  double builds_per_step = 0.0;
};

/// One step on N ranks, per part, on the rank that takes longest.
struct RankStepCost {
  int ranks = 1;
  int slowest_rank = 0;
  double own = 0.0, ghosts = 0.0;  // the slowest rank's (scaled to the run's particles)
  int partners = 0;
  double compute_s = 0.0;      // its own particles and ghosts at one process's cost per particle (an upper bound)
  double halo_s = 0.0;         // its ghost refreshes
  double build_s = 0.0;        // its share of the neighbour builds' messages, per step
  double collectives_s = 0.0;  // every rank's
  double step_s = 0.0;         // the step, as long as the slowest rank's
  double efficiency = 1.0;     // one process's step / (ranks x step_s)
};

RankStepCost project_step(const RankShares& shares, const OneProcessStep& one, const NetworkModel& network,
                          const CodeTraffic& traffic);

/// A gather (every rank given every particle, where a run reads or adds particles:
/// snapshots, insertions, checkpoints, a stage's end): three all-gathers (six collectives:
/// the particles, bond breaks, impacts) moving `particles` of `bytes_per_particle` each
/// (fields, contact histories, bonds), then every rank's lists rebuilt over all of them,
/// counted as one step of one process. The build the next step makes to split them again
/// is not charged (a build's collectives and exchanges, small beside that step).
double project_gather_s(double particles, double bytes_per_particle, int ranks, double one_process_step_s,
                        const NetworkModel& network);

/// One merge of every rank's sums (a sample's or a measurement's): `collectives`
/// all-gathers, every rank receiving every rank's `bytes_per_rank`.
double project_merge_s(int collectives, double bytes_per_rank, int ranks, const NetworkModel& network);

/// Weak scaling: every rank holds an interior brick of a bed that grows with the ranks,
/// `own` particles each, with `ghosts` from min(26, ranks - 1) partners (its face, edge and
/// corner neighbours in a 3-D arrangement).
RankShares uniform_shares(int ranks, std::size_t own, std::size_t ghosts);

/// The ghosts of a cubic brick of `own` particles in a bed of `particles_per_m3`: those in
/// the shell within `reach_m` of it (the brick grown by a sphere: faces, rounded edges
/// and corners).
double cubic_brick_ghosts(double own, double particles_per_m3, double reach_m);

/// The most ranks a projection cuts a bed into (its partner table is ranks^2 bytes).
inline constexpr int kMostProjectedRanks = 16384;

/// Rounds of a collective over `ranks`: ceil(log2 ranks), 0 for one.
int collective_rounds(int ranks);

}  // namespace regodem
