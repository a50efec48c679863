// The step split over ranks (src/sim/particle_halo.hpp, src/parallel/mpi/halo_exchange.hpp),
// run by CTest with mpirun on 1, 2 and 3 ranks. A dense cluster of grains with random
// velocities and spins, drifting sideways in a cup under gravity, collides, slides and rolls
// against the cup and each other, and takes heat from the cup's wall held at 400 K (friction
// heat on). After 2,000 steps in one process it is split into bricks (each rank keeping its
// own grains with the contact history they own) and runs 3,000 steps more, grains crossing
// between bricks with their contact history; each particle ends with the position,
// velocity, spin and temperature it has in one process, bit for bit (the lists are rebuilt
// at the same steps on every rank and on the same grid, each contact with a ghost is computed
// from the same values on every rank that holds it, and each particle's sums run in the
// order of one process).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "../physics/physics_fixtures.hpp"
#include "core/error.hpp"
#include "core/rng.hpp"
#include "parallel/mpi/halo_exchange.hpp"
#include "parallel/rank_cost_model.hpp"

namespace regodem {
namespace {

using testing::one_material;
using testing::settings_for;
using testing::sphere;
using testing::SphereMaterial;

constexpr double kRadius = 0.5e-3;
constexpr std::uint64_t kSettle = 2000;  // in one process, before the split
constexpr std::uint64_t kSteps = 3000;   // split

enum class Cup { held_at_400K, lumped };

Simulation falling_cup(SphereMaterial& m, Cup kind = Cup::held_at_400K) {
  m.restitution = 0.3;
  m.sliding_friction = 0.5;
  m.rolling_friction = 0.1;
  const double dt = 0.1 * testing::rayleigh_time_for(m, kRadius);
  WallSet walls;
  walls.add_cylinder(walls.add_body("cup", {}), {0, 0, -0.01}, {0, 0, 1}, 0.006, 0.03, true, false, true, false, 0);
  SimulationSettings settings = settings_for(kRadius, dt, {0, 0, -9.81}, 0.03, 1);
  // Longest across x, so that the bricks are cut across the grains' drift.
  settings.domain = {{-0.025, -0.008, -0.012}, {0.025, 0.008, 0.03}};
  settings.heat.enabled = true;
  settings.heat.time_scale_factor = 1e4;
  settings.heat.friction_heating = true;
  ThermalWall cup;
  cup.mode = WallThermalMode::fixed;
  cup.prescribed_temperature_K = TimeTable(400.0);
  if (kind == Cup::lumped) {  // starts at 400 K and cools as the grains take its heat
    cup.mode = WallThermalMode::lumped;
    cup.initial_temperature_K = 400.0;
    cup.heat_capacity_J_per_K = 0.01;
  }
  Simulation sim(one_material(m), walls, settings, {cup});
  Rng rng(17);
  testing::add_grain_lattice(sim, rng, kRadius, m.density, {0.5, 0.0, 0.0}, 0.3, 0.9);
  return sim;
}

bool same_bytes(const auto& a, const auto& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// The same run as one rank: the lists are rebuilt where the split run rebuilds them to hand
// out the particles (a build re-sorts them, and with them the order of every sum).
struct OneProcess {
  Communicator alone{MPI_COMM_SELF};
  Simulation sim;
  std::unique_ptr<HaloExchange> whole;
  std::map<ParticleId, std::size_t> index_of;
  OneProcess(Simulation simulation, std::uint64_t settle_steps, std::uint64_t steps) : sim(std::move(simulation)) {
    sim.advance(settle_steps);
    const Domain& domain = sim.settings().domain;
    whole = std::make_unique<HaloExchange>(alone, RecursiveBisection(Brick{domain.min_m, domain.max_m}, {}, {}, 1),
                                           sim.ghost_skin_m());
    sim.distribute(whole.get());
    sim.advance(steps);
    for (std::size_t i = 0; i < sim.particles.size(); ++i) index_of[sim.particles.id[i]] = i;
  }
};

// The same run split over this run's ranks after settle_steps, in bricks of equal particle
// counts; each rank keeps the particles of its own brick.
struct SplitRun {
  Communicator comm;
  Simulation sim;
  std::optional<RecursiveBisection> bricks;
  std::unique_ptr<HaloExchange> halo;
  std::size_t total;
  /// skew_m: the bricks are cut for the particles moved by this much along x (all of them
  /// then start on the highest rank, to be spread again by the first rebalance).
  SplitRun(Simulation simulation, std::uint64_t settle_steps, std::uint64_t steps, double skew_m = 0.0)
      : sim(std::move(simulation)) {
    sim.advance(settle_steps);
    total = sim.particles.size();
    const Domain& domain = sim.settings().domain;
    std::vector<Vec3> points = sim.particles.position_m;
    for (Vec3& x : points) x.x += skew_m;
    bricks.emplace(Brick{domain.min_m, domain.max_m}, points, std::span<const double>{}, comm.size());
    halo = std::make_unique<HaloExchange>(comm, *bricks, sim.ghost_skin_m(), HaloExchange::Start::replicated);
    sim.distribute(halo.get());
    sim.advance(steps);
  }
};

class DistributedStepOnBricks : public ::testing::TestWithParam<double> {};

// Bricks cut for the grains as they are, or for the grains 20 mm away along x: then every
// grain starts on the highest rank, and the first build that weighs the ranks' work cuts the
// domain again (the bricks decide where a grain is stepped, not what it does).
INSTANTIATE_TEST_SUITE_P(CutForTheGrainsOrFarFromThem, DistributedStepOnBricks, ::testing::Values(0.0, -0.02));

TEST_P(DistributedStepOnBricks, EveryParticleEndsAsInOneProcessBitForBit) {
  SphereMaterial m;
  const OneProcess one(falling_cup(m), kSettle, kSteps);
  SplitRun split(falling_cup(m), kSettle, kSteps, GetParam());
  const Communicator& comm = split.comm;
  const Simulation& sim = split.sim;

  EXPECT_EQ(comm.sum(sim.own_particle_count()), split.total);
  EXPECT_GT(sim.neighbor_list().rebuild_count(), 10u);
  if (comm.size() > 1) {
    EXPECT_GT(comm.sum(split.halo->migrated_count()), 0u) << "no particle crossed between bricks: the test tests less";
    EXPECT_GT(comm.sum(split.halo->migrated_contact_count()), 0u) << "no contact history crossed with its particle";
    EXPECT_GT(comm.sum(split.halo->ghost_count()), 0u);
    if (GetParam() != 0.0) {
      EXPECT_GT(split.halo->rebalance_count(), 0u);
      EXPECT_GT(sim.own_particle_count(), 0u) << "rank " << comm.rank() << " was given no grains";
    }
  }
  std::size_t checked = 0;
  for (std::size_t i = 0; i < sim.particles.size(); ++i) {
    if (sim.is_ghost(i)) continue;
    ++checked;
    const auto found = one.index_of.find(sim.particles.id[i]);
    ASSERT_NE(found, one.index_of.end()) << "particle " << sim.particles.id[i];
    const std::size_t r = found->second;
    const ParticleStore& p = one.sim.particles;
    // At the last build every particle went to the rank of its brick.
    EXPECT_EQ(split.halo->bricks().rank_of(sim.neighbor_list().positions_at_build_m()[i]), comm.rank());
    ASSERT_TRUE(same_bytes(sim.particles.position_m[i], p.position_m[r]) &&
                same_bytes(sim.particles.velocity_m_per_s[i], p.velocity_m_per_s[r]) &&
                same_bytes(sim.particles.angular_velocity_rad_per_s[i], p.angular_velocity_rad_per_s[r]) &&
                same_bytes(sim.particles.temperature_K[i], p.temperature_K[r]))
        << "particle " << sim.particles.id[i] << " on rank " << comm.rank() << " of " << comm.size() << ": off by "
        << norm(sim.particles.position_m[i] - p.position_m[r]) << " m, "
        << norm(sim.particles.velocity_m_per_s[i] - p.velocity_m_per_s[r]) << " m/s, "
        << norm(sim.particles.angular_velocity_rad_per_s[i] - p.angular_velocity_rad_per_s[r]) << " rad/s, "
        << sim.particles.temperature_K[i] - p.temperature_K[r] << " K";
  }
  EXPECT_EQ(comm.sum(checked), split.total);
  // Heat did flow from the cup.
  double warmest = 0.0;
  for (const double t : one.sim.particles.temperature_K) warmest = std::max(warmest, t);
  EXPECT_GT(warmest, 300.0);
}

// The totals of each pass (the cup's force and heat, the contact counts) and the measurements
// over particles (energies, extremes) are summed over the ranks, so a lumped cup, whose temperature follows the heat all ranks' grains take from it,
// cools as in one process. The sums go in another order than one process's, so they agree
// to round-off: each of them adds a few hundred terms per step (a relative error below
// 1e-13 of the terms' magnitudes), over 2,500 steps below 1e-9 of the cup's force and heat
// and, through the cup, of the grains' temperatures (the bounds below). The grains' motion
// does not depend on the totals: it stays bit for bit.
TEST(DistributedStep, TotalsAreSummedOverRanksAndALumpedCupCoolsAsInOneProcess) {
  constexpr std::uint64_t settle = 1000, steps = 1500;
  SphereMaterial m;
  const OneProcess one(falling_cup(m, Cup::lumped), settle, steps);
  SplitRun split(falling_cup(m, Cup::lumped), settle, steps);
  const Simulation& sim = split.sim;

  const ThermalWallState& cup = sim.wall_thermal_state[0];
  const ThermalWallState& one_cup = one.sim.wall_thermal_state[0];
  EXPECT_LT(one_cup.temperature_K, 400.0 - 1e-3) << "the cup gave no heat: the test tests less";
  EXPECT_NEAR(cup.temperature_K, one_cup.temperature_K, 1e-9 * 400.0);
  EXPECT_NEAR(cup.heat_flow_to_particles_W, one_cup.heat_flow_to_particles_W,
              1e-9 * std::abs(one_cup.heat_flow_to_particles_W));
  EXPECT_GT(std::abs(one_cup.heat_flow_to_particles_W), 0.0);
  const Vec3 force = sim.walls.bodies[0].force_N, one_force = one.sim.walls.bodies[0].force_N;
  EXPECT_GT(norm(one_force), 0.0);
  EXPECT_LE(norm(force - one_force), 1e-9 * norm(one_force));
  EXPECT_EQ(sim.contact_statistics().particle_contacts, one.sim.contact_statistics().particle_contacts);
  EXPECT_EQ(sim.contact_statistics().wall_contacts, one.sim.contact_statistics().wall_contacts);
  EXPECT_GT(one.sim.contact_statistics().wall_contacts, 0u);
  // The measurements over particles: exact sums (core/exact_sum.hpp) of bit-for-bit
  // particles, so equal (the lumped cup's heat, in the thermal energy, to its 1e-9);
  // extremes exactly.
  EXPECT_EQ(sim.translational_kinetic_energy_J(), one.sim.translational_kinetic_energy_J());
  EXPECT_EQ(sim.rotational_kinetic_energy_J(), one.sim.rotational_kinetic_energy_J());
  EXPECT_EQ(sim.gravitational_potential_energy_J(), one.sim.gravitational_potential_energy_J());
  EXPECT_NEAR(sim.thermal_energy_J(), one.sim.thermal_energy_J(), 1e-9 * one.sim.thermal_energy_J());
  EXPECT_EQ(sim.max_speed_m_per_s(), one.sim.max_speed_m_per_s());
  EXPECT_EQ(sim.max_overlap_fraction(), one.sim.max_overlap_fraction());
  EXPECT_GT(one.sim.max_overlap_fraction(), 0.0);
  for (std::size_t i = 0; i < sim.particles.size(); ++i) {
    if (sim.is_ghost(i)) continue;
    const std::size_t r = one.index_of.at(sim.particles.id[i]);
    ASSERT_TRUE(same_bytes(sim.particles.position_m[i], one.sim.particles.position_m[r]) &&
                same_bytes(sim.particles.velocity_m_per_s[i], one.sim.particles.velocity_m_per_s[r]))
        << "particle " << sim.particles.id[i];
    ASSERT_NEAR(sim.particles.temperature_K[i], one.sim.particles.temperature_K[r], 1e-9 * 400.0)
        << "particle " << sim.particles.id[i];
  }
}

// A blow-up on one rank stops every rank with that rank's message (no rank waits for one
// that has stopped): one grain of the highest rank is thrown out of the domain.
TEST(DistributedStep, AGrainThrownOutOnOneRankStopsEveryRankWithItsMessage) {
  SphereMaterial m;
  SplitRun split(falling_cup(m), 200, 10);
  Simulation& sim = split.sim;
  const int thrower = split.comm.size() - 1;
  ParticleId thrown = 0;
  if (split.comm.rank() == thrower) {
    for (std::size_t i = 0; i < sim.particles.size(); ++i)
      if (!sim.is_ghost(i)) {
        sim.particles.velocity_m_per_s[i] = {0.0, 0.0, 1e6};  // leaves the domain in one step
        thrown = sim.particles.id[i];
        break;
      }
  }
  thrown = static_cast<ParticleId>(split.comm.sum(thrown));
  try {
    sim.advance(5);
    FAIL() << "no error";
  } catch (const SimulationError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("particle " + std::to_string(thrown) + " left the domain"), std::string::npos) << message;
    if (split.comm.size() > 1) {
      EXPECT_EQ(message.rfind("rank " + std::to_string(thrower) + ": ", 0), 0u) << message;
    }
  }
}

// A build that fails part way (here: a grain outside every rank's brick, the bricks cut over
// a box lower than the domain) stops every rank with the message, and the run can still be
// gathered whole for its outputs: every grain once, on every rank. At the first build after
// the start every rank held every grain before the halo cut them; later the lists no
// longer match the particles the failed build left.
TEST(DistributedStep, AFailedBuildLeavesTheRunWholeToGather) {
  for (const bool at_first_build : {true, false}) {
    SCOPED_TRACE(at_first_build ? "at the first build" : "at a later build");
    SphereMaterial m;
    Simulation sim = falling_cup(m);
    sim.advance(200);
    const std::size_t total = sim.particles.size();
    double highest_m = -1.0;
    for (const Vec3& x : sim.particles.position_m) highest_m = std::max(highest_m, x.z);
    const Domain& domain = sim.settings().domain;
    // The bricks end below the highest grain (at once) or 1 mm above it (it is then thrown up).
    const Vec3 top{domain.max_m.x, domain.max_m.y, at_first_build ? highest_m - 1e-4 : highest_m + 1e-3};
    Communicator comm;
    const RecursiveBisection bricks(Brick{domain.min_m, top}, sim.particles.position_m, {}, comm.size());
    HaloExchange halo(comm, bricks, sim.ghost_skin_m(), HaloExchange::Start::replicated);
    // As a run starts over ranks: gathered, every rank holding every grain until the
    // first build cuts them.
    sim.start_gathered(&halo);
    sim.distribute_again();
    std::string message;
    try {
      if (!at_first_build) {
        sim.advance(20);  // builds in between
        for (std::size_t i = 0; i < sim.particles.size(); ++i)
          if (!sim.is_ghost(i) && sim.particles.position_m[i].z > highest_m - 2e-3)
            sim.particles.velocity_m_per_s[i] = {0.0, 0.0, 2.0};  // out of the bricks within a few builds
      }
      sim.advance(2000);
    } catch (const SimulationError& e) {
      message = e.what();
    }
    EXPECT_NE(message.find("outside every rank's brick"), std::string::npos) << message;
    sim.gather_everywhere();
    ASSERT_EQ(sim.particles.size(), total);
    std::vector<ParticleId> ids = sim.particles.id;
    std::sort(ids.begin(), ids.end());
    EXPECT_EQ(std::adjacent_find(ids.begin(), ids.end()), ids.end()) << "a grain twice";
    EXPECT_EQ(sim.run_particle_count(), total);
  }
}

// What would change one rank's particles between steps, so that the ranks' next decisions
// differ (and one would wait for the others), is refused until it is done over ranks.
TEST(DistributedStep, ChangesToOneRanksParticlesBetweenStepsAreRefused) {
  SphereMaterial m;
  SplitRun split(falling_cup(m), 0, 1);
  Simulation& sim = split.sim;
  EXPECT_THROW(sim.add_particle(testing::sphere({0, 0, 0.01}, {}, kRadius, m.density, 200.0)), InputError);
  EXPECT_THROW(sim.remove_particles(std::vector<char>(sim.particles.size(), 1)), InputError);
  if (sim.own_particle_count() > 0) {
    std::size_t own = 0;
    while (sim.is_ghost(own)) ++own;
    EXPECT_THROW(sim.set_particle_velocity(own, {}, {}), InputError);
  }
  sim.advance(1);  // and the ranks go on together
}

// The traffic the cost model of a run over many ranks counts on (code_traffic(),
// src/parallel/rank_cost_model.hpp) is what a step sends: the collectives and exchanges of
// a step without a build and of one with a build, and the bytes of the ghosts' refresh.
TEST(DistributedStep, AStepSendsWhatTheCostModelCounts) {
  SphereMaterial m;
  SplitRun split(falling_cup(m), 1000, 1);  // the first step after the split builds
  Simulation& sim = split.sim;
  const CodeTraffic model = code_traffic();
  const Communicator& comm = split.comm;
  std::uint64_t plain_steps = 0, build_steps = 0;
  for (int s = 0; s < 300; ++s) {
    const CommunicationTally before = comm.tally();
    const std::uint64_t builds_before = sim.neighbor_list().rebuild_count();
    const std::uint64_t rebalances_before = split.halo->rebalance_count();
    sim.step();
    // A rebalance (rare: the model leaves it out) gathers every rank's points and work.
    const std::uint64_t rebalance_collectives = split.halo->rebalance_count() != rebalances_before ? 2 : 0;
    const CommunicationTally after = comm.tally();
    const bool built = sim.neighbor_list().rebuild_count() != builds_before;
    const std::uint64_t collectives = after.collectives - before.collectives;
    const std::uint64_t exchanges = after.exchanges - before.exchanges;
    // Every rank's refresh bytes: a count, then each ghost's fields, per message.
    const std::uint64_t bytes = comm.sum(after.exchange_bytes - before.exchange_bytes);
    const std::uint64_t messages = comm.sum(after.exchange_messages - before.exchange_messages);
    const std::uint64_t ghosts = comm.sum(split.halo->ghost_count());
    // The sums just taken are the test's, not the step's: `after` was read before them.
    if (built) {
      ++build_steps;
      if (comm.size() == 1) continue;  // one rank skips the cut's agreements; the model is for more
      EXPECT_EQ(collectives - rebalance_collectives,
                std::uint64_t(model.collectives_per_step + model.collectives_per_build))
          << "step " << s;
      EXPECT_EQ(exchanges, std::uint64_t(model.exchanges_per_build)) << "step " << s;
    } else {
      ++plain_steps;
      EXPECT_EQ(collectives, std::uint64_t(model.collectives_per_step)) << "step " << s;
      EXPECT_EQ(exchanges, std::uint64_t(model.exchanges_per_step)) << "step " << s;
      EXPECT_EQ(bytes, messages * sizeof(std::uint64_t) + ghosts * model.refresh_bytes_per_ghost) << "step " << s;
    }
  }
  EXPECT_GT(plain_steps, 100u);
  EXPECT_GT(build_steps, 2u) << "no neighbour build in 300 steps: the build's counts were not checked";
  if (comm.size() > 1) {
    EXPECT_GT(comm.sum(split.halo->ghost_count()), 0u) << "no ghosts: the bytes were not checked";
  }
}

}  // namespace
}  // namespace regodem
