// The per-particle thermal history through the simulation's heat update: a sphere at
// 100 K resting on a plate held at 500 K warms as T = 500 - 400 exp(-t/tau), tau = m c / G
// with G = 2 k a, a = (3 m g R / (4 E*))^(1/3) (paper Eq. 1-2). It crosses the -70 degC
// threshold at t_c = tau ln(400 / (500 - 203.15)); by t_end it has spent t_end - t_c
// above it. Checked within one step (coupled: the mechanical step; static bed: the
// heat step), both with tau resolved by 200 steps.
#include <cmath>

#include <gtest/gtest.h>

#include "measure/thermal_history.hpp"
#include "physics_fixtures.hpp"
#include "sim/static_heat_stepper.hpp"

namespace regodem {
namespace {

using namespace regodem::testing;

constexpr double kRadius = 0.5e-3;
constexpr double kWall_K = 500.0, kStart_K = 100.0;

struct PlateCase {
  double dt_s = 0.0, tau_s = 0.0, scale = 1.0;
};

ThermalWall fixed_at(double temperature_K) {
  ThermalWall w;
  w.mode = WallThermalMode::fixed;
  w.prescribed_temperature_K = TimeTable(temperature_K);
  return w;
}

/// A sphere on a plate under gravity, heat on with the history tracked, tau = 200 dt.
Simulation sphere_on_hot_plate(PlateCase& setup) {
  const SphereMaterial m;
  setup.dt_s = 0.1 * rayleigh_time_for(m, kRadius);
  const double weight = sphere_mass(m, kRadius) * 9.81;
  const double overlap = hertz_overlap(weight, effective_youngs_modulus(m), kRadius);
  const double a = std::cbrt(3.0 * weight * kRadius / (4.0 * effective_youngs_modulus(m)));
  const double tau_s1 = sphere_mass(m, kRadius) * m.specific_heat / (2.0 * m.conductivity * a);
  setup.scale = tau_s1 / (200.0 * setup.dt_s);
  setup.tau_s = tau_s1 / setup.scale;
  SimulationSettings s = settings_for(kRadius, setup.dt_s, {0, 0, -9.81}, 0.02);
  s.heat.enabled = true;
  s.heat.time_scale_factor = setup.scale;
  s.heat.track_thermal_history = true;
  WallSet walls;
  walls.add_plane(walls.add_body("plate", {}), {0, 0, 0}, {0, 0, 1}, 0);
  Simulation sim(one_material(m), walls, s, {fixed_at(kWall_K)});
  sim.add_particle(sphere({0, 0, kRadius - overlap}, {}, kRadius, m.density, kStart_K));
  return sim;
}

double analytic_time_above_s(double tau_s, double end_s) {
  return end_s - tau_s * std::log((kWall_K - kStart_K) / (kWall_K - kDefaultThermalThreshold_K));
}

TEST(ThermalHistory, CoupledHeatingCountsTheAnalyticTimeAboveTheThreshold) {
  PlateCase setup;
  Simulation sim = sphere_on_hot_plate(setup);
  const int steps = 200;  // one tau
  for (int k = 0; k < steps; ++k) sim.step();
  const double expected_s = analytic_time_above_s(setup.tau_s, sim.time_s());
  EXPECT_NEAR(sim.particles.time_above_threshold_s[0], expected_s, setup.dt_s);
  // Rising all the way: the peak is the present temperature.
  EXPECT_EQ(sim.particles.peak_temperature_K[0], sim.particles.temperature_K[0]);
  EXPECT_GT(sim.particles.peak_temperature_K[0], kDefaultThermalThreshold_K);
}

TEST(ThermalHistory, StaticBedHeatingCountsTheAnalyticTimeAboveTheThreshold) {
  PlateCase setup;
  Simulation sim = sphere_on_hot_plate(setup);
  Stage stage;
  stage.name = "heat";
  stage.heat_stepping = HeatStepping::static_explicit;
  stage.thermal_time_step_s = setup.tau_s / 200.0;
  stage.duration_s = setup.tau_s;
  StaticHeatStepper stepper(sim, stage);
  for (int k = 0; k < 200; ++k) stepper.advance(stage.thermal_time_step_s);
  EXPECT_NEAR(sim.particles.time_above_threshold_s[0], analytic_time_above_s(setup.tau_s, sim.time_s()),
              stage.thermal_time_step_s);
  EXPECT_EQ(sim.particles.peak_temperature_K[0], sim.particles.temperature_K[0]);
}

TEST(ThermalHistory, NotTrackedUnlessAsked) {
  PlateCase setup;
  Simulation sim = sphere_on_hot_plate(setup);
  SimulationSettings s = sim.settings();
  ASSERT_TRUE(s.heat.track_thermal_history);
  s.heat.track_thermal_history = false;
  Simulation quiet(sim.model().materials, sim.walls, s, sim.model().wall_thermal);
  quiet.add_particle(sphere(sim.particles.position_m[0], {}, kRadius, SphereMaterial{}.density, kStart_K));
  for (int k = 0; k < 200; ++k) quiet.step();
  EXPECT_GT(quiet.particles.temperature_K[0], kDefaultThermalThreshold_K);
  EXPECT_EQ(quiet.particles.peak_temperature_K[0], kStart_K);
  EXPECT_EQ(quiet.particles.time_above_threshold_s[0], 0.0);
}

}  // namespace
}  // namespace regodem
