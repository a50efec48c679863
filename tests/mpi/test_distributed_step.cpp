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

#include <cstring>
#include <map>

#include "../physics/physics_fixtures.hpp"
#include "core/rng.hpp"
#include "parallel/mpi/halo_exchange.hpp"

namespace regodem {
namespace {

using testing::one_material;
using testing::settings_for;
using testing::sphere;
using testing::SphereMaterial;

constexpr double kRadius = 0.5e-3;
constexpr std::uint64_t kSettle = 2000;  // in one process, before the split
constexpr std::uint64_t kSteps = 3000;   // split

Simulation falling_cup(SphereMaterial& m) {
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
  Simulation sim(one_material(m), walls, settings, {cup});
  Rng rng(17);
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j)
      for (int k = 0; k < 10; ++k) {
        const Vec3 x{(i - 3.5) * 1.0e-3, (j - 3.5) * 1.0e-3, -0.0094 + k * 1.0e-3};
        NewParticle p = sphere(x, {0.5 + rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3)},
                               kRadius * rng.uniform(0.9, 1.0), m.density, rng.uniform(100.0, 300.0));
        p.angular_velocity_rad_per_s = {rng.uniform(-10, 10), rng.uniform(-10, 10), rng.uniform(-10, 10)};
        sim.add_particle(p);
      }
  return sim;
}

bool same_bytes(const auto& a, const auto& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(DistributedStep, EveryParticleEndsAsInOneProcessBitForBit) {
  const Communicator comm;
  SphereMaterial m;
  // One process, with the lists rebuilt where the split run rebuilds them to hand out the
  // particles (a build re-sorts them, and with them the order of every sum): as one rank.
  Simulation one_process = falling_cup(m);
  one_process.advance(kSettle);
  const Communicator alone(MPI_COMM_SELF);
  const Domain& domain = one_process.settings().domain;
  HaloExchange whole(alone, RecursiveBisection(Brick{domain.min_m, domain.max_m}, {}, {}, 1),
                     one_process.ghost_reach_m(kRadius));
  one_process.distribute(&whole);
  one_process.advance(kSteps);
  std::map<ParticleId, std::size_t> reference;
  for (std::size_t i = 0; i < one_process.particles.size(); ++i) reference[one_process.particles.id[i]] = i;

  // Split after the grains have fallen into the cup: they cross between bricks in contact.
  Simulation sim = falling_cup(m);
  sim.advance(kSettle);
  const std::size_t total = sim.particles.size();
  // Bricks of equal particle counts at the split; each rank keeps the particles of its own.
  RecursiveBisection bricks(Brick{domain.min_m, domain.max_m}, sim.particles.position_m, {}, comm.size());
  HaloExchange halo(comm, bricks, sim.ghost_reach_m(kRadius), HaloExchange::Start::replicated);
  sim.distribute(&halo);
  sim.advance(kSteps);

  EXPECT_EQ(comm.sum(sim.own_particle_count()), total);
  EXPECT_GT(sim.neighbor_list().rebuild_count(), 10u);
  if (comm.size() > 1) {
    EXPECT_GT(comm.sum(halo.migrated_count()), 0u) << "no particle crossed between bricks: the test tests less";
    EXPECT_GT(comm.sum(halo.migrated_contact_count()), 0u) << "no contact history crossed with its particle";
    EXPECT_GT(comm.sum(halo.ghost_count()), 0u);
  }
  std::size_t checked = 0;
  for (std::size_t i = 0; i < sim.particles.size(); ++i) {
    if (sim.is_ghost(i)) continue;
    ++checked;
    const auto found = reference.find(sim.particles.id[i]);
    ASSERT_NE(found, reference.end()) << "particle " << sim.particles.id[i];
    const std::size_t r = found->second;
    // At the last build every particle went to the rank of its brick.
    EXPECT_EQ(bricks.rank_of(sim.neighbor_list().positions_at_build_m()[i]), comm.rank());
    ASSERT_TRUE(same_bytes(sim.particles.position_m[i], one_process.particles.position_m[r]) &&
                same_bytes(sim.particles.velocity_m_per_s[i], one_process.particles.velocity_m_per_s[r]) &&
                same_bytes(sim.particles.angular_velocity_rad_per_s[i],
                           one_process.particles.angular_velocity_rad_per_s[r]) &&
                same_bytes(sim.particles.temperature_K[i], one_process.particles.temperature_K[r]))
        << "particle " << sim.particles.id[i] << " on rank " << comm.rank() << " of " << comm.size() << ": off by "
        << norm(sim.particles.position_m[i] - one_process.particles.position_m[r]) << " m, "
        << norm(sim.particles.velocity_m_per_s[i] - one_process.particles.velocity_m_per_s[r]) << " m/s, "
        << norm(sim.particles.angular_velocity_rad_per_s[i] - one_process.particles.angular_velocity_rad_per_s[r])
        << " rad/s, " << sim.particles.temperature_K[i] - one_process.particles.temperature_K[r] << " K";
  }
  EXPECT_EQ(comm.sum(checked), total);
  // Heat did flow from the cup, and the grains did move.
  double warmest = 0.0;
  for (std::size_t r = 0; r < one_process.particles.size(); ++r)
    warmest = std::max(warmest, one_process.particles.temperature_K[r]);
  EXPECT_GT(warmest, 300.0);
}

}  // namespace
}  // namespace regodem
