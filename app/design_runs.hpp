#pragma once
// The runs of a design study (`regodem calibrate`, `regodem envelope`): each point a
// `regodem run` child process into OUTDIR/runs/NAME, several at once; a run already
// completed with the same inputs is skipped, so an interrupted study continues where it
// stopped; progress lines with the time left; a failed run's own message.
#include <atomic>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "doe/calibration_spec.hpp"
#include "doe/central_composite_design.hpp"
#include "doe/response_surface_fit.hpp"
#include "doe/response_surface_solve.hpp"

namespace regodem::app {

namespace fs = std::filesystem;

std::string read_text(const fs::path& path);

/// `--set PATH=VALUE UNIT`: the number in its shortest exact form, so that the run
/// gets exactly the double the study computed.
std::string set_text(const std::string& path, double value, const std::string& unit);

/// The `--set` text of a factor at a value: its template with the number, or NUMBER UNIT.
std::string factor_set_text(const doe::CalibrationFactor& factor, double value);

/// "name [unit]", or the name alone without a unit.
std::string header(const std::string& name, const std::string& unit);

/// A response's quadratic surface over the design's points x: its `terms` (as `regodem fit
/// --terms`), or the full quadratic when empty; a failure names the response's place
/// (`where`) in its file.
doe::ResponseSurfaceFit fit_design_response(const std::vector<std::vector<double>>& x,
                                            const std::vector<double>& values,
                                            const std::vector<std::string>& factor_names, const std::string& terms,
                                            const std::string& name, const std::string& where);

struct NamedUnit {
  std::string name, unit;
};

/// runs.csv: run, point_type, each factor's value, each response's (y: per point, per response).
std::string runs_csv(const std::vector<doe::CalibrationFactor>& factors, const std::vector<NamedUnit>& responses,
                     const doe::CentralCompositeDesign& design, const std::vector<std::vector<double>>& y);

/// Each factor's smallest to largest value in the design (±α).
std::vector<doe::FactorRange> design_ranges(const doe::CentralCompositeDesign& design);

/// One `regodem run` of a study and what it was given.
struct PlannedRun {
  int number = 0;    // 1 the first, in the order of the study's progress lines
  std::string name;  // "reference", "point_03", "verification"
  std::string scenario;
  std::vector<std::string> set;
  std::string description;  // the factor values, for progress lines
};

/// A finished run's summary; one that is not JSON is named (InputError).
nlohmann::ordered_json read_summary(const fs::path& directory);

/// A number from a run's summary; a missing key is a mistake in the study's file (`where`).
double summary_number(const nlohmann::ordered_json& summary, const std::string& path, const std::string& where,
                      const std::string& run);

/// How a study starts each of its runs: this program, or this program over MPI ranks
/// through a launcher (`mpirun -np ranks regodem run ...`, docs/mpi.md).
struct RunLauncher {
  int ranks = 1;
  std::vector<std::string> mpirun{"mpirun"};  // the launcher and its own options, used when ranks > 1

  /// From `ranks_per_run` and the `--mpirun` text (split at spaces); InputError when empty.
  static RunLauncher from(int ranks, const std::string& mpirun_command);
  /// The launcher's words with the rank count: each "{ranks}" replaced by N, or "-np N"
  /// appended where none is given (mpirun, mpiexec). Empty for one rank.
  std::vector<std::string> launch_words() const;
  /// ", over N MPI ranks (mpirun ... -np N)" for a progress line; empty for one.
  std::string description() const;
  /// Runs at once: `option` or else `file`, when given (> 0); else the cores / (threads x ranks).
  int processes(int option, int file, int threads_per_run) const;
};

/// Runs, skips and reports batches of runs; keeps the progress count across batches.
class RunBatches {
 public:
  RunBatches(fs::path output, int processes, int threads_per_run, RunLauncher launcher, int total_runs,
             const std::atomic<int>& signals);

  fs::path directory(const PlannedRun& run) const { return output_ / "runs" / run.name; }
  fs::path log(const PlannedRun& run) const { return output_ / "logs" / (run.name + ".log"); }

  /// Runs those of `runs` not already done. Returns exit_status::success, interrupted
  /// or run_failed (after saying which run failed and why).
  int run(const std::vector<PlannedRun>& runs);

  int finished() const { return finished_; }

  /// A progress line on standard output, flushed (it must show in a file or a pipe).
  static void say(const std::string& line);

 private:
  fs::path output_;
  int processes_;
  int threads_per_run_;
  RunLauncher launcher_;
  int total_;
  const std::atomic<int>& signals_;
  std::string program_;
  int finished_ = 0, ran_ = 0;
  double run_wall_s_ = 0.0;
};

}  // namespace regodem::app
