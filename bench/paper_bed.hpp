#pragma once
// The benchmarks' paper bed: 0.6 mm particles with the paper's parameters (G = 3e9 Pa,
// e = 0.24, mu_s = 0.8, mu_r = 0.6) in a 30 mm cylinder, time step 0.2 of the Rayleigh
// time.
//
// A bed poured at the real modulus takes hours, so the bed is poured once at a
// reduced modulus (G = 3e6 Pa), frictionless as in the paper, and cached as CSV
// (REGODEM_BENCH_CACHE, default the working directory). It is then stiffened in
// decades, G = 3e7, 3e8, 3e9 Pa, relaxing 3,000 steps at each (each decade shrinks
// the overlaps 4.6-fold and the bed takes up its weight again), with the paper's
// friction.
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <string>
#include <unistd.h>

#include "io/checkpoint_file.hpp"
#include "io/particle_csv_reader.hpp"
#include "scenario/scenario_builder.hpp"
#include "sim/simulation.hpp"
#include "sim/time_step.hpp"

namespace regodem::bench {


constexpr double kRadius = 0.3e-3;
constexpr double kCylinderRadius = 15.0e-3;
constexpr double kDensity = 3000.0, kShearModulus = 3.0e9, kPoisson = 0.25;

inline double resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  double pages_total = 0.0, pages_resident = 0.0;
  statm >> pages_total >> pages_resident;
  return pages_resident * static_cast<double>(sysconf(_SC_PAGESIZE));
}

inline ScenarioSpec soft_pour_spec(std::size_t count, double height, double barrel_radius_m = kCylinderRadius) {
  ScenarioSpec spec;
  spec.name = "bench-pour";
  spec.file = "bench-pour.yaml";
  spec.seed = 11;
  spec.domain.min_m = {-barrel_radius_m - 1e-3, -barrel_radius_m - 1e-3, -1e-3};
  spec.domain.max_m = {barrel_radius_m + 1e-3, barrel_radius_m + 1e-3, height + 2e-3};
  spec.materials.push_back(elastic_material("regolith", kDensity, 3.0e6, kPoisson));
  InteractionSpec pair;
  pair.material_a = pair.material_b = "regolith";
  pair.restitution = 0.24;
  pair.sliding_friction = 0.0;  // the paper fills frictionless for a dense sample
  pair.rolling_friction = 0.0;
  spec.interactions.push_back(pair);
  WallSpec cup;
  cup.name = "barrel";
  cup.shape = WallShape::cylinder;
  cup.radius_m = barrel_radius_m;
  cup.length_m = height;
  cup.cap_bottom = true;
  spec.walls.push_back(cup);
  InsertionSpec in;
  in.name = "fine";
  in.material = "regolith";
  in.region.shape = RegionShape::cylinder;
  in.region.base_m = {0, 0, 0.5 * height};
  in.region.length_m = 0.5 * height - 0.5e-3;
  in.region.radius_m = barrel_radius_m - 0.1e-3;
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

inline double bed_height(std::size_t count, double barrel_radius_m = kCylinderRadius) {
  // Room for the poured particles at a loose 0.35 solid fraction.
  const double volume = static_cast<double>(count) * 4.0 / 3.0 * M_PI * kRadius * kRadius * kRadius / 0.35;
  return std::max(0.02, volume / (M_PI * barrel_radius_m * barrel_radius_m));
}

class Quiet : public RunObserver {};

/// The cached soft-poured bed (poured now if missing).
/// The cached soft-poured bed of `count` particles in a barrel of the given radius.
inline std::vector<ParticleRecord> settled_bed(std::size_t count, double barrel_radius_m = kCylinderRadius) {
  const char* dir = std::getenv("REGODEM_BENCH_CACHE");
  const std::filesystem::path path =
      std::filesystem::path(dir ? dir : ".") / ("regodem-bench-bed-" + std::to_string(count) +
       (barrel_radius_m == kCylinderRadius ? std::string() : "-r" + std::to_string(std::lround(barrel_radius_m * 1e6)) + "um") +
       ".csv");
  if (!std::filesystem::exists(path)) {
    std::fprintf(stderr, "pouring a %zu-particle bed at G = 3e6 Pa into %s (once)...\n", count, path.c_str());
    PreparedRun run = PreparedRun::build(soft_pour_spec(count, bed_height(count, barrel_radius_m), barrel_radius_m), 2);
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

/// The paper's bed: regolith in the barrel on a bottom plate. With heat on (the paper's
/// k = 14.76 W/(m K), c = 800 J/(kg K)), the plate is held at 700 degC and the
/// particles start at -196 degC, so every contact conducts from the start.
struct BedOptions {
  int threads = 1;
  double shear_modulus_Pa = kShearModulus;
  double barrel_radius_m = kCylinderRadius;
  bool heat = false;
  double time_scale_factor = 1.0;
  double real_shear_modulus_Pa = 0.0;  // conduction's contact radii from this modulus (0: the same)
  // A drill (mesh wall, adiabatic) placed as given, moving as given.
  std::optional<TriangleMesh> drill;
  WallMotion drill_motion;
};

inline Simulation paper_bed_simulation(const std::vector<ParticleRecord>& bed, const BedOptions& options) {
  const double shear_modulus_Pa = options.shear_modulus_Pa, barrel_radius_m = options.barrel_radius_m;
  MaterialTable materials;
  Material regolith;
  regolith.name = "regolith";
  regolith.density_kg_per_m3 = kDensity;
  regolith.shear_modulus_Pa = shear_modulus_Pa;
  regolith.poisson_ratio = kPoisson;
  regolith.conductivity_W_per_mK = TemperatureCurve(14.76);
  regolith.specific_heat_J_per_kgK = TemperatureCurve(800.0);
  regolith.real_shear_modulus_Pa = options.real_shear_modulus_Pa;
  materials.add(regolith);
  PairProperties pair;
  pair.restitution = 0.24;
  pair.sliding_friction = 0.8;
  pair.rolling_friction = 0.6;
  materials.set_pair(0, 0, pair);
  double top = 0.0;
  for (const ParticleRecord& r : bed) top = std::max(top, r.position_m.z);
  WallSet walls;
  walls.add_cylinder(walls.add_body("barrel", {}), {0, 0, 0}, {0, 0, 1}, barrel_radius_m, top + 1e-3, true,
                     false, false, false, 0);
  walls.add_plane(walls.add_body("plate", {}), {0, 0, 0}, {0, 0, 1}, 0);
  ThermalWall hot_plate;
  hot_plate.mode = WallThermalMode::fixed;
  hot_plate.prescribed_temperature_K = TimeTable(973.15);
  SimulationSettings s;
  const double domain_top = options.drill ? std::max(top, options.drill->bounding_box().hi_m.z) : top;
  s.domain = {{-barrel_radius_m - 1e-3, -barrel_radius_m - 1e-3, -1e-3},
              {barrel_radius_m + 1e-3, barrel_radius_m + 1e-3, domain_top + 5e-3}};
  s.time_step_s = 0.2 * rayleigh_time_s(kRadius, kDensity, shear_modulus_Pa, kPoisson);
  s.min_particle_radius_m = kRadius;
  s.neighbor_skin_m = 0.2 * s.min_particle_radius_m;
  s.threads = options.threads;
  s.heat.enabled = options.heat;
  s.heat.time_scale_factor = options.time_scale_factor;
  std::vector<ThermalWall> thermal{ThermalWall{}, hot_plate};
  if (options.drill) {
    walls.add_mesh(walls.add_body("drill", options.drill_motion), *options.drill, 0);
    thermal.emplace_back();
  }
  Simulation sim(std::move(materials), std::move(walls), s, std::move(thermal));
  sim.particles.reserve(bed.size());
  for (const ParticleRecord& r : bed) {
    NewParticle p;
    p.position_m = r.position_m;
    p.radius_m = kRadius;  // older caches held shrunk radii
    p.density_kg_per_m3 = kDensity;
    p.temperature_K = 77.15;
    sim.add_particle(p);
  }
  return sim;
}

/// The soft bed stiffened decade by decade to the real modulus, at rest.
inline std::vector<ParticleRecord> stiffened_bed(std::vector<ParticleRecord> bed, int threads,
                                                double barrel_radius_m = kCylinderRadius) {
  for (double modulus : {3.0e7, 3.0e8}) {
    BedOptions options;
    options.threads = threads;
    options.shear_modulus_Pa = modulus;
    options.barrel_radius_m = barrel_radius_m;
    Simulation sim = paper_bed_simulation(bed, options);
    sim.advance(3000);
    for (std::size_t i = 0; i < sim.particles.size(); ++i) bed[i].position_m = sim.particles.position_m[i];
  }
  return bed;
}

/// The stiffened bed after its last decade at the real modulus (3,000 steps, which take
/// up the load), without heat: the stiffened records and a checkpoint of that state are
/// kept in the cache (made once, on 2 threads), so that a bench's setup is a restore.
/// The restored run continues exactly as the run that wrote it would have, with the
/// physics that wrote it: the checkpoint refuses another time step, other materials or
/// walls, but not another friction, contact law or stiffening. So the files' names carry
/// a version, kLoadedBedVersion: raise it when any of those changes (or when the settled
/// bed is poured again), and the bed is made anew.
inline constexpr int kLoadedBedVersion = 1;
inline Simulation loaded_bed_simulation(std::size_t count, int threads) {
  const char* dir = std::getenv("REGODEM_BENCH_CACHE");
  const std::string base = (std::filesystem::path(dir ? dir : ".") /
                            ("regodem-bench-bed-" + std::to_string(count) + "-loaded-v" +
                             std::to_string(kLoadedBedVersion)))
                               .string();
  const std::filesystem::path records = base + ".csv", state = base + ".rgck";
  if (!std::filesystem::exists(records) || !std::filesystem::exists(state)) {
    std::fprintf(stderr, "stiffening and loading the %zu-particle bed into %s.{csv,rgck} (once)...\n", count,
                 base.c_str());
    const std::vector<ParticleRecord> bed = stiffened_bed(settled_bed(count), 2);
    // The records first, whole or not at all; the checkpoint last (written whole by
    // write_checkpoint_file): where it exists, both are complete.
    const std::filesystem::path partial = base + ".csv.partial";
    {
      std::ofstream out(partial);
      out.precision(17);  // the walls are placed from these: exact, so the checkpoint fits
      out << "x,y,z,radius\n";
      for (const ParticleRecord& r : bed)
        out << r.position_m.x << ',' << r.position_m.y << ',' << r.position_m.z << ',' << r.radius_m << '\n';
      out.close();
      if (!out) throw std::runtime_error("could not write " + partial.string());
    }
    std::filesystem::rename(partial, records);
    BedOptions options;
    options.threads = 2;
    Simulation sim = paper_bed_simulation(bed, options);
    sim.advance(3000);
    Checkpoint checkpoint;
    sim.save_state(checkpoint);
    write_checkpoint_file(state, checkpoint);
  }
  BedOptions options;
  options.threads = threads;
  Simulation sim = paper_bed_simulation(read_particle_csv(records.string()), options);
  sim.restore_state(read_checkpoint_file(state));
  return sim;
}

}  // namespace regodem::bench
