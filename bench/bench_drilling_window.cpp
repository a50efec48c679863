// The real drilling workload: a window of the reduced sieve model
// (scenarios/paper/drill-sieve-reduced.yaml: 11,600 grains with ice bonds, the auger
// turning at 16,000 rpm and feeding 40 mm/s, the five-segment sieve, heat on, S = 80),
// from a checkpoint taken with the drill 25 mm down, half way. Each run restores that
// checkpoint and times the next steps: particle-steps per second of the whole step, and
// the neighbour rebuilds, contacts and bonds of the window.
//
//   bench/make_drilling_window.sh build/release/regodem /work/bench-cache   # once
//   REGODEM_BENCH_CACHE=/work/bench-cache build/release/bench/bench_drilling_window --benchmark_counters_tabular=true
//
// REGODEM_DRILLING_WINDOW names another checkpoint file (of the same scenario);
// REGODEM_SOURCE_DIR another source tree to read the scenario from (a copy on another
// machine); REGODEM_BENCH_THREADS the thread counts (bench_threads.hpp).
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <string>

#include "bench_threads.hpp"
#include "drilling_window.hpp"
#include "state_hash.hpp"
#include "io/checkpoint_file.hpp"
#include "scenario/scenario_builder.hpp"
#include "scenario/scenario_reader.hpp"
#include "sim/simulation.hpp"

namespace regodem::bench {
namespace {

struct Window {
  PreparedRun run;
  Checkpoint checkpoint;
};

Window& window_for(int threads) {
  static std::map<int, std::unique_ptr<Window>> built;
  std::unique_ptr<Window>& slot = built[threads];
  if (!slot) {
    const std::string checkpoint_path = window_checkpoint_path();
    const std::string scenario = window_scenario_path(REGODEM_SOURCE_DIR);
    // The grains come from the window itself (restored below); the bed is not needed.
    const ScenarioSpec spec = read_scenario_file(scenario, {"initial_state.checkpoint=" + checkpoint_path});
    slot = std::make_unique<Window>(Window{PreparedRun::build(spec, threads), read_checkpoint_file(checkpoint_path)});
  }
  return *slot;
}

void BM_DrillingWindow(benchmark::State& state) {
  if (window_checkpoint_path().empty() || !std::filesystem::is_regular_file(window_checkpoint_path())) {
    state.SkipWithError("no drilling window: run bench/make_drilling_window.sh (or set REGODEM_DRILLING_WINDOW)");
    return;
  }
  const int threads = static_cast<int>(state.range(0));
  Window& w = window_for(threads);
  Simulation& sim = w.run.simulation();
  std::uint64_t rebuilds = 0;
  for (auto _ : state) {
    state.PauseTiming();
    sim.restore_state(w.checkpoint);
    const std::uint64_t rebuilds_before = sim.neighbor_list().rebuild_count();
    state.ResumeTiming();
    sim.advance(kWindowSteps);
    state.PauseTiming();
    rebuilds += sim.neighbor_list().rebuild_count() - rebuilds_before;
    state.ResumeTiming();
  }
  const double steps = static_cast<double>(state.iterations() * kWindowSteps);
  state.SetItemsProcessed(static_cast<std::int64_t>(steps * static_cast<double>(sim.particles.size())));
  state.counters["particle_steps_per_s"] =
      benchmark::Counter(steps * static_cast<double>(sim.particles.size()), benchmark::Counter::kIsRate);
  state.counters["particles"] = static_cast<double>(sim.particles.size());
  state.counters["rebuilds_per_1000_steps"] = 1000.0 * static_cast<double>(rebuilds) / steps;
  state.counters["contacts_per_particle"] =
      static_cast<double>(sim.contact_statistics().particle_contacts) / static_cast<double>(sim.particles.size());
  state.counters["bonds_per_particle"] =
      static_cast<double>(sim.bonds().size()) / static_cast<double>(sim.particles.size());
  // The state after the window: the same on every thread count, bit for bit
  // (docs/architecture.md).
  const std::uint32_t hash = state_hash(sim.particles);
  state.counters["state_hash"] = static_cast<double>(hash);
  for (const WallBody& body : sim.walls.bodies)
    if (body.name == "drill") state.counters["drill_depth_mm"] = 1e3 * (body.depth_at_start_m + body.travel_m);
}
BENCHMARK(BM_DrillingWindow)
    ->ArgName("threads")
    ->ArgsProduct({bench_thread_counts()})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->UseRealTime();

}  // namespace
}  // namespace regodem::bench

BENCHMARK_MAIN();
