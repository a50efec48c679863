#pragma once
// One run of a scenario into its output directory, as `regodem run` and `regodem resume`
// make it and as the Python module drives it: the scenario read and built, the output
// directory checked, locked and cleared, the files that reproduce the run, the recorder
// (time series, measurements, snapshots, checkpoints), the run itself, summary.json and
// the line that says how it went.
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "checkpoint_keeper.hpp"
#include "commands.hpp"
#include "core/thread_choice.hpp"
#include "io/run_directory_lock.hpp"
#include "io/summary_json_writer.hpp"
#include "progress_display.hpp"
#include "run_recorder.hpp"
#include "scenario/scenario_builder.hpp"
#include "scenario/scenario_spec.hpp"
#include "sim/snapshot_capture.hpp"

namespace regodem::app {

/// How a run ended, whether the runner returned or threw.
struct RunEnding {
  RunStatus status = RunStatus::failed;
  int exit_code = exit_status::run_failed;
  RunOutcome outcome;
  bool thrown = false;  // the runner threw: under MPI, maybe on this rank alone
};

/// The threads a run uses: `requested` when above 0, else OMP_NUM_THREADS when set, else
/// the cores other runnable processes leave free (with a note saying so).
ThreadChoice choose_run_threads(int requested);

class RunSession {
 public:
  /// Reads the scenario (from `scenario_text` when given, options.scenario_path then
  /// naming it in messages and anchoring its relative paths), checks the output
  /// directory, takes its lock and builds the model with options.threads (> 0). `resume`
  /// (kept by the caller for the session's life): go on from its checkpoint into the same
  /// directory. Throws InputError, leaving the directory as it was. `writes_outputs` false:
  /// a rank other than 0 of a run under mpirun, which runs the same plan and touches no file.
  RunSession(const RunOptions& options, const ResumePoint* resume, std::optional<std::string> scenario_text = {},
             bool writes_outputs = true);
  RunSession(const RunSession&) = delete;
  RunSession& operator=(const RunSession&) = delete;
  ~RunSession();

  /// Lets another run use the directory (the run has ended).
  void release_directory() { lock_.reset(); }
  /// Gives up before begin(): the lock goes, and the directory if the lock made it.
  void abandon();
  /// Prepares the outputs: a resume's checkpoint checked against the model, the directory
  /// cleared of a previous run's files (--overwrite), the scenario copy, --set values and
  /// generated meshes written, the recorder set up. Progress lines go to `progress`
  /// (nullptr: nowhere). Throws InputError.
  void begin(std::FILE* progress);
  /// Runs every stage (or on from the checkpoint) until the end, a failure or
  /// stop_requested, reporting to the recorder and to `extra` when given.
  RunEnding run(const std::atomic<bool>& stop_requested, RunObserver* extra = nullptr);
  /// Writes summary.json and returns the final line; `stop_cause` names what stopped an
  /// interrupted run ("SIGINT"). Nothing, and an empty line, where the session writes no outputs.
  std::string finish(const RunEnding& ending, const std::string& stop_cause);

  const ScenarioSpec& spec() const { return spec_; }
  PreparedRun& prepared() { return *prepared_; }
  const std::filesystem::path& directory() const { return directory_; }
  const RunRecorder& recorder() const { return *recorder_; }
  const CheckpointKeeper& checkpoints() const { return *checkpoints_; }
  /// The scenario file a resume reads: the given one, or the copy of a scenario from text.
  std::filesystem::path identity_scenario_path() const;

 private:
  RunOptions options_;
  const ResumePoint* resume_ = nullptr;
  bool writes_outputs_ = true;
  RunObserver quiet_;  // what a session that writes no outputs reports to
  std::optional<std::string> scenario_text_;
  std::chrono::system_clock::time_point started_at_;
  ScenarioSpec spec_;
  std::optional<PreparedRun> prepared_;
  std::optional<RunDirectoryLock> lock_;  // held to the end of the run: one writer per directory
  std::filesystem::path directory_;
  std::unique_ptr<ProgressDisplay> display_;
  std::unique_ptr<RunRecorder> recorder_;
  std::optional<SimulationSnapshotWriter> snapshots_;
  std::unique_ptr<CheckpointKeeper> checkpoints_;
};

}  // namespace regodem::app
