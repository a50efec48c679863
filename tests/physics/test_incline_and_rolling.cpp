// Friction on a slope and rolling resistance against the rigid-body results:
//   sliding block (rotation locked): a = g (sin t - mu_s cos t) when tan t > mu_s, else 0;
//   rolling sphere without slip:     a = 5/7 g (sin t - mu_r cos t)  (I = 2/5 m R^2);
//   sphere rolling on a flat plane decelerates at 5/7 mu_r g and stops at v0^2/(2 a);
//   a free sphere with rolling friction stays put while tan t <= mu_r: the static torque
//   m g sin t R about its centre is held by the resistance mu_r m g cos t R.
// The slope is a horizontal plane under tilted gravity. Time step 0.05 of the Rayleigh
// time throughout.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "physics_fixtures.hpp"

namespace regodem::testing {
namespace {

constexpr double kRadius = 1.0e-3;
constexpr double kG = 9.81;

struct Slope {
  Simulation sim;
  double dt;
};

/// A sphere resting on the plane z = 0 (at its equilibrium overlap) under gravity
/// tilted by `angle` towards +x.
Slope sphere_on_slope(const SphereMaterial& m, double angle, bool lock_rotation, Vec3 velocity = {},
                      Vec3 omega = {}, RollingModel rolling = RollingModel::relative_spin) {
  const double dt = 0.05 * rayleigh_time_for(m, kRadius);
  WallSet walls;
  walls.add_plane(walls.add_body("slope", {}), {0, 0, 0}, {0, 0, 1}, 0);
  const Vec3 gravity{kG * std::sin(angle), 0.0, -kG * std::cos(angle)};
  MaterialTable table = one_material(m);
  PairProperties pair = table.pair(0, 0);
  pair.rolling_model = rolling;
  table.set_pair(0, 0, pair);
  Slope s{Simulation(table, walls, settings_for(kRadius, dt, gravity, 1.0)), dt};
  // Equilibrium overlap of a sphere on a plane: F = 4/3 E* sqrt(R) delta^{3/2}.
  const double e_star = effective_youngs_modulus(m);
  const double mass = sphere_mass(m, kRadius);
  const double delta = std::pow(3.0 * mass * kG * std::cos(angle) / (4.0 * e_star * std::sqrt(kRadius)), 2.0 / 3.0);
  NewParticle p = sphere({0, 0, kRadius - delta}, velocity, kRadius, m.density);
  p.angular_velocity_rad_per_s = omega;
  s.sim.add_particle(p);
  if (lock_rotation) s.sim.particles.inv_inertia[0] = 0.0;
  return s;
}

/// Mean acceleration along x between t_start and t_end.
double acceleration_x(Slope& s, double t_start, double t_end) {
  s.sim.advance(static_cast<std::uint64_t>(t_start / s.dt));
  const double v0 = s.sim.particles.velocity_m_per_s[0].x, time0 = s.sim.time_s();
  s.sim.advance(static_cast<std::uint64_t>((t_end - t_start) / s.dt));
  return (s.sim.particles.velocity_m_per_s[0].x - v0) / (s.sim.time_s() - time0);
}

// Tolerance 0.5 % of the expected acceleration.
TEST(Incline, LockedSphereSlidesWithCoulombFriction) {
  SphereMaterial m;
  m.sliding_friction = 0.3;
  const double angle = 30.0 * std::numbers::pi / 180.0;
  Slope s = sphere_on_slope(m, angle, true);
  const double expected = kG * (std::sin(angle) - m.sliding_friction * std::cos(angle));
  EXPECT_NEAR(acceleration_x(s, 0.02, 0.1), expected, 0.005 * expected);
}

// Below the friction angle the locked sphere only creeps elastically: it moves less
// than 0.1 % of its radius in 0.2 s.
TEST(Incline, LockedSphereStaysBelowFrictionAngle) {
  SphereMaterial m;
  m.sliding_friction = 0.3;
  const double angle = 10.0 * std::numbers::pi / 180.0;  // tan = 0.176 < 0.3
  Slope s = sphere_on_slope(m, angle, true);
  s.sim.advance(static_cast<std::uint64_t>(0.02 / s.dt));
  const double x0 = s.sim.particles.position_m[0].x;
  s.sim.advance(static_cast<std::uint64_t>(0.2 / s.dt));
  EXPECT_LT(std::abs(s.sim.particles.position_m[0].x - x0), 1e-3 * kRadius);
  EXPECT_LT(std::abs(s.sim.particles.velocity_m_per_s[0].x), 1e-5);
}

// Rolling without slip under rolling friction; tolerance 1 %, and slip speed
// |v - omega R| below 1 % of v.
TEST(Incline, FreeSphereRollsWithRollingResistance) {
  SphereMaterial m;
  m.sliding_friction = 0.8;
  m.rolling_friction = 0.1;
  const double angle = 20.0 * std::numbers::pi / 180.0;
  Slope s = sphere_on_slope(m, angle, false);
  const double expected = 5.0 / 7.0 * kG * (std::sin(angle) - m.rolling_friction * std::cos(angle));
  EXPECT_NEAR(acceleration_x(s, 0.02, 0.1), expected, 0.01 * expected);
  const double v = s.sim.particles.velocity_m_per_s[0].x;
  const double rim_speed = s.sim.particles.angular_velocity_rad_per_s[0].y * kRadius;
  EXPECT_NEAR(rim_speed, v, 0.01 * v);
}

// Rolling on a flat plane from v0 = 0.05 m/s: stopping distance v0^2 / (2 * 5/7 mu_r g)
// within 2 %, and at rest afterwards (no chatter). Under EDEM's own-spin model the arm
// R - delta differs from R by under 1e-4 of R, so the same bounds hold.
void expect_flat_plane_stop(RollingModel rolling) {
  SphereMaterial m;
  m.sliding_friction = 0.8;
  m.rolling_friction = 0.1;
  const double v0 = 0.05;
  Slope s = sphere_on_slope(m, 0.0, false, {v0, 0, 0}, {0, v0 / kRadius, 0}, rolling);
  const double deceleration = 5.0 / 7.0 * m.rolling_friction * kG;
  const double stop_time = v0 / deceleration;
  s.sim.advance(static_cast<std::uint64_t>(1.5 * stop_time / s.dt));
  const double expected = v0 * v0 / (2.0 * deceleration);
  EXPECT_NEAR(s.sim.particles.position_m[0].x, expected, 0.02 * expected);
  EXPECT_LT(std::abs(s.sim.particles.velocity_m_per_s[0].x), 1e-4 * v0);
  EXPECT_LT(std::abs(s.sim.particles.angular_velocity_rad_per_s[0].y) * kRadius, 1e-4 * v0);
}

TEST(Rolling, SphereOnFlatPlaneStopsAsPredicted) { expect_flat_plane_stop(RollingModel::relative_spin); }

TEST(Rolling, OwnSpinSphereOnFlatPlaneStopsAsPredicted) { expect_flat_plane_stop(RollingModel::own_spin); }

// EDEM's own-spin model on the slope: above the rolling-friction angle the sphere rolls
// at 5/7 g (sin t - mu_r cos t) without slip (the arm R - delta differs from R by under
// 1e-4 of R), tolerance 1 % on the acceleration and on |v - omega R| against v;
// below it (tan t = mu_r / 2) it stays put. A resistance capped at I |omega| / dt alone,
// the gravity's torque left out, would let it roll on at the creep speed
// 5/2 g sin t dt (omega = m g sin t R dt / I); the bound, stated before the run, is 1 % of
// that speed, and 1 % of the distance it would creep in 0.2 s.
TEST(Incline, OwnSpinSphereRollsAboveAndStaysBelowTheRollingFrictionAngle) {
  SphereMaterial m;
  m.sliding_friction = 0.8;
  m.rolling_friction = 0.1;
  const double rolling_angle = 20.0 * std::numbers::pi / 180.0;
  Slope rolls = sphere_on_slope(m, rolling_angle, false, {}, {}, RollingModel::own_spin);
  const double expected = 5.0 / 7.0 * kG * (std::sin(rolling_angle) - m.rolling_friction * std::cos(rolling_angle));
  EXPECT_NEAR(acceleration_x(rolls, 0.02, 0.1), expected, 0.01 * expected);
  const double v = rolls.sim.particles.velocity_m_per_s[0].x;
  EXPECT_NEAR(rolls.sim.particles.angular_velocity_rad_per_s[0].y * kRadius, v, 0.01 * v);

  const double resting_angle = std::atan(0.5 * m.rolling_friction);
  Slope rests = sphere_on_slope(m, resting_angle, false, {}, {}, RollingModel::own_spin);
  const double creep_speed = 2.5 * kG * std::sin(resting_angle) * rests.dt;
  rests.sim.advance(static_cast<std::uint64_t>(0.02 / rests.dt));
  const double x0 = rests.sim.particles.position_m[0].x, t0 = rests.sim.time_s();
  rests.sim.advance(static_cast<std::uint64_t>(0.2 / rests.dt));
  const double travel = rests.sim.particles.position_m[0].x - x0;
  EXPECT_LT(std::abs(travel), 0.01 * creep_speed * (rests.sim.time_s() - t0));
  EXPECT_LT(std::abs(rests.sim.particles.velocity_m_per_s[0].x), 0.01 * creep_speed);
  EXPECT_LT(std::abs(rests.sim.particles.angular_velocity_rad_per_s[0].y) * kRadius, 0.01 * creep_speed);
}

}  // namespace
}  // namespace regodem::testing
