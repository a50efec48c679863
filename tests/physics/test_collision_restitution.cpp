// Head-on collisions: rebound speed ratio = restitution coefficient (DESIGN.md
// section 2: unclamped Hertz + restitution damping reproduces e exactly in the
// continuum limit), Hertz contact duration, and convergence with the time step.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "physics_fixtures.hpp"

namespace regodem::testing {
namespace {

constexpr double kRadius = 1.0e-3;
constexpr double kSpeed = 0.1;

struct CollisionResult {
  double speed_ratio;
  double duration_s;
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
  return {relative / kSpeed, contact_time};
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
  return {sim.particles.velocity_m_per_s[0].z / kSpeed, contact_time};
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
  EXPECT_NEAR(sphere_plane(0.99, 0.02).duration_s, expected_wall, 0.02 * expected_wall);
}

}  // namespace
}  // namespace regodem::testing
