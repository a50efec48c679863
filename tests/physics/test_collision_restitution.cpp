// Head-on collisions: rebound speed ratio = restitution coefficient (DESIGN.md
// section 2: unclamped Hertz + restitution damping reproduces e exactly in the
// continuum limit), Hertz contact duration, and convergence with the time step; then
// the same between two materials, with the tangential (Mindlin) period on a plane of
// another material, so that the mixing of E*, G*, m* and R* is checked by the dynamics.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "physics_fixtures.hpp"

namespace regodem::testing {
namespace {

constexpr double kRadius = 1.0e-3;
constexpr double kSpeed = 0.1;

struct CollisionResult {
  double speed_ratio;
  double duration_s;
  ImpactRecord fastest_impact;
};

/// Two equal spheres approach head-on at +-kSpeed/2; returns |v_rel after| / |v_rel before|.
CollisionResult sphere_sphere(double e, double rayleigh_fraction) {
  SphereMaterial m;
  m.restitution = e;
  const double dt = rayleigh_fraction * rayleigh_time_for(m, kRadius);
  Simulation sim(one_material(m), WallSet{}, settings_for(kRadius, dt));
  const double gap = 0.01 * kRadius;
  sim.add_particle(sphere({-kRadius - gap, 0, 0}, {0.5 * kSpeed, 0, 0}, kRadius, m.density));
  sim.add_particle(sphere({kRadius + gap, 0, 0}, {-0.5 * kSpeed, 0, 0}, kRadius, m.density));
  double contact_time = 0.0;
  bool touched = false;
  for (int s = 0; s < 10'000'000; ++s) {
    sim.step();
    const bool touching = sim.contact_statistics().particle_contacts > 0;
    if (touching) contact_time += dt, touched = true;
    if (touched && !touching) break;
  }
  const auto& v = sim.particles.velocity_m_per_s;
  // Particle order may change with spatial sorting: use the x components' difference.
  const double relative = std::abs(v[0].x - v[1].x);
  return {relative / kSpeed, contact_time, sim.fastest_impact()};
}

CollisionResult sphere_plane(double e, double rayleigh_fraction) {
  SphereMaterial m;
  m.restitution = e;
  const double dt = rayleigh_fraction * rayleigh_time_for(m, kRadius);
  WallSet walls;
  walls.add_plane(walls.add_body("floor", {}), {0, 0, 0}, {0, 0, 1}, 0);
  Simulation sim(one_material(m), walls, settings_for(kRadius, dt));
  sim.add_particle(sphere({0, 0, kRadius * 1.01}, {0, 0, -kSpeed}, kRadius, m.density));
  double contact_time = 0.0;
  bool touched = false;
  for (int s = 0; s < 10'000'000; ++s) {
    sim.step();
    const bool touching = sim.contact_statistics().wall_contacts > 0;
    if (touching) contact_time += dt, touched = true;
    if (touched && !touching) break;
  }
  return {sim.particles.velocity_m_per_s[0].z / kSpeed, contact_time, sim.fastest_impact()};
}

/// Hertz contact time of an elastic impact: t_c = 2.9432 delta_max / v with
/// delta_max = (15 m* v^2 / (16 E* sqrt(R*)))^{2/5} (Johnson, Contact Mechanics 11.2).
double hertz_duration_s(double effective_mass, double effective_youngs, double effective_radius, double speed) {
  const double delta_max =
      std::pow(15.0 * effective_mass * speed * speed / (16.0 * effective_youngs * std::sqrt(effective_radius)), 0.4);
  return 2.9432 * delta_max / speed;
}

class RestitutionCases : public ::testing::TestWithParam<double> {};

// Step 0.05 T_R; tolerance 1 % (the acceptance bound).
TEST_P(RestitutionCases, SphereSphereReboundMatchesRestitution) {
  const double e = GetParam();
  EXPECT_NEAR(sphere_sphere(e, 0.05).speed_ratio, e, 0.01 * e);
}

TEST_P(RestitutionCases, SpherePlaneReboundMatchesRestitution) {
  const double e = GetParam();
  EXPECT_NEAR(sphere_plane(e, 0.05).speed_ratio, e, 0.01 * e);
}

INSTANTIATE_TEST_SUITE_P(SeveralCoefficients, RestitutionCases, ::testing::Values(0.24, 0.5, 0.9));

// The error in e falls as the step shrinks (0.2 -> 0.05 -> 0.0125 of T_R).
TEST(Restitution, ErrorFallsWithTimeStep) {
  const double e = 0.24;
  const double coarse = std::abs(sphere_sphere(e, 0.2).speed_ratio - e);
  const double medium = std::abs(sphere_sphere(e, 0.05).speed_ratio - e);
  const double fine = std::abs(sphere_sphere(e, 0.0125).speed_ratio - e);
  EXPECT_LT(medium, coarse);
  EXPECT_LT(fine, medium);
}

// e close to 1: duration within 2 % of Hertz theory, at a step of 0.02 T_R.
TEST(Restitution, ContactDurationMatchesHertz) {
  SphereMaterial m;
  const double e_star = effective_youngs_modulus(m);
  const double mass = sphere_mass(m, kRadius);
  const double expected_pair = hertz_duration_s(mass / 2.0, e_star, kRadius / 2.0, kSpeed);
  EXPECT_NEAR(sphere_sphere(0.99, 0.02).duration_s, expected_pair, 0.02 * expected_pair);
  const double expected_wall = hertz_duration_s(mass, e_star, kRadius, kSpeed);
  const double wall_s = sphere_plane(0.99, 0.02).duration_s;
  EXPECT_NEAR(wall_s, expected_wall, 0.02 * expected_wall);
  // The engine's own Hertz time (sim/time_step.hpp), which `validate` uses for moving
  // walls' impacts, against the same collision.
  const double engine_s = hertz_contact_time_s(mass, kRadius, e_star, kSpeed);
  EXPECT_NEAR(wall_s, engine_s, 0.02 * engine_s);
}

// The run's fastest impact (sim/impact_record.hpp) is the collision's own: the speed
// the bodies met at (no gravity: exactly kSpeed until the first contact force, so to
// 1e-12), the pair or the wall, and a Hertz time that is the contact's measured
// duration, to the 2 % of the test above.
TEST(Restitution, TheRunsFastestImpactIsTheCollision) {
  const CollisionResult pair = sphere_sphere(0.99, 0.02);
  ASSERT_TRUE(pair.fastest_impact.seen());
  EXPECT_EQ(pair.fastest_impact.wall_body, -1);
  EXPECT_NEAR(pair.fastest_impact.approach_speed_m_per_s, kSpeed, 1e-12 * kSpeed);
  EXPECT_NEAR(pair.fastest_impact.contact_time_s(), pair.duration_s, 0.02 * pair.duration_s);
  const CollisionResult wall = sphere_plane(0.99, 0.02);
  ASSERT_TRUE(wall.fastest_impact.seen());
  EXPECT_EQ(wall.fastest_impact.wall_body, 0);
  EXPECT_NEAR(wall.fastest_impact.approach_speed_m_per_s, kSpeed, 1e-12 * kSpeed);
  EXPECT_NEAR(wall.fastest_impact.contact_time_s(), wall.duration_s, 0.02 * wall.duration_s);
}

// ---- Two materials (docs/physics.md, "Mixing") ----
// A soft grain (material 0) meets a stiffer, denser, smaller grain and a plane of that
// stiffer material (material 1). The constants are far enough apart that a wrong mixing
// misses by much more than the tolerances: E* of the soft body alone is 46 % low (t_c
// 28 % long); m* or R* of one sphere alone moves t_c by 10-44 %; G* of the soft body alone
// moves the tangential period by 35 %. E*, G*, m* and R* are computed here from the
// material constants (physics_fixtures.hpp), not taken from the contact code.

constexpr double kStiffRadius = 0.6e-3;

SphereMaterial soft_grain() {
  SphereMaterial m;
  m.density = 2500.0;
  m.shear_modulus = 1.0e8;
  m.poisson = 0.25;
  return m;
}

SphereMaterial stiff_grain() {  // steel-like density and Poisson ratio, 10x the shear modulus
  SphereMaterial m;
  m.density = 7800.0;
  m.shear_modulus = 1.0e9;
  m.poisson = 0.35;
  return m;
}

PairProperties soft_stiff_pair(double e) {
  PairProperties pair;
  pair.restitution = e;
  pair.sliding_friction = 0.0;
  pair.rolling_friction = 0.0;
  return pair;
}

/// Steps until the first contact has opened again; returns the time spent in contact.
double time_in_contact(Simulation& sim, bool with_wall) {
  double contact_time = 0.0;
  bool touched = false;
  for (int s = 0; s < 10'000'000; ++s) {
    sim.step();
    const ContactStatistics& c = sim.contact_statistics();
    const bool touching = (with_wall ? c.wall_contacts : c.particle_contacts) > 0;
    if (touching) contact_time += sim.time_step_s(), touched = true;
    if (touched && !touching) break;
  }
  return contact_time;
}

/// The soft sphere falls (no gravity) onto a plane of the stiff material at kSpeed.
CollisionResult soft_sphere_on_stiff_plane(double e, double rayleigh_fraction) {
  const SphereMaterial soft = soft_grain(), stiff = stiff_grain();
  const double dt = rayleigh_fraction * rayleigh_time_for(soft, kRadius);
  WallSet walls;
  walls.add_plane(walls.add_body("floor", {}), {0, 0, 0}, {0, 0, 1}, 1);
  Simulation sim(two_materials(soft, stiff, soft_stiff_pair(e)), walls, settings_for(kRadius, dt));
  sim.add_particle(sphere({0, 0, kRadius * 1.01}, {0, 0, -kSpeed}, kRadius, soft.density));
  const double duration = time_in_contact(sim, true);
  return {sim.particles.velocity_m_per_s[0].z / kSpeed, duration, sim.fastest_impact()};
}

/// The soft sphere meets the smaller stiff one head-on, relative speed kSpeed, zero
/// total momentum; returns |v_rel after| / kSpeed.
CollisionResult soft_sphere_on_stiff_sphere(double e, double rayleigh_fraction) {
  const SphereMaterial soft = soft_grain(), stiff = stiff_grain();
  const double dt = rayleigh_fraction * std::min(rayleigh_time_for(soft, kRadius),
                                                 rayleigh_time_for(stiff, kStiffRadius));
  const double m_soft = sphere_mass(soft, kRadius), m_stiff = sphere_mass(stiff, kStiffRadius);
  Simulation sim(two_materials(soft, stiff, soft_stiff_pair(e)), WallSet{}, settings_for(kStiffRadius, dt));
  const double gap = 0.01 * kStiffRadius;
  sim.add_particle(
      sphere({-kRadius - gap, 0, 0}, {kSpeed * m_stiff / (m_soft + m_stiff), 0, 0}, kRadius, soft.density));
  NewParticle hard = sphere({kStiffRadius + gap, 0, 0}, {-kSpeed * m_soft / (m_soft + m_stiff), 0, 0},
                            kStiffRadius, stiff.density);
  hard.material = 1;
  sim.add_particle(hard);
  const double duration = time_in_contact(sim, false);
  const auto& v = sim.particles.velocity_m_per_s;  // order-free: the x components' difference
  return {std::abs(v[0].x - v[1].x) / kSpeed, duration, sim.fastest_impact()};
}

class MixedRestitutionCases : public ::testing::TestWithParam<double> {};

// Rebound speed ratio = e with the damping's m* and S_n (from E*, R*) of the mixed pair.
// Step 0.05 T_R of the faster particle; tolerance 1 %, as RestitutionCases.
TEST_P(MixedRestitutionCases, SoftSphereOnStiffPlaneReboundsWithRestitution) {
  const double e = GetParam();
  EXPECT_NEAR(soft_sphere_on_stiff_plane(e, 0.05).speed_ratio, e, 0.01 * e);
}

TEST_P(MixedRestitutionCases, SoftSphereOnSmallerStiffSphereReboundsWithRestitution) {
  const double e = GetParam();
  EXPECT_NEAR(soft_sphere_on_stiff_sphere(e, 0.05).speed_ratio, e, 0.01 * e);
}

INSTANTIATE_TEST_SUITE_P(TwoCoefficients, MixedRestitutionCases, ::testing::Values(0.3, 0.8));

// Hertz duration t_c = 2.9432 delta_max / v (Johnson 1985, 11.2) with the mixed
// constants: wall R* = R, m* = m; pair 1/R* = 1/R_a + 1/R_b, 1/m* = 1/m_a + 1/m_b;
// 1/E* = (1 - nu_a^2)/E_a + (1 - nu_b^2)/E_b in both. e = 0.99, step 0.02 T_R;
// tolerance 2 %, as Restitution.ContactDurationMatchesHertz.
TEST(MixedMaterials, ContactDurationMatchesHertzWithTheMixedConstants) {
  const SphereMaterial soft = soft_grain(), stiff = stiff_grain();
  const double e_star = effective_youngs_modulus(soft, stiff);
  const double m_soft = sphere_mass(soft, kRadius), m_stiff = sphere_mass(stiff, kStiffRadius);

  const double expected_wall = hertz_duration_s(m_soft, e_star, kRadius, kSpeed);
  EXPECT_NEAR(soft_sphere_on_stiff_plane(0.99, 0.02).duration_s, expected_wall, 0.02 * expected_wall);

  const double pair_mass = m_soft * m_stiff / (m_soft + m_stiff);
  const double pair_radius = kRadius * kStiffRadius / (kRadius + kStiffRadius);
  const double expected_pair = hertz_duration_s(pair_mass, e_star, pair_radius, kSpeed);
  EXPECT_NEAR(soft_sphere_on_stiff_sphere(0.99, 0.02).duration_s, expected_pair, 0.02 * expected_pair);
}

// The soft sphere rests under gravity on a plane of the stiff material (F_n = m g,
// delta from Hertz with the mixed E*) and is set sliding sideways slowly enough that
// the Mindlin spring S_t = 8 G* sqrt(R delta) never reaches the Coulomb limit (peak
// 0.1 mu m g). The contact point, at arm r = R - delta below the centre, then oscillates
// with omega^2 = S_t (1/m + r^2/I), I = 2/5 m R^2, the sphere rolling on at 5/7 of its
// start speed. e = 1, so nothing damps it (beta = 0). Measured from the zero crossings
// of the wall's tangential reaction over about 5 periods; tolerance 0.5 % (velocity
// Verlet's frequency error (omega dt)^2/24 is 4e-5 at 0.05 T_R; a crossing is
// interpolated to well under a step, 1/200 of a period).
TEST(MixedMaterials, TangentialOscillationOnAPlaneOfAnotherMaterialHasTheMindlinPeriod) {
  const SphereMaterial soft = soft_grain(), stiff = stiff_grain();
  constexpr double kFriction = 1.0, kGravity = 9.81;
  PairProperties pair = soft_stiff_pair(1.0);
  pair.sliding_friction = kFriction;
  const double mass = sphere_mass(soft, kRadius);
  const double weight = mass * kGravity;
  const double overlap = hertz_overlap(weight, effective_youngs_modulus(soft, stiff), kRadius);
  const double spring = 8.0 * effective_shear_modulus(soft, stiff) * std::sqrt(kRadius * overlap);
  const double arm = kRadius - overlap;
  const double inverse_mobility_mass = 1.0 / mass + arm * arm / (0.4 * mass * kRadius * kRadius);
  const double omega = std::sqrt(spring * inverse_mobility_mass);
  const double expected_period = 2.0 * std::numbers::pi / omega;
  // Peak spring force S_t v0 / omega = 0.1 mu m g.
  const double start_speed = 0.1 * kFriction * weight * omega / spring;

  const double dt = 0.05 * rayleigh_time_for(soft, kRadius);
  WallSet walls;
  walls.add_plane(walls.add_body("floor", {}), {0, 0, 0}, {0, 0, 1}, 1);
  Simulation sim(two_materials(soft, stiff, pair), walls, settings_for(kRadius, dt, {0, 0, -kGravity}));
  sim.add_particle(sphere({0, 0, kRadius - overlap}, {start_speed, 0, 0}, kRadius, soft.density));
  std::vector<double> crossings;
  double previous = 0.0, peak = 0.0;
  const int steps = static_cast<int>(std::ceil(5.2 * expected_period / dt));
  for (int s = 0; s < steps; ++s) {
    sim.step();
    const double force = sim.walls.bodies[0].force_N.x;
    peak = std::max(peak, std::abs(force));
    if (s > 0 && (force > 0.0) != (previous > 0.0))
      crossings.push_back(sim.time_s() - dt * force / (force - previous));
    previous = force;
  }
  ASSERT_GE(crossings.size(), 9u);
  const double measured_period =
      2.0 * (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  EXPECT_NEAR(measured_period / expected_period, 1.0, 0.005);
  EXPECT_LT(peak, kFriction * weight);  // stuck throughout: the Coulomb limit never cut the spring
  EXPECT_NEAR(sim.walls.bodies[0].force_N.z / weight, -1.0, 1e-3);  // the plane carries m g
}

}  // namespace
}  // namespace regodem::testing
