// The energy ledger (DESIGN.md section 2, "Energy"): in a closed adiabatic box the
// thermal energy of moving, colliding particles changes only by round-off; with
// friction heating on, by exactly the friction heat booked, which equals the kinetic
// energy that sliding dissipates.
#include <gtest/gtest.h>

#include <cmath>

#include "core/rng.hpp"
#include "physics_fixtures.hpp"

namespace regodem::testing {
namespace {

constexpr double kRadius = 0.5e-3;

struct BoxRun {
  double worst_step_change = 0.0;  // largest |change of imbalance| in one step / energy
  double final_imbalance = 0.0;    // / energy
  double generated_heat_J = 0.0;
  double energy_J = 0.0;
  double temperature_spread_start = 0.0, temperature_spread_end = 0.0;
};

/// 1,000 particles with random temperatures (100-400 K) and velocities, colliding in
/// a closed adiabatic box under gravity, with a time-scale factor that makes heat move.
BoxRun closed_box(bool friction_heating, int steps) {
  SphereMaterial m;
  m.restitution = 0.5;
  m.sliding_friction = 0.5;
  m.rolling_friction = 0.1;
  const double dt = 0.1 * rayleigh_time_for(m, kRadius);
  const double half = 5.5e-3;
  WallSet walls;
  const std::uint32_t box = walls.add_body("box", {});
  for (int axis = 0; axis < 3; ++axis)
    for (const double side : {-1.0, 1.0}) {
      Vec3 normal{};
      (axis == 0 ? normal.x : axis == 1 ? normal.y : normal.z) = -side;
      walls.add_plane(box, -half * normal, normal, 0);
    }
  SimulationSettings settings = settings_for(kRadius, dt, {0, 0, -9.81}, 0.01);
  settings.heat.enabled = true;
  settings.heat.time_scale_factor = 1e5;
  settings.heat.friction_heating = friction_heating;
  Simulation sim(one_material(m), walls, settings);
  Rng rng(5);
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j)
      for (int k = 0; k < 10; ++k) {
        const Vec3 x{(i - 4.5) * 1.05e-3, (j - 4.5) * 1.05e-3, (k - 4.5) * 1.05e-3};
        const Vec3 v{rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2)};
        sim.add_particle(sphere(x, v, kRadius * rng.uniform(0.9, 1.0), m.density, rng.uniform(100.0, 400.0)));
      }
  auto spread = [&] {
    double sum = 0.0, sum2 = 0.0;
    for (double t : sim.particles.temperature_K) sum += t, sum2 += t * t;
    const double n = static_cast<double>(sim.particles.size());
    return std::sqrt(sum2 / n - sum * sum / (n * n));
  };
  BoxRun r;
  r.temperature_spread_start = spread();
  double previous = sim.energy_imbalance_J();
  for (int s = 0; s < steps; ++s) {
    sim.step();
    const double imbalance = sim.energy_imbalance_J();
    r.worst_step_change = std::max(r.worst_step_change, std::abs(imbalance - previous) / sim.thermal_energy_J());
    previous = imbalance;
  }
  r.energy_J = sim.thermal_energy_J();
  r.final_imbalance = sim.energy_imbalance_J() / r.energy_J;
  r.generated_heat_J = sim.thermal_ledger().generated_heat_J;
  r.temperature_spread_end = spread();
  return r;
}

// The bound: below 1e-12 relative per step (round-off only).
TEST(HeatEnergyBalance, ClosedAdiabaticBoxConservesEnergyToRoundOff) {
  const BoxRun r = closed_box(false, 1500);
  EXPECT_LT(r.worst_step_change, 1e-12);
  EXPECT_LT(std::abs(r.final_imbalance), 1e-12);
  EXPECT_LT(r.temperature_spread_end, 0.95 * r.temperature_spread_start);  // heat did move
}

TEST(HeatEnergyBalance, FrictionHeatIsBookedAndConserved) {
  const BoxRun r = closed_box(true, 1500);
  EXPECT_GT(r.generated_heat_J, 0.0);
  EXPECT_LT(r.worst_step_change, 1e-12);
  EXPECT_LT(std::abs(r.final_imbalance), 1e-12);
}

/// A sphere launched sliding (no spin) on a plane under gravity: it slides until it
/// rolls at 5/7 of its speed, and friction dissipates m v0^2 / 7 (translational +
/// rotational kinetic energy lost). That is the heat the ledger must book; the wall's
/// share follows the partition (all of it to the particle at an adiabatic wall).
struct SlideResult {
  double generated_heat_J, expected_J, particle_heat_J, wall_heat_J;
};

SlideResult slide(WallThermalMode wall_mode, double partition, bool every_loss = false) {
  SphereMaterial m;
  m.restitution = 0.5;
  m.sliding_friction = 0.3;
  const double radius = 1.0e-3, v0 = 0.05;
  const double dt = 0.05 * rayleigh_time_for(m, radius);
  const double mass = sphere_mass(m, radius);
  const double overlap = hertz_overlap(mass * 9.81, effective_youngs_modulus(m), radius);
  WallSet walls;
  walls.add_plane(walls.add_body("floor", {}), {0, 0, 0}, {0, 0, 1}, 0);
  ThermalWall floor;
  floor.mode = wall_mode;
  floor.initial_temperature_K = 200.0;
  floor.heat_capacity_J_per_K = 1.0;
  floor.conductivity_W_per_mK = 0.0;  // isolate friction heat from conduction
  SimulationSettings settings = settings_for(radius, dt, {0, 0, -9.81}, 0.1);
  settings.heat.enabled = true;
  settings.heat.friction_heating = !every_loss;
  settings.heat.dissipation_heating = every_loss;
  settings.heat.friction_partition = partition;
  Simulation sim(one_material(m), walls, settings, {floor});
  sim.add_particle(sphere({0, 0, radius - overlap}, {v0, 0, 0}, radius, m.density, 200.0));
  // Sliding lasts 2 v0 / (7 mu g) ~ 5 ms; run twice that.
  const int steps = static_cast<int>(std::ceil(2.0 * 2.0 * v0 / (7.0 * 0.3 * 9.81) / dt));
  sim.advance(static_cast<std::uint64_t>(steps));
  const double particle_heat = mass * m.specific_heat * (sim.particles.temperature_K[0] - 200.0);
  return {sim.thermal_ledger().generated_heat_J, mass * v0 * v0 / 7.0, particle_heat,
          sim.wall_thermal_state[0].generated_heat_J};
}

// Friction heat equals the analytic dissipation within 1 % (the tangential spring's
// stored energy and the stick transition make up the difference); the split between
// particle and wall follows the partition to 1e-6 (the particle's share is read from a
// temperature rise of ~4e-7 K on 200 K, so round-off limits it to ~1e-8).
TEST(HeatEnergyBalance, SlidingFrictionHeatMatchesTheDissipatedKineticEnergy) {
  const SlideResult adiabatic = slide(WallThermalMode::adiabatic, 0.5);
  EXPECT_NEAR(adiabatic.generated_heat_J / adiabatic.expected_J, 1.0, 0.01);
  EXPECT_NEAR(adiabatic.particle_heat_J / adiabatic.generated_heat_J, 1.0, 1e-6);

  const SlideResult lumped = slide(WallThermalMode::lumped, 0.3);
  EXPECT_NEAR(lumped.generated_heat_J / lumped.expected_J, 1.0, 0.01);
  EXPECT_NEAR(lumped.particle_heat_J / lumped.generated_heat_J, 0.3, 1e-6);
  EXPECT_NEAR(lumped.wall_heat_J / lumped.generated_heat_J, 0.7, 1e-9);

  // Every loss as heat (the engine's dissipation heating): the same m v0^2 / 7 within
  // 1 % (the sphere starts at its static overlap: no normal damping to speak of). The
  // partition shares each contact's loss, its end-of-step part too (a fraction of a per
  // cent here): the wall's share to 1e-9, as above. (Held to 1e-3 while that part heated
  // the particle alone.)
  const SlideResult every_loss = slide(WallThermalMode::lumped, 0.3, true);
  EXPECT_NEAR(every_loss.generated_heat_J / every_loss.expected_J, 1.0, 0.01);
  EXPECT_NEAR(every_loss.wall_heat_J / every_loss.generated_heat_J, 0.7, 1e-9);
}

}  // namespace
}  // namespace regodem::testing
