#pragma once
// What a running scenario reports to whoever watches it (the command line's progress
// display, the CSV and summary writers). The simulation layer calls these hooks; it
// never prints or writes files itself.
#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "contact/bond_store.hpp"

namespace regodem {

class Simulation;
struct RunState;

struct StageInfo {
  std::string name;
  std::size_t index = 0;   // 0-based
  std::size_t count = 0;   // number of stages
  double start_time_s = 0.0;
  /// Simulated time at which the stage ends if it runs to a time limit; for a
  /// "settled" stage this is its max_duration limit (may be infinite).
  double planned_end_time_s = 0.0;
  bool ends_when_settled = false;
  /// Simulated time at which the stage ended; set in stage_finished(), NaN before.
  double end_time_s = std::numeric_limits<double>::quiet_NaN();
};

struct ProgressSnapshot {
  StageInfo stage;
  double time_s = 0.0;
  std::uint64_t step = 0;
  std::size_t particles = 0;
  double wall_s = 0.0;               // since the run started
  double steps_per_s = 0.0;          // recent rate
  double particle_steps_per_s = 0.0; // recent rate
  double estimated_remaining_s = -1; // wall seconds left in this stage; < 0 unknown
  double kinetic_energy_per_particle_J = 0.0;
};

/// One named, unit-carrying column of the time series; the header is "name [unit]".
struct SeriesColumn {
  std::string name;
  std::string unit;  // "-" for dimensionless counts
};

/// A measurement's table (the scenario's `measurements`): written to FOLDER/NAME.csv.
struct MeasurementTable {
  std::string name;
  std::string kind;    // "region", "band" or "profile"
  std::string folder;  // "regions" (regions and bands) or "profiles"
  std::vector<SeriesColumn> columns;
};

enum class StageResult { finished, failed, interrupted };

class RunObserver {
 public:
  virtual ~RunObserver() = default;
  /// Called once before the first stage with the time-series columns.
  virtual void columns(const std::vector<SeriesColumn>& /*columns*/) {}
  virtual void stage_started(const StageInfo& /*stage*/) {}
  /// Called every progress_interval_s() of wall time; the observer decides how often to show it.
  virtual void progress(const ProgressSnapshot& /*snapshot*/) {}
  /// Wall seconds between progress() calls (checked at step boundaries).
  virtual double progress_interval_s() const { return 0.25; }
  /// The run's wall clock, seconds from any origin: what progress, the rates and the time
  /// left are measured with (a test gives one that does not depend on the machine's load).
  virtual double wall_clock_s() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  }
  /// One row of the time series, values in the order of columns().
  virtual void sample(const std::vector<double>& /*row*/) {}
  /// A snapshot (ParaView files) is due by the plan's SnapshotSchedule: the observer
  /// reads what it needs from the simulation, which does not change meanwhile.
  virtual void snapshot(const Simulation& /*sim*/) {}
  /// A message worth telling the user (an insertion region that is full, ...).
  virtual void notice(const std::string& /*message*/) {}
  virtual void stage_finished(const StageInfo& /*stage*/, StageResult /*result*/,
                              const std::string& /*message*/) {}
  /// Bonds that broke in the last step, in the order they broke.
  virtual void bonds_broken(const std::vector<BondBreakEvent>& /*events*/) {}
  /// Called once before the first stage with the measurements' tables (none: not called).
  virtual void measurement_tables(const std::vector<MeasurementTable>& /*tables*/) {}
  /// Rows of table `table` taken at one instant: one for a region or band, one per bin
  /// for a profile; values in the order of its columns.
  virtual void measurement_rows(std::size_t /*table*/, const std::vector<std::vector<double>>& /*rows*/) {}
  /// Asked at step boundaries every few dozen steps: whether to write a checkpoint now
  /// (a wall-clock interval).
  virtual bool checkpoint_due() { return false; }
  /// A checkpoint of the run as it stands (sim/run_checkpoint.hpp): when due, at the end
  /// of every stage, and before returning on a stop request. The run can go on from it.
  virtual void checkpoint(const RunState& /*state*/) {}
  /// Called at every step boundary, after that instant's samples, snapshots and end
  /// checks and before the step (mechanical or, in a static-bed stage, thermal): the
  /// simulation is in a state a checkpoint could take. The Python module pauses a run
  /// here (python/src/run_binding.cpp); the command line does nothing.
  virtual void before_step(const Simulation& /*sim*/) {}
};

/// Hands every report to two observers, `first` then `second` (the command line's
/// recorder and a second watcher, e.g. Python's); a checkpoint is due when either says so.
class ObserverPair final : public RunObserver {
 public:
  ObserverPair(RunObserver& first, RunObserver& second) : first_(first), second_(second) {}
  void columns(const std::vector<SeriesColumn>& c) override { first_.columns(c), second_.columns(c); }
  void stage_started(const StageInfo& s) override { first_.stage_started(s), second_.stage_started(s); }
  void progress(const ProgressSnapshot& p) override { first_.progress(p), second_.progress(p); }
  double progress_interval_s() const override {
    return std::min(first_.progress_interval_s(), second_.progress_interval_s());
  }
  double wall_clock_s() const override { return first_.wall_clock_s(); }
  void sample(const std::vector<double>& row) override { first_.sample(row), second_.sample(row); }
  void snapshot(const Simulation& sim) override { first_.snapshot(sim), second_.snapshot(sim); }
  void notice(const std::string& m) override { first_.notice(m), second_.notice(m); }
  void stage_finished(const StageInfo& s, StageResult r, const std::string& m) override {
    first_.stage_finished(s, r, m), second_.stage_finished(s, r, m);
  }
  void bonds_broken(const std::vector<BondBreakEvent>& e) override { first_.bonds_broken(e), second_.bonds_broken(e); }
  void measurement_tables(const std::vector<MeasurementTable>& t) override {
    first_.measurement_tables(t), second_.measurement_tables(t);
  }
  void measurement_rows(std::size_t table, const std::vector<std::vector<double>>& rows) override {
    first_.measurement_rows(table, rows), second_.measurement_rows(table, rows);
  }
  bool checkpoint_due() override {
    const bool a = first_.checkpoint_due();
    const bool b = second_.checkpoint_due();
    return a || b;
  }
  void checkpoint(const RunState& state) override { first_.checkpoint(state), second_.checkpoint(state); }
  void before_step(const Simulation& sim) override { first_.before_step(sim), second_.before_step(sim); }

 private:
  RunObserver& first_;
  RunObserver& second_;
};

struct RunOutcome {
  bool completed = false;            // every stage finished
  bool interrupted = false;          // stopped by a signal
  std::string message;               // why it stopped, when not completed
  std::size_t stages_finished = 0;
  std::size_t particles = 0;
  std::uint64_t steps = 0;
  double simulated_time_s = 0.0;
  double wall_s = 0.0;
  double particle_steps_per_s = 0.0;  // sum of particles over steps / wall time
  double time_step_s = 0.0;
  int threads = 1;
  bool bonds_configured = false;  // the scenario has bond kinds
  BondCounts bonds;
};

}  // namespace regodem
