// Results are deterministic for a fixed seed: two runs of the same collapsing, rotating,
// wall-bounded packing on two threads are bit-for-bit identical, positions and
// temperatures (heat on, friction heating on, a lumped cup). Other thread counts giving
// the same run: ThreadCount.* in test_checkpoint_restart.cpp.
#include <gtest/gtest.h>

#include "core/rng.hpp"
#include "physics_fixtures.hpp"

namespace regodem::testing {
namespace {

struct State {
  std::vector<Vec3> position;
  std::vector<double> temperature;
  double cup_temperature;
};

State run_once() {
  SphereMaterial m;
  m.restitution = 0.3;
  m.sliding_friction = 0.5;
  m.rolling_friction = 0.1;
  const double radius = 0.5e-3;
  const double dt = 0.1 * rayleigh_time_for(m, radius);
  WallSet walls;
  walls.add_cylinder(walls.add_body("cup", {}), {0, 0, -0.01}, {0, 0, 1}, 0.006, 0.03, true, false, true, false, 0);
  SimulationSettings settings = settings_for(radius, dt, {0, 0, -9.81}, 0.03, 2);
  settings.min_particles_per_thread = 100;  // make both threads work on this small system
  settings.heat.enabled = true;
  settings.heat.time_scale_factor = 1e4;
  settings.heat.friction_heating = true;
  ThermalWall cup;
  cup.mode = WallThermalMode::lumped;
  cup.initial_temperature_K = 400.0;
  cup.heat_capacity_J_per_K = 0.01;
  Simulation sim(one_material(m), walls, settings, {cup});
  Rng rng(17);
  add_grain_lattice(sim, rng, radius, m.density, {}, 0.05, 0.97);
  sim.advance(8000);
  EXPECT_GT(sim.contact_statistics().particle_contacts, 100u);
  EXPECT_GT(sim.neighbor_list().rebuild_count(), 1u);
  return {sim.particles.position_m, sim.particles.temperature_K, sim.wall_thermal_state[0].temperature_K};
}

TEST(Determinism, SameStartAndThreadsGiveIdenticalState) {
  const State first = run_once(), second = run_once();
  ASSERT_EQ(first.position.size(), second.position.size());
  for (std::size_t i = 0; i < first.position.size(); ++i) {
    ASSERT_EQ(first.position[i], second.position[i]) << "particle " << i;
    ASSERT_EQ(first.temperature[i], second.temperature[i]) << "particle " << i;
  }
  EXPECT_EQ(first.cup_temperature, second.cup_temperature);
  EXPECT_NE(first.cup_temperature, 400.0);  // heat did flow
}

}  // namespace
}  // namespace regodem::testing
