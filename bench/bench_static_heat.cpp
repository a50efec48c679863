// Coupled against static-bed heat stepping on a small settled cell (DESIGN.md
// section 2, "Thermal stepping"): 3,000 particles of the paper bed (bench/paper_bed.hpp)
// poured and settled at a reduced modulus (G = 3e6 Pa) in an adiabatic barrel of 5 mm
// radius, conduction with the real modulus (3e9 Pa) for the contact radii, on a plate
// at 700 degC, from -196 degC, heated for 0.05 s of simulated time with a time-scale
// factor S = 400 (20 s of real heating). Coupled stepping advances the mechanics and
// the heat at every 0.2-Rayleigh step; the static modes freeze the bed and step the
// heat alone. (A bed stiffened to 3e9 Pa keeps relaxing for 1e5 steps: its contact
// conductances drift by half, which would make the comparison one of creep.)
// Counters: the mean temperature of the 2 mm bands below and above
// z = 3 mm (band_below_K, band_above_K) and simulated seconds per wall second;
// items are particle-steps of the mode's own step.
//
//   build/release/bench/bench_static_heat --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <chrono>
#include <memory>

#include "paper_bed.hpp"
#include "sim/static_heat_stepper.hpp"

namespace regodem::bench {
namespace {

constexpr double kCellRadius = 5.0e-3;
constexpr std::size_t kCellParticles = 3000;
constexpr double kSoftShearModulus = 3.0e6;
constexpr double kHeatingTime_s = 0.05;
constexpr double kScale = 400.0;
constexpr double kBandPlane_m = 3.0e-3, kBandWidth_m = 2.0e-3;

/// A 3,000-particle bed poured into a 5 mm-radius barrel at the reduced modulus and
/// cached like the big beds; conduction takes its contact radii from the real modulus.
/// The plate at 700 degC, the particles at -196 degC.
Simulation small_cell() {
  static const std::vector<ParticleRecord> bed = settled_bed(kCellParticles, kCellRadius);
  BedOptions options;
  options.shear_modulus_Pa = kSoftShearModulus;
  options.real_shear_modulus_Pa = kShearModulus;
  options.barrel_radius_m = kCellRadius;
  options.heat = true;
  options.time_scale_factor = kScale;
  Simulation sim = paper_bed_simulation(bed, options);
  sim.advance(2000);  // let the bed take up the paper's friction
  return sim;
}

double band_mean_K(const Simulation& sim, double from_m, double to_m) {
  double sum = 0.0;
  int count = 0;
  for (std::size_t i = 0; i < sim.particles.size(); ++i) {
    const double z = sim.particles.position_m[i].z;
    if (z >= from_m && z < to_m) sum += sim.particles.temperature_K[i], ++count;
  }
  return count ? sum / count : 0.0;
}

void BM_SmallCellHeat(benchmark::State& state) {
  const auto mode = static_cast<HeatStepping>(state.range(0));
  double particle_steps = 0.0, simulated = 0.0, wall = 0.0;
  Simulation last = small_cell();
  for (auto _ : state) {
    state.PauseTiming();
    Simulation sim = small_cell();
    const double start = sim.time_s();
    state.ResumeTiming();
    const auto clock = std::chrono::steady_clock::now();
    if (mode == HeatStepping::coupled) {
      while (sim.time_s() - start < kHeatingTime_s) {
        sim.step();
        particle_steps += static_cast<double>(sim.particles.size());
      }
    } else {
      Stage stage;
      stage.heat_stepping = mode;
      StaticHeatStepper stepper(sim, stage);
      while (sim.time_s() - start < kHeatingTime_s * (1.0 - 1e-12)) {
        stepper.advance(std::min(stepper.time_step_s(), start + kHeatingTime_s - sim.time_s()));
        particle_steps += static_cast<double>(sim.particles.size());
      }
    }
    wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - clock).count();
    simulated += sim.time_s() - start;
    last = std::move(sim);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(particle_steps));
  state.counters["particles"] = static_cast<double>(last.particles.size());
  state.counters["band_below_K"] = band_mean_K(last, kBandPlane_m - kBandWidth_m, kBandPlane_m);
  state.counters["band_above_K"] = band_mean_K(last, kBandPlane_m, kBandPlane_m + kBandWidth_m);
  state.counters["simulated_s_per_wall_s"] = simulated / wall;
  state.counters["boundary_heat_J"] = last.thermal_ledger().boundary_heat_in_J;
  state.counters["plate_contacts"] = static_cast<double>(last.contact_statistics().wall_contacts);
  state.counters["energy_imbalance"] = last.energy_imbalance_J() / last.thermal_energy_J();
}
BENCHMARK(BM_SmallCellHeat)
    ->ArgName("mode")  // 0 coupled, 1 static explicit, 2 static backward Euler, 3 static Crank-Nicolson
    ->DenseRange(0, 3)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->UseRealTime();

/// The paper's matching cell at full size (Section 3): the 100,000-particle bed of
/// 0.6 mm particles, about 27 mm deep in the 30 mm barrel, settled at the reduced
/// modulus (conduction with the real one), heated from the plate at 700 degC for
/// 1000 s of real time (S = 1): some 5e9 mechanical steps for coupled stepping, one
/// static-bed stage here. Counters: the mean temperatures of the 2 mm bands below
/// and above z = 10 mm (where the paper's sieve sits) and the wall seconds per
/// simulated second.
void BM_MatchingCellHeat(benchmark::State& state) {
  const auto mode = static_cast<HeatStepping>(state.range(0));
  constexpr double kDuration_s = 1000.0, kPlane_m = 10.0e-3;
  static const std::vector<ParticleRecord> bed = settled_bed(100000);
  BedOptions options;
  options.shear_modulus_Pa = kSoftShearModulus;
  options.real_shear_modulus_Pa = kShearModulus;
  options.heat = true;
  options.threads = 2;
  double steps = 0.0, particle_steps = 0.0;
  std::unique_ptr<Simulation> last;
  for (auto _ : state) {
    state.PauseTiming();
    auto sim = std::make_unique<Simulation>(paper_bed_simulation(bed, options));
    state.ResumeTiming();
    Stage stage;
    stage.heat_stepping = mode;
    StaticHeatStepper stepper(*sim, stage);
    while (sim->time_s() < kDuration_s * (1.0 - 1e-12)) {
      stepper.advance(std::min(stepper.time_step_s(), kDuration_s - sim->time_s()));
      steps += 1.0;
      particle_steps += static_cast<double>(sim->particles.size());
    }
    last = std::move(sim);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(particle_steps));
  state.counters["particles"] = static_cast<double>(last->particles.size());
  state.counters["heat_steps"] = steps / static_cast<double>(state.iterations());
  state.counters["band_below_K"] = band_mean_K(*last, kPlane_m - kBandWidth_m, kPlane_m);
  state.counters["band_above_K"] = band_mean_K(*last, kPlane_m, kPlane_m + kBandWidth_m);
  state.counters["energy_imbalance"] = last->energy_imbalance_J() / last->thermal_energy_J();
}
BENCHMARK(BM_MatchingCellHeat)
    ->ArgName("mode")  // 1 static explicit, 3 static Crank-Nicolson
    ->Arg(1)
    ->Arg(3)
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->UseRealTime();

}  // namespace
}  // namespace regodem::bench

BENCHMARK_MAIN();
