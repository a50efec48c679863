// Particle-steps per second of the settled paper bed (bench/paper_bed.hpp: 20,000
// particles of 0.6 mm, G = 3e9 Pa, 0.2 of the Rayleigh step) with every touching pair
// (and every pair within 5 % of the radius) bonded with the default icy-regolith bond,
// against the same bed without bonds. The bond pass runs after the contact pass: one
// update per bond, then a gather per particle. The bed at rest at the real modulus is made
// once and kept in the cache (loaded_bed_simulation, paper_bed.hpp): a later run restores it.
//
//   REGODEM_BENCH_CACHE=/work/bench-cache build/release/bench/bench_bonds --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "paper_bed.hpp"

namespace regodem::bench {
namespace {

void BM_BondedBed(benchmark::State& state) {
  const auto count = static_cast<std::size_t>(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  const bool bonded = state.range(2) != 0;
  Simulation sim = loaded_bed_simulation(count, threads);  // at rest at the real modulus
  if (bonded) {
    sim.configure_bonds({icy_regolith_bond_parameters()}, {0});
    sim.form_bonds(0.05);
    sim.advance(200);  // the bonds take their share of the load
  }
  const std::uint64_t broken_before = sim.bond_counts().broken();
  for (auto _ : state) sim.step();
  const double n = static_cast<double>(sim.particles.size());
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * sim.particles.size()));
  state.counters["particles"] = n;
  state.counters["bonds_per_particle"] = static_cast<double>(sim.bond_counts().intact) / n;
  state.counters["broken_while_timed"] = static_cast<double>(sim.bond_counts().broken() - broken_before);
  state.counters["contacts_per_particle"] = 2.0 * static_cast<double>(sim.contact_statistics().particle_contacts) / n;
}
BENCHMARK(BM_BondedBed)
    ->ArgNames({"particles", "threads", "bonds"})
    ->ArgsProduct({{20000}, {1, 2}, {0, 1}})
    ->Unit(benchmark::kMillisecond)->Iterations(1000)->UseRealTime();

/// Uniaxial (unconfined) compression of a bonded cylinder: the 3,000-particle paper bed
/// settled in a 5 mm-radius barrel and stiffened to G = 3e9 Pa, the barrel taken away,
/// every pair within 5 % of the radius bonded, then pressed between the floor and a top
/// plate moving down at 0.2 m/s (a strain rate of ~27 /s: the sample's elastic wave,
/// ~200 m/s at its ~75 MPa modulus, crosses it ~100 times over 10 % strain, and the
/// plate's dynamic pressure rho v^2 ~ 70 Pa is nothing against MPa: quasi-static). The
/// axial stress is the top plate's force over the sample's cross-section pi (5 mm)^2;
/// its peak is the uniaxial compressive strength (UCS). preset 0: the default
/// icy-regolith bond; 1: the paper's Table 2 (zhao2023), which no test breaks;
/// strength_MPa, where not 0, replaces both strengths of the preset. The test stops at
/// failure (the stress down to half its peak) or at max_strain_percent: the top of a
/// poured sample is rough by about a radius, so the first ~4 % of strain only seat the
/// plate. Fragments thrown off the failing sample leave the domain and are removed.
void BM_UniaxialCompression(benchmark::State& state) {
  const bool paper = state.range(0) != 0;
  const double strength_Pa = 1e6 * static_cast<double>(state.range(1));  // 0: the preset's
  const double max_strain = 0.01 * static_cast<double>(state.range(2));
  constexpr double kSampleRadius = 5.0e-3;
  static const std::vector<ParticleRecord> bed = stiffened_bed(settled_bed(3000, kSampleRadius), 2, kSampleRadius);
  double ucs = 0.0, strain_at_peak = 0.0, steps_run = 0.0, bonds = 0.0, broken = 0.0, final_strain = 0.0;
  double burst = 0.0, lost = 0.0;
  for (auto _ : state) {
    double top = 0.0;
    for (const ParticleRecord& r : bed) top = std::max(top, r.position_m.z + kRadius);
    BedOptions options;
    options.threads = 2;
    options.barrel_radius_m = kSampleRadius;
    Simulation barrel = paper_bed_simulation(bed, options);
    barrel.advance(3000);  // the last decade of stiffening, in the barrel
    const double dt = barrel.time_step_s();
    const double relax_s = 2000 * dt;
    const double speed = 0.2;  // m/s
    WallSet walls;
    walls.add_plane(walls.add_body("floor", {}), {0, 0, 0}, {0, 0, 1}, 0);
    WallMotion press;
    press.velocity_m_per_s = {0, 0, -speed};
    press.start_s = relax_s;
    walls.add_plane(walls.add_body("press", press), {0, 0, top}, {0, 0, -1}, 0);
    SimulationSettings s = barrel.settings();
    // Fragments thrown off the failing sample leave the domain and are dropped: the
    // plate's force is what the test measures.
    s.lost_particles = LostParticles::remove;
    // Room to bulge and crumble: a bonded sample fails suddenly, and the elastic energy
    // it releases (sigma^2/2E ~ 3e5 J/m^3 at 9 MPa) throws fragments at ~20 m/s.
    s.domain.max_m.z = top + 20e-3;
    s.domain.min_m.x = s.domain.min_m.y = -6.0 * kSampleRadius;
    s.domain.max_m.x = s.domain.max_m.y = 6.0 * kSampleRadius;
    Simulation sim(barrel.model().materials, walls, s);
    for (std::size_t i = 0; i < barrel.particles.size(); ++i) {
      NewParticle p;
      p.position_m = barrel.particles.position_m[i];
      p.velocity_m_per_s = barrel.particles.velocity_m_per_s[i];
      p.radius_m = barrel.particles.radius_m[i];
      p.density_kg_per_m3 = kDensity;
      sim.add_particle(p);
    }
    BondParameters bond = paper ? zhao2023_bond_parameters() : icy_regolith_bond_parameters();
    if (strength_Pa > 0.0) bond.tensile_strength_Pa = bond.shear_strength_Pa = strength_Pa;
    sim.configure_bonds({bond}, {0});
    bonds = static_cast<double>(sim.form_bonds(0.05));
    const double area = M_PI * kSampleRadius * kSampleRadius;
    ucs = 0.0;
    std::uint64_t steps = 0;
    burst = 0.0;
    for (;;) {
      try {
        sim.advance(100);
      } catch (const SimulationError& e) {  // a blow-up: report what was reached
        std::fprintf(stderr, "%s\n", e.what());
        burst = 1.0;
        break;
      }
      steps += 100;
      const double strain = std::max(0.0, (sim.time_s() - relax_s) * speed / top);
      const double stress = std::max(0.0, sim.walls.bodies[1].force_N.z) / area;  // the particles push the press up
      if (stress > ucs) ucs = stress, strain_at_peak = strain;
      final_strain = strain;
      // Failed: the stress has fallen to half its peak; or max_strain without failure.
      if ((ucs > 0.0 && stress < 0.5 * ucs && strain > strain_at_peak + 0.002) || strain > max_strain) break;
      if (steps % 2000 == 0)
        std::fprintf(stderr, "strain %.4f stress %.4g MPa broken %llu lost %llu\n", strain, stress / 1e6,
                     static_cast<unsigned long long>(sim.bond_counts().broken()),
                     static_cast<unsigned long long>(sim.lost_particle_count()));
    }
    steps_run = static_cast<double>(steps);
    broken = static_cast<double>(sim.bond_counts().broken());
    lost = static_cast<double>(sim.lost_particle_count());
  }
  state.counters["ucs_MPa"] = ucs / 1e6;
  state.counters["strain_at_peak"] = strain_at_peak;
  state.counters["final_strain"] = final_strain;
  state.counters["bonds"] = bonds;
  state.counters["broken"] = broken;
  state.counters["steps"] = steps_run;
  state.counters["burst"] = burst;
  state.counters["lost"] = lost;
}
BENCHMARK(BM_UniaxialCompression)
    ->ArgNames({"paper_preset", "strength_MPa", "max_strain_percent"})
    ->Args({0, 0, 30})->Args({0, 10, 30})->Args({1, 0, 15})
    ->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
}  // namespace regodem::bench

BENCHMARK_MAIN();
