// The two rolling friction models (docs/physics.md, contact law, "rolling"), each
// against the rigid-body spin-down under a constant torque, omega(t) = omega0 - alpha t
// with alpha = mu_r F_n arm / I, I = 2/5 m R^2, stopping at t_stop = omega0 / alpha:
//   relative_spin (Ai et al. 2011 type A): the torque resists omega_i - omega_j less its
//     normal part, arm = R* (R/2 for two equal spheres, R at a wall);
//   own_spin (EDEM's standard model): each body's torque resists its own spin, whole,
//     with arm = its centre's distance to the contact point (R - delta/2 for two
//     spheres, R - delta at a wall).
// The centres are held (zero inverse mass) at a known overlap, so F_n is the Hertz
// force of that overlap, constant; sliding friction 0, so only rolling acts on the spin.
// Tolerances, stated before the runs: a constant torque under velocity Verlet changes the
// spin exactly linearly, so omega after the step nearest t_stop/2 is omega0 - alpha t
// there to 1e-3 of omega0 (t_stop is over 2,000 steps); at 1.1 t_stop the cap has stopped
// it (|omega| < 1e-9 omega0); where a model applies no torque the spin is unchanged exactly.
#include <gtest/gtest.h>

#include <cmath>

#include "physics_fixtures.hpp"

namespace regodem::testing {
namespace {

constexpr double kRadius = 1.0e-3;
constexpr double kOverlap = 1.0e-3 * kRadius;
constexpr double kOmega0 = 100.0;  // rad/s: t_stop over 2,000 steps with mu_r below

SphereMaterial rolling_grain() {
  SphereMaterial m;
  m.rolling_friction = 0.01;
  m.sliding_friction = 0.0;
  return m;
}

MaterialTable table_with(const SphereMaterial& m, RollingModel model) {
  MaterialTable table = one_material(m);
  PairProperties pair = table.pair(0, 0);
  pair.rolling_model = model;
  table.set_pair(0, 0, pair);
  return table;
}

struct SpinRun {
  double half_fraction = 0.0;  // time of the first reading / t_stop (about 1/2, whole steps)
  Vec3 half_a, half_b;         // spins then
  Vec3 late_a, late_b;         // spins at 1.1 t_stop
};

/// Advances to t_stop/2 and to 1.1 t_stop for a given expected t_stop.
template <class Spins>
void run_to(Simulation& sim, double dt, double t_stop, Spins&& read, SpinRun& out) {
  const auto half_steps = static_cast<std::uint64_t>(std::llround(0.5 * t_stop / dt));
  EXPECT_GT(half_steps, 1000u);
  sim.advance(half_steps);
  out.half_fraction = static_cast<double>(half_steps) * dt / t_stop;
  read(out.half_a, out.half_b);
  sim.advance(static_cast<std::uint64_t>(std::llround(0.6 * t_stop / dt)));
  read(out.late_a, out.late_b);
}

/// Two equal spheres along x, overlapping by kOverlap, spinning at omega_a and omega_b.
SpinRun two_spheres(RollingModel model, const Vec3& omega_a, const Vec3& omega_b, double expected_t_stop) {
  const SphereMaterial m = rolling_grain();
  const double dt = 0.1 * rayleigh_time_for(m, kRadius);
  Simulation sim(table_with(m, model), WallSet{}, settings_for(kRadius, dt));
  NewParticle a = sphere({-kRadius + 0.5 * kOverlap, 0, 0}, {}, kRadius, m.density);
  NewParticle b = sphere({kRadius - 0.5 * kOverlap, 0, 0}, {}, kRadius, m.density);
  a.angular_velocity_rad_per_s = omega_a;
  b.angular_velocity_rad_per_s = omega_b;
  sim.add_particle(a);
  sim.add_particle(b);
  for (std::size_t i = 0; i < 2; ++i) sim.particles.inv_mass_per_kg[i] = 0.0;
  SpinRun out;
  run_to(
      sim, dt, expected_t_stop,
      [&](Vec3& wa, Vec3& wb) {
        wa = sim.particles.angular_velocity_rad_per_s[index_of(sim, 0)];
        wb = sim.particles.angular_velocity_rad_per_s[index_of(sim, 1)];
      },
      out);
  return out;
}

/// One sphere pressed kOverlap into the plane z = 0, spinning at omega.
SpinRun sphere_on_plane(RollingModel model, const Vec3& omega, double expected_t_stop) {
  const SphereMaterial m = rolling_grain();
  const double dt = 0.1 * rayleigh_time_for(m, kRadius);
  WallSet walls;
  walls.add_plane(walls.add_body("floor", {}), {0, 0, 0}, {0, 0, 1}, 0);
  Simulation sim(table_with(m, model), walls, settings_for(kRadius, dt));
  NewParticle p = sphere({0, 0, kRadius - kOverlap}, {}, kRadius, m.density);
  p.angular_velocity_rad_per_s = omega;
  sim.add_particle(p);
  sim.particles.inv_mass_per_kg[0] = 0.0;
  SpinRun out;
  run_to(
      sim, dt, expected_t_stop,
      [&](Vec3& wa, Vec3& wb) {
        wa = sim.particles.angular_velocity_rad_per_s[0];
        wb = {};
      },
      out);
  return out;
}

/// Hertz: F = 4/3 E* sqrt(R*) delta^(3/2); E* = E/(2(1 - nu^2)) for two bodies of one
/// material (the plane here is of the grain's material too).
double hertz_force(double effective_youngs_Pa, double effective_radius_m) {
  return 4.0 / 3.0 * effective_youngs_Pa * std::sqrt(effective_radius_m) * std::pow(kOverlap, 1.5);
}

double stop_time(double force_N, double arm_m) {
  const SphereMaterial m = rolling_grain();
  const double inertia = 0.4 * sphere_mass(m, kRadius) * kRadius * kRadius;
  return kOmega0 * inertia / (m.rolling_friction * force_N * arm_m);
}

/// omega(t) = omega0 (1 - t/t_stop) at the first reading, then stopped.
void expect_spin_down(const SpinRun& run, const Vec3& half, const Vec3& late, const Vec3& omega0) {
  const Vec3 expected = omega0 * (1.0 - run.half_fraction);
  EXPECT_NEAR(half.x, expected.x, 1e-3 * kOmega0);
  EXPECT_NEAR(half.y, expected.y, 1e-3 * kOmega0);
  EXPECT_NEAR(half.z, expected.z, 1e-3 * kOmega0);
  EXPECT_LT(norm(late), 1e-9 * kOmega0);
}

// Both spheres spin the same way about y (their surfaces slide past each other, but
// without friction only rolling acts): no relative spin, so the relative-spin model
// leaves them alone; EDEM's model slows each with arm R - delta/2.
TEST(RollingModels, SameSpinsAreFreeUnderRelativeSpinAndSlowedUnderOwnSpin) {
  const SphereMaterial m = rolling_grain();
  const double force = hertz_force(effective_youngs_modulus(m), 0.5 * kRadius);
  const Vec3 spin{0, kOmega0, 0};
  const double t_own = stop_time(force, kRadius - 0.5 * kOverlap);
  const SpinRun own = two_spheres(RollingModel::own_spin, spin, spin, t_own);
  expect_spin_down(own, own.half_a, own.late_a, spin);
  expect_spin_down(own, own.half_b, own.late_b, spin);
  const SpinRun relative = two_spheres(RollingModel::relative_spin, spin, spin, t_own);
  EXPECT_EQ(relative.late_a.y, kOmega0);
  EXPECT_EQ(relative.late_b.y, kOmega0);
}

// Opposite spins about y roll the two surfaces on each other (as gears): the relative
// spin is 2 omega0; relative-spin torque mu_r F R* on each (R* = R/2), own-spin
// mu_r F (R - delta/2): EDEM's model stops them in about half the time.
TEST(RollingModels, OppositeSpinsStopAtEachModelsTime) {
  const SphereMaterial m = rolling_grain();
  const double force = hertz_force(effective_youngs_modulus(m), 0.5 * kRadius);
  const Vec3 spin{0, kOmega0, 0};
  const SpinRun relative = two_spheres(RollingModel::relative_spin, spin, -1.0 * spin, stop_time(force, 0.5 * kRadius));
  expect_spin_down(relative, relative.half_a, relative.late_a, spin);
  expect_spin_down(relative, relative.half_b, relative.late_b, -1.0 * spin);
  const SpinRun own =
      two_spheres(RollingModel::own_spin, spin, -1.0 * spin, stop_time(force, kRadius - 0.5 * kOverlap));
  expect_spin_down(own, own.half_a, own.late_a, spin);
  expect_spin_down(own, own.half_b, own.late_b, -1.0 * spin);
}

// A twist about the normal (x): the relative-spin model drops the normal part, EDEM's
// resists the whole spin.
TEST(RollingModels, TwistAboutTheNormalIsResistedOnlyByOwnSpin) {
  const SphereMaterial m = rolling_grain();
  const double force = hertz_force(effective_youngs_modulus(m), 0.5 * kRadius);
  const Vec3 twist{kOmega0, 0, 0};
  const double t_own = stop_time(force, kRadius - 0.5 * kOverlap);
  const SpinRun own = two_spheres(RollingModel::own_spin, twist, -1.0 * twist, t_own);
  expect_spin_down(own, own.half_a, own.late_a, twist);
  expect_spin_down(own, own.half_b, own.late_b, -1.0 * twist);
  const SpinRun relative = two_spheres(RollingModel::relative_spin, twist, -1.0 * twist, t_own);
  EXPECT_EQ(relative.late_a.x, kOmega0);
  EXPECT_EQ(relative.late_b.x, -kOmega0);
}

// At a wall: R* = R for the relative model, arm R - delta for EDEM's (the contact point
// is on the wall's surface); the plane is of the grain's material, E* = E/(2(1 - nu^2)).
TEST(RollingModels, SphereSpinningOnAPlaneStopsAtEachModelsTime) {
  const SphereMaterial m = rolling_grain();
  const double force = hertz_force(effective_youngs_modulus(m), kRadius);
  const Vec3 spin{0, kOmega0, 0};
  const SpinRun relative = sphere_on_plane(RollingModel::relative_spin, spin, stop_time(force, kRadius));
  expect_spin_down(relative, relative.half_a, relative.late_a, spin);
  const SpinRun own = sphere_on_plane(RollingModel::own_spin, spin, stop_time(force, kRadius - kOverlap));
  expect_spin_down(own, own.half_a, own.late_a, spin);
}

}  // namespace
}  // namespace regodem::testing
