// Static-bed heat stepping (DESIGN.md section 2, "Thermal stepping"): on a frozen bed
// the contact network is taken once and temperatures advance on their own step.
//  * Explicit static stepping at the mechanical step reproduces coupled stepping (the
//    same forward-Euler update on the same conductances) to round-off.
//  * On a 2,000-particle bed heated from one side, explicit and Crank-Nicolson
//    solutions agree within 0.5 K (the bound); backward Euler converges at
//    first order from its default step down.
//  * With a specific heat that triples over the range, every method keeps the energy
//    ledger and two spheres end at the enthalpy mean, 2 h(T_f) = h(T_a) + h(T_b).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "physics_fixtures.hpp"
#include "sim/stage_runner.hpp"
#include "sim/static_heat_stepper.hpp"

namespace regodem::testing {
namespace {

constexpr double kRadius = 0.3e-3;

/// One material, `m` with its specific heat replaced by a curve over temperature.
MaterialTable with_specific_heat(const SphereMaterial& m, const TemperatureCurve& specific_heat) {
  const MaterialTable constant = one_material(m);
  Material grain = constant[0];
  grain.specific_heat_J_per_kgK = specific_heat;
  MaterialTable table;
  table.add(grain);
  table.set_pair(0, 0, constant.pair(0, 0));
  return table;
}

/// Advances a static stage to `duration_s`, the last step cut to land on it.
void run_static(Simulation& sim, StaticHeatStepper& stepper, double duration_s) {
  while (sim.time_s() < duration_s * (1.0 - 1e-12))
    stepper.advance(std::min(stepper.time_step_s(), duration_s - sim.time_s()));
}

constexpr HeatStepping kStaticMethods[] = {HeatStepping::static_explicit, HeatStepping::static_backward_euler,
                                           HeatStepping::static_crank_nicolson};

const char* name_of(HeatStepping method) {
  switch (method) {
    case HeatStepping::static_explicit: return "explicit";
    case HeatStepping::static_backward_euler: return "backward Euler";
    case HeatStepping::static_crank_nicolson: return "Crank-Nicolson";
    default: return "coupled";
  }
}

/// A simple-cubic block of nx x ny x nz spheres, pitch 1.99 R, boxed by walls placed
/// where they press with the same Hertz force as the neighbours (so every particle is
/// in equilibrium and the block stays at rest: coupled and static stepping see the same
/// contacts). The bottom wall is a plate at 973 K, the others one body, `box_thermal`
/// (adiabatic unless given); particles at 77 K, of `specific_heat` (800 J/(kg K) unless given).
Simulation lattice_bed(int nx, int ny, int nz, double scale, double dt,
                       const TemperatureCurve& specific_heat = TemperatureCurve(800.0),
                       const ThermalWall& box_thermal = {}) {
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
  Simulation sim(with_specific_heat(m, specific_heat), walls, settings, {plate, box_thermal});
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
// Crank-Nicolson at its default step (5 L) agrees with explicit at 0.5 L within 0.5 K
// everywhere (the bound); each keeps the energy ledger to 1e-9.
TEST(StaticBedHeat, ImplicitAndExplicitSolutionsAgreeOnABedHeatedFromOneSide) {
  const double dt = 0.2 * rayleigh_time_s(kRadius, 3000.0, 3.0e7, 0.25);
  std::vector<std::vector<double>> results;
  double duration = 0.0;
  for (const HeatStepping method : {HeatStepping::static_explicit, HeatStepping::static_crank_nicolson}) {
    Simulation sim = lattice_bed(10, 10, 20, 1.0, dt);
    Stage stage;
    stage.heat_stepping = method;
    stage.stability_fraction = 0.5;
    StaticHeatStepper stepper(sim, stage);
    if (duration == 0.0) duration = 300.0 * stepper.stability_limit_s();
    run_static(sim, stepper, duration);
    EXPECT_NEAR(sim.energy_imbalance_J() / sim.thermal_ledger().boundary_heat_in_J, 0.0, 1e-9);
    EXPECT_GT(sim.thermal_ledger().boundary_heat_in_J, 0.0);
    results.push_back(temperatures_by_id(sim));
  }
  double largest_rise = 0.0;
  for (std::size_t i = 0; i < results[0].size(); ++i) {
    largest_rise = std::max(largest_rise, results[0][i] - 77.15);
    EXPECT_NEAR(results[1][i], results[0][i], 0.5) << "Crank-Nicolson, particle " << i;
  }
  EXPECT_GT(largest_rise, 100.0);  // the comparison is over a real heating
}

// Backward Euler is first order, and at its default step (10 x 0.5 = 5 L) about 2 K off
// (docs/physics.md), so it is held to its order rather than to the 0.5 K bound: on the
// bed above, its largest error after 300 L halves as the step halves, 5 L -> 2.5 L ->
// 1.25 L. The reference is Crank-Nicolson at 0.5 L: second order and ~0.1 K off at 5 L,
// so ~1e-3 K here, well below BE's ~0.5 K at 1.25 L. Bound, set before running: the
// global error is K h (1 + O(lambda h)) with corrections ~ lambda h / 3 and lambda^2 t h / 8;
// the modes that carry the profile at 300 L span its ~7 heated layers, lambda ~ (pi/7)^2 /
// 6 per L, so lambda h <= 0.17 and each correction is <= ~6 %: each ratio lies in [1.7, 2.3].
TEST(StaticBedHeat, BackwardEulerErrorHalvesWithTheStepFromItsDefault) {
  const double dt = 0.2 * rayleigh_time_s(kRadius, 3000.0, 3.0e7, 0.25);
  double limit = 0.0;
  {
    Simulation probe_bed = lattice_bed(10, 10, 20, 1.0, dt);
    Stage explicit_stage;
    explicit_stage.heat_stepping = HeatStepping::static_explicit;
    limit = StaticHeatStepper(probe_bed, explicit_stage).stability_limit_s();
  }
  const double duration = 300.0 * limit;
  const auto run = [&](HeatStepping method, double step_in_limits) {
    Simulation sim = lattice_bed(10, 10, 20, 1.0, dt);
    Stage stage;
    stage.heat_stepping = method;
    stage.stability_fraction = 0.5;
    if (step_in_limits > 0.0) stage.thermal_time_step_s = step_in_limits * limit;
    StaticHeatStepper stepper(sim, stage);
    if (step_in_limits == 0.0) {
      EXPECT_NEAR(stepper.time_step_s() / limit, 5.0, 1e-12);  // the default
    }
    run_static(sim, stepper, duration);
    EXPECT_NEAR(sim.energy_imbalance_J() / sim.thermal_ledger().boundary_heat_in_J, 0.0, 1e-9);
    return temperatures_by_id(sim);
  };
  const std::vector<double> reference = run(HeatStepping::static_crank_nicolson, 0.5);
  std::vector<double> largest_error;
  for (const double step_in_limits : {0.0, 2.5, 1.25}) {
    const std::vector<double> t = run(HeatStepping::static_backward_euler, step_in_limits);
    double e = 0.0;
    for (std::size_t i = 0; i < t.size(); ++i) e = std::max(e, std::abs(t[i] - reference[i]));
    largest_error.push_back(e);
  }
  std::printf("backward Euler, largest error at 5, 2.5, 1.25 L: %.4g, %.4g, %.4g K\n", largest_error[0],
              largest_error[1], largest_error[2]);
  for (std::size_t k = 0; k + 1 < largest_error.size(); ++k) {
    const double ratio = largest_error[k] / largest_error[k + 1];
    EXPECT_GE(ratio, 1.7) << "step " << k;
    EXPECT_LE(ratio, 2.3) << "step " << k;
  }
}

// c(T) tripling from 300 to 900 J/(kg K) between 80 K and 350 K (regolith's shape, as
// HeatConduction.TemperatureDependentSpecificHeatConservesEnthalpy), 1000 at 1000 K: a
// 128-particle bed heated from the 973 K plate for 300 L, the other walls one lumped
// body. Every method must keep sum m h(T) + C_w T_w = start + heat through the plate to
// 1e-9 of the heat in, the bound of the constant-c bed: round-off for explicit and the
// factor, and CG's 1e-12 relative residual over the implicit methods' 60 steps.
TEST(StaticBedHeat, TemperatureDependentSpecificHeatKeepsTheLedgerOnAHeatedBed) {
  const double dt = 0.2 * rayleigh_time_s(kRadius, 3000.0, 3.0e7, 0.25);
  const TemperatureCurve c({80.0, 350.0, 1000.0}, {300.0, 900.0, 1000.0});
  ThermalWall box;
  box.mode = WallThermalMode::lumped;
  box.initial_temperature_K = 77.15;
  box.heat_capacity_J_per_K = 0.01;  // ~ the bed's m c at 77 K
  for (const HeatStepping method : kStaticMethods) {
    Simulation sim = lattice_bed(4, 4, 8, 1.0, dt, c, box);
    Stage stage;
    stage.heat_stepping = method;
    stage.stability_fraction = 0.5;
    StaticHeatStepper stepper(sim, stage);
    run_static(sim, stepper, 300.0 * stepper.stability_limit_s());
    const double heat_in = sim.thermal_ledger().boundary_heat_in_J;
    std::printf("%s: heat in %.6g J, imbalance %.3g of it; box at %.2f K\n", name_of(method),
                heat_in, sim.energy_imbalance_J() / heat_in, sim.wall_thermal_state[1].temperature_K);
    EXPECT_GT(heat_in, 0.0);
    EXPECT_GT(sim.wall_thermal_state[1].temperature_K, 77.15 + 1.0);  // the lumped walls take part
    EXPECT_NEAR(sim.energy_imbalance_J() / heat_in, 0.0, 1e-9) << name_of(method);
  }
}

// Two touching spheres at 300 K and 100 K, no walls, c(T) as the coupled test's (300,
// 600, 900 J/(kg K) at 100, 200, 350 K): for 400 L every method settles at T_f with
// 2 h(T_f) = h(300) + h(100), not at 200 K. Bounds, set before running: the energy to
// 1e-10 of its start (round-off, or CG's 1e-12 relative residual over <= 80 implicit
// steps), so T_f to ~1e-10 x 300 K; the difference left after 400 L (at most a factor
// 0.67 a step, Crank-Nicolson at 5 L) is below 1e-12 K; hence 1e-6 K.
TEST(StaticBedHeat, TwoSpheresWithTemperatureDependentSpecificHeatEndAtTheEnthalpyMean) {
  const double dt = 0.2 * rayleigh_time_s(kRadius, 3000.0, 3.0e7, 0.25);
  const TemperatureCurve c({100.0, 200.0, 350.0}, {300.0, 600.0, 900.0});
  SphereMaterial m;
  m.density = 3000.0;
  m.shear_modulus = 3.0e7;
  m.conductivity = 14.76;
  const double expected = c.inverse_integral(0.5 * (c.integral_from_zero(300.0) + c.integral_from_zero(100.0)));
  EXPECT_GT(expected, 200.0 + 20.0);  // far from the arithmetic mean
  for (const HeatStepping method : kStaticMethods) {
    SimulationSettings settings = settings_for(kRadius, dt, {}, 0.05);
    settings.heat.enabled = true;
    Simulation sim(with_specific_heat(m, c), WallSet{}, settings);
    sim.add_particle(sphere({0, 0, 0}, {}, kRadius, m.density, 300.0));
    sim.add_particle(sphere({1.99 * kRadius, 0, 0}, {}, kRadius, m.density, 100.0));
    const double energy_before = sim.thermal_energy_J();
    Stage stage;
    stage.heat_stepping = method;
    stage.stability_fraction = 0.5;
    StaticHeatStepper stepper(sim, stage);
    run_static(sim, stepper, 400.0 * stepper.stability_limit_s());
    std::printf("%s: T = %.9f, %.9f K (expected %.9f), energy %.3g of its start\n", name_of(method),
                sim.particles.temperature_K[0], sim.particles.temperature_K[1], expected,
                sim.energy_imbalance_J() / energy_before);
    EXPECT_NEAR(sim.particles.temperature_K[0], expected, 1e-6) << name_of(method);
    EXPECT_NEAR(sim.particles.temperature_K[1], expected, 1e-6) << name_of(method);
    EXPECT_NEAR(sim.energy_imbalance_J() / energy_before, 0.0, 1e-10) << name_of(method);
  }
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
