#pragma once
// Runs the stages of a plan on a simulation: insertions, end conditions, overrides,
// time-series samples and progress reports to an observer, and a clean stop on request.
#include <atomic>

#include "sim/run_observer.hpp"
#include "sim/simulation.hpp"
#include "sim/stage_plan.hpp"

namespace regodem {

/// The time-series columns a run reports (fixed part, then per wall body).
std::vector<SeriesColumn> time_series_columns(const Simulation& sim);
/// One time-series row matching time_series_columns().
std::vector<double> time_series_row(const Simulation& sim, std::size_t stage_index);

RunOutcome run_stages(Simulation& sim, StagePlan& plan, RunObserver& observer,
                      const std::atomic<bool>& stop_requested);

}  // namespace regodem
