#pragma once
// The subcommands of `regodem`: main.cpp parses the command line into these options
// and calls one function; each lives in its own command_*.cpp.
#include <string>
#include <vector>

#include "io/checkpoint_file.hpp"

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
};

/// `regodem resume` (command_resume.cpp).
struct ResumeOptions {
  std::string run_directory;
  int threads = 0;  // 0: the run's own (the same thread count continues bit for bit)
  double checkpoint_every_s = 0.0;
};

/// A checkpoint `regodem resume` chose, with what it found on the way.
struct ResumePoint {
  Checkpoint checkpoint;
  std::string file;
  std::vector<std::string> skipped;  // newer checkpoints that could not be used, and why
};

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

int run_scenario(const RunOptions& options);
/// Runs on from a checkpoint into options.output_directory (command_run.cpp).
int continue_run(const RunOptions& options, const ResumePoint& resume);
int resume_run(const ResumeOptions& options);
int plot_runs(const PlotOptions& options);
int validate_scenario(const ValidateOptions& options);
int print_info();

/// The version line of `regodem --version`.
std::string version_line();

}  // namespace regodem::app
