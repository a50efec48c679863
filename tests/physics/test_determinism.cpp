// Results are deterministic for a fixed seed and thread count: two runs of the same
// collapsing, rotating, wall-bounded packing on two threads (force sums split between
// threads and merged in a fixed order) are bit-for-bit identical.
#include <gtest/gtest.h>

#include "core/rng.hpp"
#include "physics_fixtures.hpp"

namespace regodem::testing {
namespace {

std::vector<Vec3> run_once() {
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
  Simulation sim(one_material(m), walls, settings);
  Rng rng(17);
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j)
      for (int k = 0; k < 10; ++k) {
        const Vec3 x{(i - 3.5) * 1.0e-3, (j - 3.5) * 1.0e-3, -0.0094 + k * 1.0e-3};
        NewParticle p = sphere(x, {rng.uniform(-0.05, 0.05), rng.uniform(-0.05, 0.05), rng.uniform(-0.05, 0.05)}, radius * rng.uniform(0.97, 1.0),
                               m.density);
        p.angular_velocity_rad_per_s = {rng.uniform(-10, 10), rng.uniform(-10, 10), rng.uniform(-10, 10)};
        sim.add_particle(p);
      }
  sim.advance(8000);
  EXPECT_GT(sim.contact_statistics().particle_contacts, 100u);
  EXPECT_GT(sim.neighbor_list().rebuild_count(), 1u);
  return sim.particles.position_m;
}

TEST(Determinism, SameStartAndThreadsGiveIdenticalState) {
  const std::vector<Vec3> first = run_once(), second = run_once();
  ASSERT_EQ(first.size(), second.size());
  for (std::size_t i = 0; i < first.size(); ++i) ASSERT_EQ(first[i], second[i]) << "particle " << i;
}

}  // namespace
}  // namespace regodem::testing
