#pragma once
// The subcommands of `regodem`: main.cpp parses the command line into these options
// and calls one function; each lives in its own command_*.cpp.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "io/checkpoint_file.hpp"
namespace CLI {
class App;
}

namespace regodem::app {

/// Exit statuses, documented in `regodem --help`.
namespace exit_status {
inline constexpr int success = 0;
inline constexpr int run_failed = 1;   // a stage failed (blow-up, did not settle) or an internal error
inline constexpr int bad_input = 2;    // scenario, command line or output directory is wrong; nothing ran
inline constexpr int interrupted = 130;  // SIGINT or SIGTERM (128 + SIGINT, as shells report Ctrl-C)
}  // namespace exit_status

struct RunOptions {
  std::string scenario_path;
  std::string output_directory;  // empty: out/<scenario name>
  int threads = 0;               // 0: OpenMP's default
  std::vector<std::string> overrides;  // key.path=value
  bool overwrite = false;
  double checkpoint_every_s = 0.0;  // wall clock; 0: only at stage ends and on Ctrl-C
  int mpi_ranks = 1;                // the ranks the run is split over (set under mpirun, for summary.json)
};

/// `regodem resume` (command_resume.cpp).
struct ResumeOptions {
  std::string run_directory;
  int threads = 0;  // 0: the run's own (any thread count continues bit for bit)
  double checkpoint_every_s = 0.0;
};

/// A checkpoint `regodem resume` chose, with what it found on the way.
struct ResumePoint {
  Checkpoint checkpoint;
  std::string file;
  std::vector<std::string> skipped;  // newer checkpoints that could not be used, and why
};

/// What `regodem resume` found in a run's directory: the checkpoint to go on from and
/// the run's options, or that the run has completed (and the message that says so).
struct ResumeChoice {
  ResumePoint point;
  RunOptions run;
  bool completed = false;
  std::string completed_message;
};

/// Chooses the checkpoint (command_resume.cpp), telling `note` what it meets on the way
/// as it meets it (checkpoints skipped, another thread count). Throws InputError: no run
/// there, none usable, a live run holding the directory, the scenario gone.
ResumeChoice choose_resume(const ResumeOptions& options, const std::function<void(const std::string&)>& note = {});

struct ValidateOptions {
  std::string scenario_path;
  std::vector<std::string> overrides;
};

/// `regodem plot` (command_plot.cpp).
struct PlotOptions {
  std::vector<std::string> run_directories;  // OUTDIRs of runs, overlaid
  std::string labels;                        // comma-separated, one per run; empty: folder names
  std::string output_directory;              // empty: FIRST_OUTDIR/plots
  bool section = false;                      // also the temperature field on a section
  std::string section_axis = "z";
  std::string section_through = "0,0,0";     // a point on the axis, metres
  double section_thickness_m = 0.0;          // 0: cut spheres; > 0: a slab
};

/// `regodem doe ccd` (command_doe.cpp).
struct DoeOptions {
  std::vector<std::string> factors;  // NAME[ [unit]]=CENTRE:STEP
  std::string alpha = "rotatable";   // rotatable | face | a number
  int centre_points = 3;
  bool half_fraction = false;
  std::string order = "standard";  // standard | random
  std::uint64_t seed = 1;
  std::string output_path;  // empty: stdout
};

/// `regodem fit` (command_fit.cpp).
struct FitOptions {
  std::string runs_path;
  std::string factors;                 // A,B,...
  std::vector<std::string> responses;  // column names
  std::vector<std::string> terms;      // "A,B,B^2" for all, or "RESPONSE=A,B,B^2"
  std::string json_path;               // empty: no JSON
  std::vector<std::string> solve;      // RESPONSE=TARGET[,RESPONSE=TARGET...]
  std::vector<std::string> fix;        // FACTOR=VALUE
  std::vector<std::string> then;       // RESPONSE=TARGET[:FACTOR]
};

/// `regodem calibrate` (command_calibrate.cpp).
struct CalibrateOptions {
  std::string calibration_path;
  std::string output_directory;  // empty: out/<calibration file stem>
  int processes = 0;             // 0: the file's `processes`
  int ranks_per_run = 0;         // 0: the file's `ranks_per_run`
  // How a run over ranks is started: ranks not bound to cores, since several runs share them.
  std::string mpirun = "mpirun --bind-to none";
};

/// `regodem envelope` (command_envelope.cpp).
struct EnvelopeOptions {
  std::string envelope_path;
  std::string output_directory;  // empty: out/<envelope file stem>
  int processes = 0;             // 0: the file's `processes`
  int ranks_per_run = 0;         // 0: the file's `ranks_per_run`
  // How a run over ranks is started: ranks not bound to cores, since several runs share them.
  std::string mpirun = "mpirun --bind-to none";
};

/// `regodem estimate` (command_estimate.cpp).
struct EstimateCommandOptions {
  std::string scenario_path;
  std::vector<std::string> overrides;  // key.path=value
  int threads = 0;                     // 0: OpenMP's default
  std::string json_path;               // empty: no JSON
  double solid_fraction = 0.6;         // of the geometric beds
  std::uint64_t sample_steps = 300;    // per stage
  double sample_seconds = 5.0;         // wall-clock cap of one stage's timed steps
  std::vector<int> ranks;              // MPI rank counts to project the run onto
  double latency_us = 2.0;             // of the network the ranks would share
  double bandwidth_GB_per_s = 10.0;    // per rank
};

/// Each adds its subcommand (with its options bound to `options`) to `app`.
CLI::App* add_doe_command(CLI::App& app, DoeOptions& options);
CLI::App* add_fit_command(CLI::App& app, FitOptions& options);
CLI::App* add_calibrate_command(CLI::App& app, CalibrateOptions& options);
CLI::App* add_envelope_command(CLI::App& app, EnvelopeOptions& options);
CLI::App* add_estimate_command(CLI::App& app, EstimateCommandOptions& options);

int run_scenario(const RunOptions& options);
/// Runs on from a checkpoint into options.output_directory (command_run.cpp).
int continue_run(const RunOptions& options, const ResumePoint& resume);
int resume_run(const ResumeOptions& options);
int run_doe(const DoeOptions& options);
int run_fit(const FitOptions& options);
int run_calibrate(const CalibrateOptions& options);
int run_envelope(const EnvelopeOptions& options);
int estimate_scenario(const EstimateCommandOptions& options);
int plot_runs(const PlotOptions& options);
int validate_scenario(const ValidateOptions& options);
int print_info();

/// The version line of `regodem --version`.
std::string version_line();

}  // namespace regodem::app
