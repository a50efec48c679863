#pragma once
// The RunObserver of `regodem run`: passes progress to the display, samples to the
// time-series CSV, keeps each stage's result and times for summary.json, and writes
// checkpoints with what the outputs hold so far (a resumed run cuts them back to it).
#include <chrono>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "checkpoint_keeper.hpp"
#include "io/csv_time_series_writer.hpp"
#include "io/summary_json_writer.hpp"
#include "progress_display.hpp"
#include "sim/run_observer.hpp"
#include "sim/snapshot_capture.hpp"

namespace regodem::app {

class RunRecorder final : public RunObserver {
 public:
  /// `planned_stage_names`: every stage of the scenario, so that summary.json lists
  /// those never reached too.
  RunRecorder(std::filesystem::path time_series_path, ProgressDisplay& display,
              const std::vector<std::string>& planned_stage_names);

  void columns(const std::vector<SeriesColumn>& columns) override;
  void stage_started(const StageInfo& stage) override;
  void progress(const ProgressSnapshot& snapshot) override;
  void sample(const std::vector<double>& row) override;
  void snapshot(const Simulation& sim) override;
  void notice(const std::string& message) override;
  void stage_finished(const StageInfo& stage, StageResult result, const std::string& message) override;
  /// Appends the events to the breakage CSV, created at the first broken bond.
  void bonds_broken(const std::vector<BondBreakEvent>& events) override;
  void set_bond_breaks_path(std::filesystem::path path) { bond_breaks_path_ = std::move(path); }
  /// Creates DIRECTORY/FOLDER/NAME.csv for each table (regions, bands, profiles).
  void measurement_tables(const std::vector<MeasurementTable>& tables) override;
  void measurement_rows(std::size_t table, const std::vector<std::vector<double>>& rows) override;
  void set_measurements_directory(std::filesystem::path directory) { measurements_directory_ = std::move(directory); }
  /// Each table with its file and its last sample, for summary.json.
  const std::vector<MeasurementFinal>& measurement_finals() const { return measurement_finals_; }

  /// Checkpoints go to `keeper`, with the run's identity.
  void keep_checkpoints_with(CheckpointKeeper* keeper, RunIdentity identity) {
    checkpoints_ = keeper;
    identity_ = std::move(identity);
  }
  bool checkpoint_due() override;
  void checkpoint(const RunState& state) override;
  /// A resumed run: the outputs as the checkpoint knew them (CSV lengths, snapshot
  /// collections, stage records, notices); call before the run starts.
  void resume_outputs(const Checkpoint& checkpoint);
  /// Why the last checkpoint could not be written, if it could not.
  const std::string& checkpoint_failure() const { return checkpoint_failure_; }

  /// Stage records. The last stage started ends at `final_time_s` (the run's simulated
  /// time when it returned) and, if it never reported its end (the run threw), gets
  /// `result_if_unfinished`.
  std::vector<StageSummary> stage_summaries(double final_time_s,
                                            StageResult result_if_unfinished) const;
  /// Where snapshots go; without one, due snapshots are not written.
  void write_snapshots_with(SimulationSnapshotWriter* writer) { snapshots_ = writer; }

  /// The stage running or last run, if any started.
  std::optional<StageInfo> current_stage() const { return current_stage_; }
  /// The latest progress report, if any came.
  std::optional<ProgressSnapshot> last_snapshot() const { return last_snapshot_; }
  const std::vector<std::string>& notices() const { return notices_; }

 private:
  using Clock = std::chrono::steady_clock;

  std::filesystem::path time_series_path_;
  ProgressDisplay& display_;
  std::unique_ptr<CsvTimeSeriesWriter> time_series_;
  SimulationSnapshotWriter* snapshots_ = nullptr;
  std::filesystem::path bond_breaks_path_;
  std::unique_ptr<CsvTimeSeriesWriter> bond_breaks_;
  std::filesystem::path measurements_directory_;
  std::vector<std::unique_ptr<CsvTimeSeriesWriter>> measurement_writers_;
  std::vector<MeasurementFinal> measurement_finals_;
  std::vector<StageSummary> stages_;
  std::optional<StageInfo> current_stage_;
  std::optional<ProgressSnapshot> last_snapshot_;
  std::vector<std::string> notices_;
  std::optional<std::size_t> last_started_index_;
  Clock::time_point stage_wall_start_;
  CheckpointKeeper* checkpoints_ = nullptr;
  RunIdentity identity_;
  std::string checkpoint_failure_;
  // A resumed run's time series: continue the file at this length instead of a new one.
  std::optional<std::pair<std::uintmax_t, std::size_t>> continue_time_series_;
  // A resumed run's measurement files, in table order: where to cut them back to.
  struct MeasurementContinuation {
    std::uint64_t bytes = 0, rows = 0, samples = 0;
    std::vector<std::vector<double>> last_rows;
  };
  std::vector<MeasurementContinuation> continue_measurements_;
};

}  // namespace regodem::app
