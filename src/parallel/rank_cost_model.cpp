#include "parallel/rank_cost_model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "contact/neighbor_list.hpp"
#include "parallel/bond_transfer.hpp"
#include "parallel/ghost_reach.hpp"
#include "parallel/particle_transfer.hpp"

namespace regodem {

CodeTraffic code_traffic(bool bonds, bool removes_lost_particles) {
  CodeTraffic t;
  // Simulation::step over ranks: the vote on a rebuild (any_rank), the wall and heat
  // totals summed in rank order (a gather and a broadcast), the end-of-step agreement.
  t.collectives_per_step = 4;
  t.exchanges_per_step = 1;  // HaloExchange::refresh_ghosts
  // A build (Simulation::rebuild_neighbors, HaloExchange::redistribute), instead of the
  // refresh: 6 collectives (the particle count, the busiest rank's work, the agreement that
  // no particle left its brick unowned, every rank's radius bands for the ghosts' reach,
  // ...: measured by the test); with bonds the
  // agreement that none outreaches the ghosts; with lost grains removed their books
  // gathered (and their bonds' stored energy summed); the migrants sent, then the new ghosts.
  t.collectives_per_build = 6 + (bonds ? 1 : 0) + (removes_lost_particles ? 2 + (bonds ? 2 : 0) : 0);
  t.exchanges_per_build = 2;
  t.refresh_bytes_per_ghost = bytes_per_particle(ParticleTransfer::ghost_refresh);
  t.new_ghost_bytes = bytes_per_particle(ParticleTransfer::ghost);
  t.gathered_bytes_per_particle = bytes_per_particle(ParticleTransfer::whole);
  t.bytes_per_history_entry = sizeof(SavedContact);
  t.bytes_per_bond = bytes_per_bond();
  // Counted in stage_runner's time_series_row, not measured, for a run with heat, the
  // energy audit and bonds (fewer without): each sum over the particles is its own
  // all-gather (a count and the data: 2), each largest value one round:
  // the energies (kinetic twice over, potential, bonds' stored, and again inside the
  // audit's balance), temperatures, thermal energy and history, bond counts, the fastest
  // impact, the heat step's stability check (with the lumped walls' conductance).
  t.collectives_per_sample = 33;
  t.collectives_per_measurement = 2;
  // An exact sum travels as 5 doubles and its nonzero 32-bit digits (a few where the
  // terms' magnitudes are alike).
  t.merged_bytes_per_sample = 20 * 8 * sizeof(double);
  t.merged_bytes_per_statistic = 12 * sizeof(double);
  return t;
}

int collective_rounds(int ranks) {
  int rounds = 0;
  for (int reach = 1; reach < ranks; reach *= 2) ++rounds;
  return rounds;
}

RankShares cut_into_bricks(const Brick& domain, std::span<const Vec3> points, std::span<const double> radii_m,
                           std::span<const double> weights, double skin_m, int ranks) {
  if (ranks < 1 || ranks > kMostProjectedRanks)
    throw InputError(fmt::format("{} ranks: from 1 to {}", ranks, kMostProjectedRanks));
  if (!weights.empty() && weights.size() != points.size())
    throw InputError(fmt::format("{} weights for {} points", weights.size(), points.size()));
  if (radii_m.size() != points.size())
    throw InputError(fmt::format("{} radii for {} points", radii_m.size(), points.size()));
  const RecursiveBisection bricks(domain, points, weights, ranks);
  const GhostReach reach{skin_m, radius_bands_by_brick(bricks, points, radii_m)};
  const auto n = static_cast<std::size_t>(ranks);
  RankShares shares;
  shares.ranks = ranks;
  shares.own.assign(n, 0);
  shares.ghosts.assign(n, 0);
  shares.own_work.assign(n, 0.0);
  shares.ghost_work.assign(n, 0.0);
  shares.partners.assign(n, 0);
  std::vector<char> hears_from(n * n, 0);  // [receiver * n + sender]
  // Each brick asks wanted() of the bricks near its own points only (as a run does).
  std::vector<std::size_t> owner_of(points.size());
  std::vector<std::vector<std::size_t>> own_points(n);
  for (std::size_t p = 0; p < points.size(); ++p) {
    owner_of[p] = static_cast<std::size_t>(bricks.rank_of(points[p]));
    own_points[owner_of[p]].push_back(p);
  }
  std::vector<std::vector<int>> near(n);
  for (std::size_t r = 0; r < n; ++r) {
    std::vector<Vec3> x;
    std::vector<double> radius;
    for (const std::size_t p : own_points[r]) {
      x.push_back(points[p]);
      radius.push_back(radii_m[p]);
    }
    const CentresBox box = centres_box(x, radius);
    if (!x.empty()) near[r] = reach.bricks_near(box.box, box.largest_radius_m, static_cast<int>(r));
  }
  for (std::size_t p = 0; p < points.size(); ++p) {
    const double w = weights.empty() ? 1.0 : weights[p];
    const std::size_t owner = owner_of[p];
    ++shares.own[owner];
    shares.own_work[owner] += w;
    shares.total_work += w;
    for (const int near_rank : near[owner]) {
      const auto r = static_cast<std::size_t>(near_rank);
      if (!reach.wanted(near_rank, points[p], radii_m[p])) continue;
      ++shares.ghosts[r];
      shares.ghost_work[r] += w;
      hears_from[r * n + owner] = 1;
    }
  }
  for (std::size_t r = 0; r < n; ++r)
    shares.partners[r] = static_cast<int>(std::count(hears_from.begin() + static_cast<std::ptrdiff_t>(r * n),
                                                     hears_from.begin() + static_cast<std::ptrdiff_t>((r + 1) * n), 1));
  return shares;
}

RankShares uniform_shares(int ranks, std::size_t own, std::size_t ghosts) {
  if (ranks < 1) throw InputError(fmt::format("{} ranks: at least one", ranks));
  const auto n = static_cast<std::size_t>(ranks);
  RankShares shares;
  shares.ranks = ranks;
  shares.own.assign(n, own);
  shares.ghosts.assign(n, ranks > 1 ? ghosts : 0);
  shares.own_work.assign(n, static_cast<double>(own));
  shares.ghost_work.assign(n, ranks > 1 ? static_cast<double>(ghosts) : 0.0);
  shares.partners.assign(n, std::min(26, ranks - 1));
  shares.total_work = static_cast<double>(own) * ranks;
  return shares;
}

double cubic_brick_ghosts(double own, double particles_per_m3, double reach_m) {
  const double side_m = std::cbrt(own / particles_per_m3), pi = std::acos(-1.0);
  // The brick grown by a ball of radius reach (Steiner): 6 faces, 12 quarter-cylinder
  // edges, 8 eighth-sphere corners.
  const double shell_m3 = 6.0 * side_m * side_m * reach_m + 3.0 * pi * side_m * reach_m * reach_m +
                          4.0 / 3.0 * pi * reach_m * reach_m * reach_m;
  return particles_per_m3 * shell_m3;
}

RankStepCost project_step(const RankShares& shares, const OneProcessStep& one, const NetworkModel& network,
                          const CodeTraffic& traffic) {
  RankStepCost cost;
  cost.ranks = shares.ranks;
  if (shares.total_work <= 0.0 || one.particles <= 0.0) return cost;
  std::size_t counted = 0;
  for (const std::size_t own : shares.own) counted += own;
  const double scale = one.particles / static_cast<double>(counted);  // the cut's sample to the run's count
  const int rounds = collective_rounds(shares.ranks);
  const double alpha = network.latency_s, beta = network.bandwidth_bytes_per_s;
  cost.collectives_s = traffic.collectives_per_step * rounds * alpha;
  double slowest_s = -1.0;
  for (std::size_t r = 0; r < shares.own.size(); ++r) {
    if (shares.ranks == 1) break;
    const double ghosts = scale * static_cast<double>(shares.ghosts[r]);
    // A ghost is charged an own particle's cost, an upper bound: it is binned and listed and
    // its pairs with own particles are computed here too, but its pairs with other ghosts
    // are skipped and it is not integrated.
    const double compute_s = one.step_s * (shares.own_work[r] + shares.ghost_work[r]) / shares.total_work;
    // An exchange: the all-to-all of counts (rounds x latency, 4 bytes per rank per
    // round), then one message from each partner.
    const double exchange_latency_s =
        (rounds + shares.partners[r]) * alpha + 4.0 * shares.ranks * rounds / beta;
    const double halo_s =
        traffic.exchanges_per_step * (exchange_latency_s + ghosts * static_cast<double>(traffic.refresh_bytes_per_ghost) / beta);
    // A build's messages in place of a refresh (the migrants, few between two builds, not counted).
    const double build_s =
        one.builds_per_step *
        ((traffic.exchanges_per_build - traffic.exchanges_per_step) * exchange_latency_s +
         ghosts * (static_cast<double>(traffic.new_ghost_bytes) - static_cast<double>(traffic.refresh_bytes_per_ghost)) /
             beta +
         traffic.collectives_per_build * rounds * alpha);
    const double total_s = compute_s + halo_s + build_s;
    if (total_s > slowest_s) {
      slowest_s = total_s;
      cost.slowest_rank = static_cast<int>(r);
      cost.own = scale * static_cast<double>(shares.own[r]);
      cost.ghosts = ghosts;
      cost.partners = shares.partners[r];
      cost.compute_s = compute_s;
      cost.halo_s = halo_s;
      cost.build_s = build_s;
    }
  }
  if (shares.ranks == 1) {
    cost.own = one.particles;
    cost.compute_s = one.step_s;
    cost.collectives_s = 0.0;
  }
  cost.step_s = cost.compute_s + cost.halo_s + cost.build_s + cost.collectives_s;
  cost.efficiency = cost.step_s > 0.0 ? one.step_s / (shares.ranks * cost.step_s) : 1.0;
  return cost;
}

double project_gather_s(double particles, double bytes_per_particle, int ranks, double one_process_step_s,
                        const NetworkModel& network) {
  if (ranks <= 1) return 0.0;
  // Three all-gathers of two collectives each (a count, then the data): the particles, the
  // bond breaks and the fastest impacts (Simulation::gather_everywhere).
  constexpr double collectives_per_gather = 6.0;
  return collectives_per_gather * collective_rounds(ranks) * network.latency_s +
         particles * bytes_per_particle / network.bandwidth_bytes_per_s + one_process_step_s;
}

double project_merge_s(int collectives, double bytes_per_rank, int ranks, const NetworkModel& network) {
  if (ranks <= 1) return 0.0;
  return collectives * collective_rounds(ranks) * network.latency_s +
         static_cast<double>(ranks) * bytes_per_rank / network.bandwidth_bytes_per_s;
}

}  // namespace regodem
