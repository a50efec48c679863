// Static-bed heat stepping (DESIGN.md section 2, "Thermal stepping"): on a frozen bed
// the contact network is taken once and temperatures advance on their own step.
//  * Explicit static stepping at the mechanical step reproduces coupled stepping (the
//    same forward-Euler update on the same conductances) to round-off.
//  * On a 2,000-particle bed heated from one side, explicit, backward-Euler and
//    Crank-Nicolson solutions agree within 0.5 K (the bound).
#include <gtest/gtest.h>

#include <cmath>

#include "physics_fixtures.hpp"
#include "sim/stage_runner.hpp"
#include "sim/static_heat_stepper.hpp"

namespace regodem::testing {
namespace {

constexpr double kRadius = 0.3e-3;

/// A simple-cubic block of nx x ny x nz spheres, pitch 1.99 R, boxed by walls placed
/// where they press with the same Hertz force as the neighbours (so every particle is
/// in equilibrium and the block stays at rest: coupled and static stepping see the same
/// contacts). The bottom wall is a plate at 973 K, the others adiabatic; particles at 77 K.
Simulation lattice_bed(int nx, int ny, int nz, double scale, double dt) {
  SphereMaterial m;
  m.density = 3000.0;
  m.shear_modulus = 3.0e7;
  m.conductivity = 14.76;
  m.specific_heat = 800.0;
  const double pitch = 1.99 * kRadius;
  const double e_star = effective_youngs_modulus(m);
  const double pair_overlap = 2.0 * kRadius - pitch;
  const double force = 4.0 / 3.0 * e_star * std::sqrt(0.5 * kRadius) * std::pow(pair_overlap, 1.5);
  const double inset = kRadius - hertz_overlap(force, e_star, kRadius);  // wall distance from the outer centres
  WallSet walls;
  walls.add_plane(walls.add_body("plate", {}), {0, 0, -inset}, {0, 0, 1}, 0);
  const std::uint32_t box = walls.add_body("box", {});
  walls.add_plane(box, {0, 0, (nz - 1) * pitch + inset}, {0, 0, -1}, 0);
  walls.add_plane(box, {-inset, 0, 0}, {1, 0, 0}, 0);
  walls.add_plane(box, {(nx - 1) * pitch + inset, 0, 0}, {-1, 0, 0}, 0);
  walls.add_plane(box, {0, -inset, 0}, {0, 1, 0}, 0);
  walls.add_plane(box, {0, (ny - 1) * pitch + inset, 0}, {0, -1, 0}, 0);
  ThermalWall plate;
  plate.mode = WallThermalMode::fixed;
  plate.prescribed_temperature_K = TimeTable(973.15);
  SimulationSettings settings = settings_for(kRadius, dt, {}, 0.05);
  settings.heat.enabled = true;
  settings.heat.time_scale_factor = scale;
  Simulation sim(one_material(m), walls, settings, {plate, ThermalWall{}});
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j)
      for (int k = 0; k < nz; ++k)
        sim.add_particle(sphere({i * pitch, j * pitch, k * pitch}, {}, kRadius, m.density, 77.15));
  return sim;
}

std::vector<double> temperatures_by_id(const Simulation& sim) {
  std::vector<double> out(sim.particles.size());
  for (std::size_t i = 0; i < sim.particles.size(); ++i) out[sim.particles.id[i]] = sim.particles.temperature_K[i];
  return out;
}

// Coupled and static-explicit stepping at the same step on a bed at rest: the same
// update, so the same temperatures to 1e-9 K after 400 steps (forces of the lattice's
// round-off move nothing measurable).
TEST(StaticBedHeat, ExplicitStaticStepReproducesCoupledStepping) {
  const double dt = 0.2 * rayleigh_time_s(kRadius, 3000.0, 3.0e7, 0.25);
  Simulation coupled = lattice_bed(4, 4, 6, 1e4, dt);
  Simulation frozen = lattice_bed(4, 4, 6, 1e4, dt);
  coupled.advance(400);
  Stage stage;
  stage.heat_stepping = HeatStepping::static_explicit;
  stage.thermal_time_step_s = dt;
  StaticHeatStepper stepper(frozen, stage);
  ASSERT_LT(dt, stepper.stability_limit_s());
  for (int s = 0; s < 400; ++s) stepper.advance(dt);
  const std::vector<double> a = temperatures_by_id(coupled), b = temperatures_by_id(frozen);
  double hottest = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_NEAR(a[i], b[i], 1e-9) << "particle " << i;
    hottest = std::max(hottest, a[i]);
  }
  EXPECT_GT(hottest, 100.0);  // heat has come in
  EXPECT_NEAR(coupled.time_s(), frozen.time_s(), 1e-15);
  EXPECT_NEAR(coupled.thermal_ledger().boundary_heat_in_J / frozen.thermal_ledger().boundary_heat_in_J, 1.0, 1e-9);
}

// 2,000 particles (10 x 10 x 20) heated from the bottom for 300 explicit limits L:
// Crank-Nicolson at its default step (5 L) and backward Euler at 0.5 L agree with
// explicit at 0.5 L within 0.5 K everywhere (the bound); each keeps the energy
// ledger to 1e-9. Backward Euler is first order: at 5 L it is off by ~2 K here, so it
// suits long, smooth heating; Crank-Nicolson is the accurate large-step choice.
TEST(StaticBedHeat, ImplicitAndExplicitSolutionsAgreeOnABedHeatedFromOneSide) {
  const double dt = 0.2 * rayleigh_time_s(kRadius, 3000.0, 3.0e7, 0.25);
  std::vector<std::vector<double>> results;
  double duration = 0.0;
  for (const HeatStepping method :
       {HeatStepping::static_explicit, HeatStepping::static_backward_euler, HeatStepping::static_crank_nicolson}) {
    Simulation sim = lattice_bed(10, 10, 20, 1.0, dt);
    Stage stage;
    stage.heat_stepping = method;
    stage.stability_fraction = 0.5;
    if (method == HeatStepping::static_backward_euler) {
      const StaticHeatStepper probe(sim, stage);
      stage.thermal_time_step_s = 0.5 * probe.stability_limit_s();
    }
    StaticHeatStepper stepper(sim, stage);
    if (duration == 0.0) duration = 300.0 * stepper.stability_limit_s();
    while (sim.time_s() < duration * (1.0 - 1e-12))
      stepper.advance(std::min(stepper.time_step_s(), duration - sim.time_s()));
    EXPECT_NEAR(sim.energy_imbalance_J() / sim.thermal_ledger().boundary_heat_in_J, 0.0, 1e-9);
    EXPECT_GT(sim.thermal_ledger().boundary_heat_in_J, 0.0);
    results.push_back(temperatures_by_id(sim));
  }
  double largest_rise = 0.0;
  for (std::size_t i = 0; i < results[0].size(); ++i) {
    largest_rise = std::max(largest_rise, results[0][i] - 77.15);
    EXPECT_NEAR(results[1][i], results[0][i], 0.5) << "backward Euler, particle " << i;
    EXPECT_NEAR(results[2][i], results[0][i], 0.5) << "Crank-Nicolson, particle " << i;
  }
  EXPECT_GT(largest_rise, 100.0);  // the comparison is over a real heating
}


// A coupled stage whose time-scale factor pushes the heat step past the explicit limit
// min m c / sum G is refused before it runs, with the largest stable S in the message;
// at a stable S the same plan runs.
TEST(StaticBedHeat, CoupledStageRefusesAnUnstableTimeScaleFactor) {
  const double dt = 0.2 * rayleigh_time_s(kRadius, 3000.0, 3.0e7, 0.25);
  class Quiet : public RunObserver {};
  Quiet quiet;
  std::atomic<bool> stop{false};
  for (const double scale : {1e9, 1.0}) {
    Simulation sim = lattice_bed(3, 3, 3, scale, dt);
    StagePlan plan;
    Stage heat;
    heat.name = "heat";
    heat.duration_s = 10 * dt;
    plan.stages.push_back(heat);
    const RunOutcome outcome = run_stages(sim, plan, quiet, stop);
    if (scale > 1.0) {
      EXPECT_FALSE(outcome.completed);
      EXPECT_NE(outcome.message.find("heat stability limit"), std::string::npos) << outcome.message;
      EXPECT_NE(outcome.message.find("use S below"), std::string::npos) << outcome.message;
      EXPECT_EQ(sim.step_count(), 0u);
    } else {
      EXPECT_TRUE(outcome.completed) << outcome.message;
    }
  }
}

}  // namespace
}  // namespace regodem::testing
