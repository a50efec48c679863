// The auger drilling into the settled 20,000-particle paper bed (bench/paper_bed.hpp:
// 0.6 mm particles, G = 3e9 Pa, 0.2 of the Rayleigh time, 30 mm barrel, bed 5.4 mm
// deep): particle-steps per second while it cuts, and the share of the step that the
// drill costs (mesh contact search and forces, and the extra neighbour-list rebuilds
// its motion causes), from the same bed without the drill.
//
// Drill: outer 10 mm, core 5 mm, pitch 8 mm, 2 flutes 1.2 mm thick, 40 mm long, 118
// degree cone tip, 64 facets per turn. It turns at 200 rpm (the paper's) and feeds at
// 1 m/s, 2,000 times the paper's 0.5 mm/s, so that it cuts 0.2 micrometre per step:
// its tip starts 0.3 mm above the bed, and 19,000 steps (3.8 mm) bring it 3.5 mm into
// the bed (the cone, 1.5 mm, and two flute turns' worth of blade edge) before the
// timed steps.
//
//   REGODEM_BENCH_CACHE=/work/bench-cache build/release/bench/bench_auger_drilling --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <map>
#include <numbers>

#include "geometry/auger_generator.hpp"
#include "paper_bed.hpp"

namespace regodem::bench {
namespace {

const std::vector<ParticleRecord>& stiffened_20k() {
  static const std::vector<ParticleRecord> bed = stiffened_bed(settled_bed(20000), 2);
  return bed;
}

Simulation drilling_bed(int threads, bool with_drill) {
  const std::vector<ParticleRecord>& bed = stiffened_20k();
  double top = 0.0;
  for (const ParticleRecord& r : bed) top = std::max(top, r.position_m.z + kRadius);
  BedOptions options;
  options.threads = threads;
  if (with_drill) {
    AugerSpec auger;
    auger.outer_diameter_m = 10e-3;
    auger.core_diameter_m = 5e-3;
    auger.pitch_m = 8e-3;
    auger.flutes = 2;
    auger.flute_thickness_m = 1.2e-3;
    auger.length_m = 40e-3;
    auger.tip = AugerTip::cone;
    TriangleMesh drill = make_auger(auger);
    const Vec3 tip{0.0, 0.0, top + 0.3e-3};
    drill.apply(MeshTransform::from_axis_angle(1.0, {0, 0, 1}, 0.0, tip));
    options.drill = std::move(drill);
    options.drill_motion.velocity_m_per_s = {0.0, 0.0, -1.0};
    options.drill_motion.angular_velocity_rad_per_s = {0.0, 0.0, 200.0 * 2.0 * std::numbers::pi / 60.0};
    options.drill_motion.axis_point_m = tip;
  }
  Simulation sim = paper_bed_simulation(bed, options);
  sim.advance(19000);  // settle at the real modulus; the drill cuts 3.5 mm into the bed
  return sim;
}

void BM_AugerDrilling(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  const bool with_drill = state.range(1) != 0;
  Simulation sim = drilling_bed(threads, with_drill);
  const std::uint64_t rebuilds_before = sim.neighbor_list().rebuild_count();
  for (auto _ : state) sim.step();
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * sim.particles.size()));
  state.counters["particles"] = static_cast<double>(sim.particles.size());
  state.counters["rebuilds_per_1000_steps"] =
      1000.0 * static_cast<double>(sim.neighbor_list().rebuild_count() - rebuilds_before) /
      static_cast<double>(state.iterations());
  if (with_drill) {
    const WallBody& drill = sim.walls.bodies.back();
    state.counters["drill_depth_mm"] = 1e3 * (-drill.displacement_m.z - 0.3e-3);
    state.counters["wall_contacts"] = static_cast<double>(sim.contact_statistics().wall_contacts);
    state.counters["thrust_N"] = drill.force_N.z;
    state.counters["mesh_entries"] = static_cast<double>(sim.neighbor_list().mesh_triangle.size());
  }
}
BENCHMARK(BM_AugerDrilling)
    ->ArgNames({"threads", "drill"})
    ->ArgsProduct({{1, 2}, {0, 1}})
    ->Unit(benchmark::kMillisecond)->Iterations(2000)->UseRealTime();

}  // namespace
}  // namespace regodem::bench

BENCHMARK_MAIN();
