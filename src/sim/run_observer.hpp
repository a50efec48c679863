#pragma once
// What a running scenario reports to whoever watches it (the command line's progress
// display, the CSV and summary writers). The simulation layer calls these hooks; it
// never prints or writes files itself.
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
