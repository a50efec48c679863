// Conservation in an elastic, frictionless collision (e = 1): the energy error of
// velocity Verlet is second order in the step, and pair forces conserve momentum to
// round-off even with friction and rotation.
#include <gtest/gtest.h>

#include <cmath>

#include "physics_fixtures.hpp"

namespace regodem::testing {
namespace {

constexpr double kRadius = 1.0e-3;

struct EnergyErrors {
  double after_collision;   // |E_after - E_before| / E_before
  double largest_during;    // max over the collision of |E(t) - E_before| / E_before
};

/// Energy errors of a head-on elastic collision at the given fraction of the Rayleigh
/// time. E = kinetic + Hertz elastic energy U = 8/15 E* sqrt(R*) delta^{5/2}.
EnergyErrors energy_errors(double rayleigh_fraction) {
  SphereMaterial m;
  m.restitution = 1.0;
  const double dt = rayleigh_fraction * rayleigh_time_for(m, kRadius);
  Simulation sim(one_material(m), WallSet{}, settings_for(kRadius, dt));
  sim.add_particle(sphere({-1.01 * kRadius, 0, 0}, {0.05, 0, 0}, kRadius, m.density));
  sim.add_particle(sphere({1.01 * kRadius, 0, 0}, {-0.05, 0, 0}, kRadius, m.density));
  const double e_star = effective_youngs_modulus(m);
  auto total_energy = [&] {
    const double overlap = 2.0 * kRadius - norm(sim.particles.position_m[1] - sim.particles.position_m[0]);
    const double elastic =
        overlap > 0.0 ? 8.0 / 15.0 * e_star * std::sqrt(kRadius / 2.0) * std::pow(overlap, 2.5) : 0.0;
    return sim.translational_kinetic_energy_J() + elastic;
  };
  const double before = total_energy();
  EnergyErrors errors{0.0, 0.0};
  bool touched = false;
  for (int s = 0; s < 10'000'000; ++s) {
    sim.step();
    const bool touching = sim.contact_statistics().particle_contacts > 0;
    errors.largest_during = std::max(errors.largest_during, std::abs(total_energy() - before) / before);
    touched = touched || touching;
    if (touched && !touching) break;
  }
  errors.after_collision = std::abs(total_energy() - before) / before;
  return errors;
}

// Step 0.01 T_R: the energy after the collision within 1e-6 of the energy before,
// and never off by more than 1e-4 during it.
TEST(Energy, ElasticCollisionConservesEnergy) {
  const EnergyErrors e = energy_errors(0.01);
  EXPECT_LT(e.after_collision, 1e-6);
  EXPECT_LT(e.largest_during, 1e-4);
}

// Halving the step cuts the energy error during the collision about fourfold
// (velocity Verlet is second order); accepted 3.5x-4.5x.
TEST(Energy, ErrorIsSecondOrderInTimeStep) {
  const double coarse = energy_errors(0.02).largest_during, fine = energy_errors(0.01).largest_during;
  ASSERT_GT(fine, 0.0);
  EXPECT_GT(coarse / fine, 3.5);
  EXPECT_LT(coarse / fine, 4.5);
}

// An oblique, rough collision with spin: total momentum unchanged to 1e-14 of its
// scale (round-off), step 0.05 T_R.
TEST(Momentum, ConservedInFrictionalParticleContact) {
  SphereMaterial m;
  m.restitution = 0.5;
  m.sliding_friction = 0.5;
  m.rolling_friction = 0.2;
  const double dt = 0.05 * rayleigh_time_for(m, kRadius);
  Simulation sim(one_material(m), WallSet{}, settings_for(kRadius, dt));
  NewParticle a = sphere({-1.01 * kRadius, 0.5 * kRadius, 0}, {0.08, 0, 0.01}, kRadius, m.density);
  a.angular_velocity_rad_per_s = {10, -30, 50};
  NewParticle b = sphere({1.01 * kRadius, -0.5 * kRadius, 0}, {-0.05, 0.02, 0}, 0.7 * kRadius, m.density);
  sim.add_particle(a);
  sim.add_particle(b);
  auto momentum = [&sim] {
    Vec3 p;
    for (std::size_t i = 0; i < sim.particles.size(); ++i)
      p += sim.particles.velocity_m_per_s[i] * sim.particles.mass_kg[i];
    return p;
  };
  const Vec3 before = momentum();
  const double scale = sim.particles.mass_kg[0] * 0.1;
  bool touched = false;
  for (int s = 0; s < 100000; ++s) {
    sim.step();
    touched = touched || sim.contact_statistics().particle_contacts > 0;
  }
  ASSERT_TRUE(touched);
  EXPECT_LT(norm(momentum() - before), 1e-14 * scale);
}

}  // namespace
}  // namespace regodem::testing
