// A wall's feed that stops at a thrust (`motion.stop_at_thrust`): the piston that presses
// the matching cell's hot side. A sphere between a fixed floor and a slowly descending
// piston carries the same Hertz force on both sides (quasi-static), so the piston stops
// once it has travelled the gap plus twice the Hertz overlap under the thrust limit F,
// delta_F = (3 F / (4 E* sqrt(R)))^(2/3), and stays there.
#include <gtest/gtest.h>

#include "physics_fixtures.hpp"

namespace regodem::testing {
namespace {

TEST(WallThrustStop, PistonStopsWhereTheSphereCarriesTheThrustLimit) {
  constexpr double kRadius = 1.0e-3, kGap = 1.0e-6, kThrust_N = 1.0e-3, kSpeed = 1.0e-3;
  SphereMaterial m;
  m.restitution = 0.5;
  const double dt = 0.1 * rayleigh_time_for(m, kRadius);
  WallSet walls;
  walls.add_plane(walls.add_body("floor", {}), {0, 0, 0}, {0, 0, 1}, 0);
  WallMotion press;
  press.velocity_m_per_s = {0, 0, -kSpeed};
  press.max_thrust_N = kThrust_N;
  walls.add_plane(walls.add_body("piston", press), {0, 0, 2.0 * kRadius + kGap}, {0, 0, -1}, 0);
  Simulation sim(one_material(m), walls, settings_for(kRadius, dt, {}, 0.01), {});
  sim.add_particle(sphere({0, 0, kRadius}, {}, kRadius, m.density));

  const WallBody& piston = sim.walls.bodies[1];
  const auto thrust_N = [&] { return -dot(piston.force_N, piston.feed_direction); };
  // The thrust each step starts from: the last one of the feed must be the first at or
  // above the limit.
  double last_thrust_N = 0.0, thrust_before_N = 0.0;
  int steps = 0;
  while (norm2(piston.motion.velocity_m_per_s) > 0.0 && steps < 100000) {
    thrust_before_N = last_thrust_N;
    last_thrust_N = thrust_N();
    sim.step();
    ++steps;
  }
  ASSERT_LT(steps, 100000) << "the piston never stopped";
  EXPECT_GE(last_thrust_N, kThrust_N);
  EXPECT_LT(thrust_before_N, kThrust_N);
  // Where: the gap plus the two Hertz overlaps under F. A step's travel is kSpeed dt =
  // 5e-3 delta here; 2 % leaves room for the sphere's lag behind the slow piston.
  const double delta = hertz_overlap(kThrust_N, effective_youngs_modulus(m), kRadius);
  EXPECT_NEAR(piston.travel_m / (kGap + 2.0 * delta), 1.0, 0.02);
  // Stopped for good: a thrust that relaxes below F does not restart the feed.
  const double stopped_at_m = piston.travel_m;
  for (int i = 0; i < 2000; ++i) sim.step();
  EXPECT_EQ(piston.travel_m, stopped_at_m);
}

}  // namespace
}  // namespace regodem::testing
