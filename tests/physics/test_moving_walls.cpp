// Walls in prescribed motion move particles through contact as rigid-body kinematics
// says: a translating plate pushes a sliding sphere at the plate's speed; a turntable
// (a plane spinning about its normal) carries a sphere round at omega r; and the force
// the particles exert on a wall is reported (a resting sphere loads the floor with its
// weight). Time step 0.05 of the Rayleigh time.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "physics_fixtures.hpp"

namespace regodem::testing {
namespace {

constexpr double kRadius = 1.0e-3;
constexpr double kG = 9.81;

Simulation sphere_on_floor(const SphereMaterial& m, WallSet walls, double dt) {
  walls.add_plane(walls.add_body("floor", {}), {0, 0, 0}, {0, 0, 1}, 0);
  Simulation sim(one_material(m), walls, settings_for(kRadius, dt, {0, 0, -kG}, 0.2));
  sim.add_particle(sphere({0.01, 0, kRadius}, {}, kRadius, m.density));
  sim.particles.inv_inertia[0] = 0.0;  // a sliding block
  return sim;
}

// Mean sphere speed over the last 0.1 s equals the plate speed within 1 %.
TEST(MovingWalls, TranslatingPlatePushesAtItsSpeed) {
  SphereMaterial m;
  m.sliding_friction = 0.5;
  const double dt = 0.05 * rayleigh_time_for(m, kRadius);
  const double speed = 0.02;
  WallMotion push;
  push.velocity_m_per_s = {speed, 0, 0};
  WallSet walls;
  walls.add_plane(walls.add_body("plate", push), {0.01 - 1.5 * kRadius, 0, 0}, {1, 0, 0}, 0);
  Simulation sim = sphere_on_floor(m, walls, dt);
  sim.advance(static_cast<std::uint64_t>(0.4 / dt));
  const double x0 = sim.particles.position_m[0].x, t0 = sim.time_s();
  sim.advance(static_cast<std::uint64_t>(0.1 / dt));
  const double mean_speed = (sim.particles.position_m[0].x - x0) / (sim.time_s() - t0);
  EXPECT_NEAR(mean_speed, speed, 0.01 * speed);
  // The plate feels the sliding friction it overcomes, mu m g, pushing back (-x),
  // within 1 %.
  const double weight = sim.particles.mass_kg[0] * kG;
  EXPECT_NEAR(sim.walls.bodies[0].force_N.x, -m.sliding_friction * weight, 0.01 * m.sliding_friction * weight);
}

// A turntable at 1 rad/s carries a sphere at r = 10 mm round at omega r within 1 %
// (friction 0.5 g far exceeds the centripetal 0.01 m/s^2), and the floor carries the
// sphere's weight within 0.1 %.
TEST(MovingWalls, TurntableCarriesSphereRoundAndFloorCarriesItsWeight) {
  SphereMaterial m;
  m.sliding_friction = 0.5;
  const double dt = 0.05 * rayleigh_time_for(m, kRadius);
  const double omega = 1.0;
  MaterialTable materials = one_material(m);
  WallMotion spin;
  spin.angular_velocity_rad_per_s = {0, 0, omega};
  WallSet walls;
  walls.add_plane(walls.add_body("turntable", spin), {0, 0, 0}, {0, 0, 1}, 0);
  Simulation sim(materials, walls, settings_for(kRadius, dt, {0, 0, -kG}, 0.2));
  sim.add_particle(sphere({0.01, 0, kRadius}, {}, kRadius, m.density));
  sim.particles.inv_inertia[0] = 0.0;
  sim.advance(static_cast<std::uint64_t>(0.3 / dt));
  const Vec3 x = sim.particles.position_m[0], v = sim.particles.velocity_m_per_s[0];
  const double r = std::hypot(x.x, x.y);
  EXPECT_NEAR(norm(v), omega * r, 0.01 * omega * r);
  EXPECT_NEAR(r, 0.01, 1e-4);
  const double weight = sim.particles.mass_kg[0] * kG;
  EXPECT_NEAR(sim.walls.bodies[0].force_N.z, -weight, 1e-3 * weight);
}

}  // namespace
}  // namespace regodem::testing
