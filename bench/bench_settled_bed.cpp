// Particle-steps per second of the contact + integration step on settled beds of
// 0.6 mm particles with the paper's parameters (G = 3e9 Pa, e = 0.24, mu_s = 0.8,
// mu_r = 0.6) in a 30 mm cylinder, time step 0.2 of the Rayleigh time; and of a pour.
//
// A bed poured at the real modulus takes hours, so the bed is poured once at a
// reduced modulus (G = 3e6 Pa), frictionless as in the paper, and cached as CSV
// (REGODEM_BENCH_CACHE, default the working directory). It is then stiffened in
// decades, G = 3e7, 3e8, 3e9 Pa, relaxing 3,000 steps at each (each decade shrinks
// the overlaps 4.6-fold and the bed takes up its weight again), with the paper's
// friction; only then is the clock started (contacts_per_particle reports the bed).
//
//   build/release/bench/bench_settled_bed --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "io/particle_csv_reader.hpp"
#include "scenario/scenario_builder.hpp"
#include "sim/simulation.hpp"
#include "sim/time_step.hpp"

namespace regodem {
namespace {

constexpr double kRadius = 0.3e-3;
constexpr double kCylinderRadius = 15.0e-3;
constexpr double kDensity = 3000.0, kShearModulus = 3.0e9, kPoisson = 0.25;

double resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  double pages_total = 0.0, pages_resident = 0.0;
  statm >> pages_total >> pages_resident;
  return pages_resident * static_cast<double>(sysconf(_SC_PAGESIZE));
}

ScenarioSpec soft_pour_spec(std::size_t count, double height) {
  ScenarioSpec spec;
  spec.name = "bench-pour";
  spec.file = "bench-pour.yaml";
  spec.seed = 11;
  spec.domain.min_m = {-kCylinderRadius - 1e-3, -kCylinderRadius - 1e-3, -1e-3};
  spec.domain.max_m = {kCylinderRadius + 1e-3, kCylinderRadius + 1e-3, height + 2e-3};
  spec.materials.push_back({"regolith", kDensity, 3.0e6, kPoisson, {}});
  InteractionSpec pair;
  pair.material_a = pair.material_b = "regolith";
  pair.restitution = 0.24;
  pair.sliding_friction = 0.0;  // the paper fills frictionless for a dense sample
  pair.rolling_friction = 0.0;
  spec.interactions.push_back(pair);
  WallSpec cup;
  cup.name = "barrel";
  cup.shape = WallShape::cylinder;
  cup.radius_m = kCylinderRadius;
  cup.length_m = height;
  cup.cap_bottom = true;
  spec.walls.push_back(cup);
  InsertionSpec in;
  in.name = "fine";
  in.material = "regolith";
  in.region.shape = RegionShape::cylinder;
  in.region.base_m = {0, 0, 0.5 * height};
  in.region.length_m = 0.5 * height - 0.5e-3;
  in.region.radius_m = kCylinderRadius - 0.1e-3;
  in.sizes.push_back({kRadius, 1.0});
  in.amount = static_cast<double>(count);
  in.rate_per_s = static_cast<double>(count) / 0.15;
  in.interval_s = 0.005;
  in.initial_velocity_m_per_s = {0, 0, -0.5};
  spec.insertions.push_back(in);
  StageSpec settle;
  settle.name = "settle";
  settle.end = StageEnd::settled;
  settle.settled_kinetic_energy_J = 1e-12;
  settle.min_duration_s = 0.15;
  settle.max_duration_s = 0.5;  // a frictionless bed creeps long after it has packed
  spec.stages.push_back(settle);
  return spec;
}

double bed_height(std::size_t count) {
  // Room for the poured particles at a loose 0.35 solid fraction.
  const double volume = static_cast<double>(count) * 4.0 / 3.0 * M_PI * kRadius * kRadius * kRadius / 0.35;
  return std::max(0.02, volume / (M_PI * kCylinderRadius * kCylinderRadius));
}

class Quiet : public RunObserver {};

/// The cached soft-poured bed (poured now if missing).
std::vector<ParticleRecord> settled_bed(std::size_t count) {
  const char* dir = std::getenv("REGODEM_BENCH_CACHE");
  const std::filesystem::path path =
      std::filesystem::path(dir ? dir : ".") / ("regodem-bench-bed-" + std::to_string(count) + ".csv");
  if (!std::filesystem::exists(path)) {
    std::fprintf(stderr, "pouring a %zu-particle bed at G = 3e6 Pa into %s (once)...\n", count, path.c_str());
    PreparedRun run = PreparedRun::build(soft_pour_spec(count, bed_height(count)), 2);
    Quiet quiet;
    std::atomic<bool> stop{false};
    const RunOutcome outcome = run.run(quiet, stop);
    if (!outcome.completed) std::fprintf(stderr, "warning: %s\n", outcome.message.c_str());
    const ParticleStore& p = run.simulation().particles;
    std::ofstream out(path);
    out.precision(17);
    out << "x,y,z,radius\n";
    for (std::size_t i = 0; i < p.size(); ++i)
      out << p.position_m[i].x << ',' << p.position_m[i].y << ',' << p.position_m[i].z << ','
          << p.radius_m[i] << '\n';
  }
  return read_particle_csv(path.string());
}

Simulation paper_bed_simulation(const std::vector<ParticleRecord>& bed, int threads,
                                double shear_modulus_Pa = kShearModulus) {
  MaterialTable materials;
  materials.add({"regolith", kDensity, shear_modulus_Pa, kPoisson});
  PairProperties pair;
  pair.restitution = 0.24;
  pair.sliding_friction = 0.8;
  pair.rolling_friction = 0.6;
  materials.set_pair(0, 0, pair);
  double top = 0.0;
  for (const ParticleRecord& r : bed) top = std::max(top, r.position_m.z);
  WallSet walls;
  walls.add_cylinder(walls.add_body("barrel", {}), {0, 0, 0}, {0, 0, 1}, kCylinderRadius, top + 1e-3, true,
                     false, true, false, 0);
  SimulationSettings s;
  s.domain = {{-kCylinderRadius - 1e-3, -kCylinderRadius - 1e-3, -1e-3},
              {kCylinderRadius + 1e-3, kCylinderRadius + 1e-3, top + 5e-3}};
  s.time_step_s = 0.2 * rayleigh_time_s(kRadius, kDensity, shear_modulus_Pa, kPoisson);
  s.min_particle_radius_m = kRadius;
  s.neighbor_skin_m = 0.2 * s.min_particle_radius_m;
  s.threads = threads;
  Simulation sim(std::move(materials), std::move(walls), s);
  sim.particles.reserve(bed.size());
  for (const ParticleRecord& r : bed) {
    NewParticle p;
    p.position_m = r.position_m;
    p.radius_m = kRadius;  // older caches held shrunk radii
    p.density_kg_per_m3 = kDensity;
    sim.add_particle(p);
  }
  return sim;
}

/// The soft bed stiffened decade by decade to the real modulus, at rest.
std::vector<ParticleRecord> stiffened_bed(std::vector<ParticleRecord> bed, int threads) {
  for (double modulus : {3.0e7, 3.0e8}) {
    Simulation sim = paper_bed_simulation(bed, threads, modulus);
    sim.advance(3000);
    for (std::size_t i = 0; i < sim.particles.size(); ++i) bed[i].position_m = sim.particles.position_m[i];
  }
  return bed;
}

void BM_SettledBed(benchmark::State& state) {
  const auto count = static_cast<std::size_t>(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  const std::vector<ParticleRecord> bed = stiffened_bed(settled_bed(count), threads);
  const double rss_before = resident_bytes();
  Simulation sim = paper_bed_simulation(bed, threads);
  sim.advance(3000);  // the last decade: take up the load at the real modulus
  const double rss_after = resident_bytes();
  for (auto _ : state) sim.step();
  const double n = static_cast<double>(sim.particles.size());
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * sim.particles.size()));
  state.counters["particles"] = n;
  state.counters["contacts_per_particle"] =
      2.0 * static_cast<double>(sim.contact_statistics().particle_contacts) / n;
  state.counters["bytes_per_particle"] = (rss_after - rss_before) / n;
  state.counters["list_entries_per_particle"] = static_cast<double>(sim.neighbor_list().pair_count()) / n;
  state.counters["rebuilds"] = static_cast<double>(sim.neighbor_list().rebuild_count());
}
BENCHMARK(BM_SettledBed)
    ->ArgNames({"particles", "threads"})
    ->Args({20000, 1})->Args({20000, 2})->Args({100000, 1})->Args({100000, 2})
    ->Unit(benchmark::kMillisecond)->Iterations(1000)->UseRealTime();

/// The pouring phase at the reduced modulus: particles inserted at a rate, falling and
/// piling up; 20,000 steps from the start of the pour.
void BM_Pour(benchmark::State& state) {
  const auto count = static_cast<std::size_t>(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  double particle_steps = 0.0;
  for (auto _ : state) {
    ScenarioSpec spec = soft_pour_spec(count, bed_height(count));
    spec.stages[0].end = StageEnd::time;
    spec.stages[0].duration_s = 0.0;
    PreparedRun run = PreparedRun::build(spec, threads);
    spec.stages[0].duration_s = 20000 * run.time_step_s();
    run = PreparedRun::build(spec, threads);
    Quiet quiet;
    std::atomic<bool> stop{false};
    const RunOutcome outcome = run.run(quiet, stop);
    particle_steps += outcome.particle_steps_per_s * outcome.wall_s;
    state.SetIterationTime(outcome.wall_s);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(particle_steps));
}
BENCHMARK(BM_Pour)->ArgNames({"particles", "threads"})->Args({20000, 1})->Args({20000, 2})
    ->Unit(benchmark::kSecond)->Iterations(1)->UseManualTime();

}  // namespace
}  // namespace regodem

BENCHMARK_MAIN();
