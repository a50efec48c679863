#pragma once
// Runs the stages of a plan on a simulation: insertions, end conditions, overrides,
// time-series samples and progress reports to an observer, and a clean stop on request.
#include <atomic>
#include <cstdint>

#include "sim/run_checkpoint.hpp"
#include "sim/run_observer.hpp"
#include "sim/simulation.hpp"
#include "sim/stage_plan.hpp"

namespace regodem {

/// Under MPI a sample merges the ranks' sums and leaves the particles split, but every
/// this-many-th sample of a stage gathers them (where a periodic checkpoint may be taken).
inline constexpr std::int64_t kSamplesPerGather = 10;

/// The time-series columns a run reports (fixed part, then per wall body).
std::vector<SeriesColumn> time_series_columns(const Simulation& sim);
/// One time-series row matching time_series_columns().
std::vector<double> time_series_row(const Simulation& sim, std::size_t stage_index);

/// Runs the plan's stages; with `resume`, from a checkpoint of a run of the same plan:
/// its state is restored (at the stage boundary or inside the stage where it was
/// taken) and the run goes on bit for bit as it would have.
RunOutcome run_stages(Simulation& sim, StagePlan& plan, RunObserver& observer,
                      const std::atomic<bool>& stop_requested, const RunResume* resume = nullptr);

}  // namespace regodem
