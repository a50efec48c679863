// Particles that leave the domain (SimulationSettings::lost_particles): `stop` ends the
// run with an error; `remove` takes them out, with their bonds and contact history, and
// books their heat as gone, while the rest of the run goes on exactly as if they had
// never been there. A bonded pair is thrown out of a box in which a sphere rolls on a
// wall (a loaded tangential spring) and a bonded, conducting pair rests beside it. The
// box stands upside down (gravity +z, the wall on top) so that the thrown pair leaves
// through the bottom: the neighbour sort puts it first, and removing it shifts every
// other particle's index, which a history kept by index would get wrong.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <numbers>
#include <vector>

#include "core/error.hpp"
#include "physics_fixtures.hpp"

namespace regodem::testing {
namespace {

constexpr double kRadius = 1.0e-3;
constexpr double kCeiling_m = 0.05;

struct Outcome {
  std::vector<Vec3> position, velocity, spin;
  std::vector<double> temperature;
  std::size_t particles = 0;
  std::uint64_t lost = 0;
  BondCounts bonds;
  double energy_imbalance_J = 0.0, thermal_energy_J = 0.0;
};

Outcome run(bool with_thrown_pair, LostParticles policy, int steps) {
  SphereMaterial m;
  m.sliding_friction = 0.5;
  const double dt = 0.2 * rayleigh_time_for(m, kRadius);
  const double tilt = 10.0 * std::numbers::pi / 180.0;  // gravity tilted: the spheres roll along x
  SimulationSettings s = settings_for(kRadius, dt, {9.81 * std::sin(tilt), 0.0, 9.81 * std::cos(tilt)});
  s.heat.enabled = true;
  s.lost_particles = policy;
  WallSet walls;
  walls.add_plane(walls.add_body("ceiling", {}), {0, 0, kCeiling_m}, {0, 0, -1}, 0);
  Simulation sim(one_material(m), walls, s);
  const double z = kCeiling_m - kRadius;
  sim.add_particle(sphere({0.0, 0.0, z}, {}, kRadius, m.density, 150.0));             // rolls alone
  sim.add_particle(sphere({0.02, -0.995 * kRadius, z}, {}, kRadius, m.density, 100.0));      // bonded pair ...
  sim.add_particle(sphere({0.02, 0.995 * kRadius, z}, {}, kRadius, m.density, 300.0));       // ... conducting
  if (with_thrown_pair) {  // a bonded pair along z, flying down out of the box (D leaves first)
    sim.add_particle(sphere({-0.03, 0.03, -kRadius}, {0, 0, -2.0}, kRadius, m.density, 50.0));
    sim.add_particle(sphere({-0.03, 0.03, kRadius}, {0, 0, -2.0}, kRadius, m.density, 400.0));
  }
  BondParameters bond;
  bond.normal_stiffness_Pa_per_m = 1e11;
  bond.shear_stiffness_Pa_per_m = 4e10;
  bond.tensile_strength_Pa = bond.shear_strength_Pa = 1e9;
  sim.configure_bonds({bond}, {0});
  EXPECT_EQ(sim.form_bonds(0.01), with_thrown_pair ? 2u : 1u);
  sim.advance(static_cast<std::uint64_t>(steps));
  Outcome out;
  out.particles = sim.particles.size();
  for (ParticleId id = 0; id < 3; ++id)
    for (std::size_t i = 0; i < sim.particles.size(); ++i)
      if (sim.particles.id[i] == id) {
        out.position.push_back(sim.particles.position_m[i]);
        out.velocity.push_back(sim.particles.velocity_m_per_s[i]);
        out.spin.push_back(sim.particles.angular_velocity_rad_per_s[i]);
        out.temperature.push_back(sim.particles.temperature_K[i]);
      }
  out.lost = sim.lost_particle_count();
  out.bonds = sim.bond_counts();
  out.energy_imbalance_J = sim.energy_imbalance_J();
  out.thermal_energy_J = sim.thermal_energy_J();
  return out;
}

// At 2 m/s against g the pair travels 0.2 m, the box bottom is 0.1 m away: both are out
// within ~0.06 s, ~300 steps apart; 20,000 steps (~0.07 s) see both go.
constexpr int kSteps = 20000;

TEST(LostParticles, StopPolicyEndsTheRunWithAnEscapeError) {
  try {
    run(true, LostParticles::stop, kSteps);
    FAIL() << "the thrown pair left the domain without an error";
  } catch (const SimulationError& e) {
    EXPECT_NE(std::string(e.what()).find("left the domain"), std::string::npos) << e.what();
  }
}

TEST(LostParticles, RemovedParticlesTakeTheirBondsAndHeatAndLeaveTheRestExactlyAsWithout) {
  const Outcome with = run(true, LostParticles::remove, kSteps);
  const Outcome without = run(false, LostParticles::remove, kSteps);
  EXPECT_EQ(with.particles, 3u);
  EXPECT_EQ(with.lost, 2u);
  EXPECT_EQ(without.lost, 0u);
  // The thrown pair's bond went with it, neither intact nor counted as broken.
  EXPECT_EQ(with.bonds.intact, 1u);
  EXPECT_EQ(with.bonds.broken(), 0u);
  // The ledger lets the removed heat go: the balance still closes to round-off.
  EXPECT_LT(std::abs(with.energy_imbalance_J), 1e-12 * with.thermal_energy_J);
  // The resting pair exchanged heat, and the rolling sphere's spring is loaded, so a
  // lost history or a mixed-up index after the removal would show here: bitwise equal.
  ASSERT_EQ(with.position.size(), 3u);
  ASSERT_EQ(without.position.size(), 3u);
  EXPECT_GT(without.temperature[1], 100.0 + 1e-3);
  EXPECT_GT(std::abs(without.spin[0].y), 1.0);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(with.position[k], without.position[k]) << "particle " << k;
    EXPECT_EQ(with.velocity[k], without.velocity[k]) << "particle " << k;
    EXPECT_EQ(with.spin[k], without.spin[k]) << "particle " << k;
    EXPECT_EQ(with.temperature[k], without.temperature[k]) << "particle " << k;
  }
}

}  // namespace
}  // namespace regodem::testing
