#pragma once
// Takes a plan's measurements during a run: asks each one's clock once per step (a few
// comparisons; nothing else happens between samples) and, when one is due, makes one
// pass over the particles and hands its rows to the observer.
#include <vector>

#include "sim/measurement_plan.hpp"
#include "sim/run_observer.hpp"

namespace regodem {

class Simulation;

/// The measurement's table: its columns, each with its unit.
MeasurementTable measurement_table(const Measurement& m, const Simulation& sim);
/// The rows of one sample of the measurement (one; one per bin for a profile).
std::vector<std::vector<double>> measurement_rows(const Measurement& m, const Simulation& sim);

/// The current value of one quantity of a region or band (NaN when it holds no
/// particle): one pass over the particles.
double measured_value(const Measurement& m, const Simulation& sim, MeasuredQuantity quantity);
/// Whether a stage's measured end condition holds now (never for a NaN value).
bool target_reached(const MeasurementPlan& plan, const MeasurementTarget& target, const Simulation& sim);

/// Time-series columns of the thermal history (none unless the run tracks it): the
/// highest peak temperature, the fraction of particles whose peak went above the
/// threshold, the mean time above it.
std::vector<SeriesColumn> thermal_history_columns(const Simulation& sim);
std::vector<double> thermal_history_row(const Simulation& sim);

class MeasurementRunner {
 public:
  explicit MeasurementRunner(const MeasurementPlan& plan);
  MeasurementRunner(const MeasurementRunner&) = delete;  // the clocks point into plan_
  MeasurementRunner& operator=(const MeasurementRunner&) = delete;

  bool empty() const { return plan_.empty(); }
  /// Tells the observer the tables (once, before the first stage).
  void announce(const Simulation& sim, RunObserver& observer) const;
  /// The measurements that sample with the time series: call at each time-series sample.
  void with_time_series(const Simulation& sim, RunObserver& observer);
  /// Whether before_step() would take any now.
  bool due(const Simulation& sim, double half_step_s) const;
  /// Before each step (as the snapshots): takes those that are due.
  void before_step(const Simulation& sim, double half_step_s, RunObserver& observer);
  /// At the end of a stage: those whose schedule adds one there.
  void at_stage_end(const Simulation& sim, RunObserver& observer);
  void count_step();

  /// The clocks' states, one per measurement in plan order (checkpoints).
  std::vector<MeasurementClock::State> clock_states() const;
  /// Throws std::invalid_argument when the count does not match the plan.
  void restore_clocks(const std::vector<MeasurementClock::State>& states);

 private:
  double depth_m(const Simulation& sim, const Measurement& m) const;
  void take(std::size_t k, const Simulation& sim, double half_step_s, RunObserver& observer);

  MeasurementPlan plan_;
  std::vector<MeasurementClock> clocks_;  // point into plan_
};

}  // namespace regodem
