// Particle-steps per second of the contact + integration step on the settled paper
// bed (bench/paper_bed.hpp: 0.6 mm particles, G = 3e9 Pa, 0.2 of the Rayleigh time),
// only once the bed has been stiffened to the real modulus (contacts_per_particle
// reports it); and of a pour.
//
// heat=1 adds contact conduction (paper Eq. 1, 2) from a bottom plate at 700 degC into
// particles at -196 degC, updated every step.
//
//   build/release/bench/bench_settled_bed --benchmark_counters_tabular=true
// (REGODEM_BENCH_THREADS="1,2,4,8,16" for other thread counts, bench_threads.hpp)
#include <benchmark/benchmark.h>

#include <map>

#include "bench_threads.hpp"
#include "paper_bed.hpp"

namespace regodem::bench {
namespace {

void BM_SettledBed(benchmark::State& state) {
  const auto count = static_cast<std::size_t>(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  const bool heat = state.range(2) != 0;
  // Stiffened once per bed size (on two threads) and shared by every case and repetition.
  static std::map<std::size_t, std::vector<ParticleRecord>> stiffened;
  if (!stiffened.count(count)) stiffened[count] = stiffened_bed(settled_bed(count), 2);
  const std::vector<ParticleRecord>& bed = stiffened[count];
  const double rss_before = resident_bytes();
  BedOptions options;
  options.threads = threads;
  options.heat = heat;
  Simulation sim = paper_bed_simulation(bed, options);
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
    ->ArgNames({"particles", "threads", "heat"})
    ->ArgsProduct({{20000, 100000}, bench_thread_counts(), {0, 1}})
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
}  // namespace regodem::bench

BENCHMARK_MAIN();
