// regodem: the command line. Parses the arguments and hands over to one subcommand
// (command_run.cpp, command_validate.cpp, command_info.cpp, command_plot.cpp,
// command_doe.cpp, command_fit.cpp, command_calibrate.cpp, command_envelope.cpp, command_estimate.cpp).
#include <exception>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "commands.hpp"
#include "core/error.hpp"
#include "scenario/units.hpp"

namespace {

constexpr const char* exit_status_help =
    "Exit status: 0 every stage finished (or the command succeeded); 1 a stage failed\n"
    "(blow-up, did not settle) or an internal error; 2 bad input (scenario, command line,\n"
    "output directory), nothing was run; 130 interrupted by SIGINT/SIGTERM.";

/// "10min", "2 h", "90 s": a wall-clock duration in seconds (the scenario's units).
double wall_duration_s(const std::string& text) {
  const double seconds = regodem::parse_quantity(text, regodem::Dimension::time);
  if (!(seconds > 0.0))
    throw regodem::InputError(fmt::format("--checkpoint-every must be a positive duration, got '{}'", text));
  return seconds;
}

constexpr const char* checkpoint_every_help =
    "Also write a checkpoint every DURATION of wall-clock time, e.g. 10min, 2h (besides the end of each stage "
    "and Ctrl-C)";

constexpr const char* set_help =
    "Override a scenario value, e.g. --set stages.settle.duration=\"0.2 s\" (key path as the "
    "file nests it, value as the file would write it); repeatable";

}  // namespace

int main(int argc, char** argv) {
  using namespace regodem::app;

  CLI::App app{"RegoDEM: discrete element simulation of granular media, for drilling in lunar regolith",
               "regodem"};
  app.set_version_flag("--version", version_line(), "Print the version and exit");
  app.require_subcommand(1);
  app.footer(exit_status_help);

  RunOptions run_options;
  CLI::App* run = app.add_subcommand("run", "Run every stage of a scenario and write its outputs");
  run->add_option("SCENARIO", run_options.scenario_path, "Scenario file (YAML)")
      ->required()
      ->check(CLI::ExistingFile);
  run->add_option("-o,--output", run_options.output_directory,
                  "Output directory (default: out/<scenario name> in the working directory); "
                  "must be new or empty unless --overwrite")
      ->type_name("OUTDIR");
  run->add_option("--threads", run_options.threads,
                  "OpenMP threads (default: OMP_NUM_THREADS, else the cores other runnable processes leave free)")
      ->type_name("N")
      ->check(CLI::Range(1, 4096));
  run->add_option("--set", run_options.overrides, set_help)
      ->type_name("KEY.PATH=VALUE")
      ->allow_extra_args(false);
  run->add_flag("--overwrite", run_options.overwrite,
                "Reuse a non-empty OUTDIR: replace the files a run writes, leave other files");
  std::string run_checkpoint_every;
  run->add_option("--checkpoint-every", run_checkpoint_every, checkpoint_every_help)->type_name("DURATION");
  run->footer(
      "Writes OUTDIR/time_series.csv (header: name [unit]), OUTDIR/summary.json, OUTDIR/scenario.yaml\n"
      "(a copy of SCENARIO) and OUTDIR/overrides.txt (the --set values); with output.snapshots, ParaView\n"
      "files OUTDIR/particles.pvd, OUTDIR/walls.pvd and OUTDIR/vtk/*.vtp. Checkpoints go to\n"
      "OUTDIR/checkpoints/ at the end of each stage, every --checkpoint-every and on Ctrl-C, which stops the run\n"
      "cleanly (exit status 130) and says how to go on: regodem resume OUTDIR; every further Ctrl-C or SIGTERM\n"
      "is the same request (Ctrl-\\ ends a run at once). Another process writing into OUTDIR is refused.");

  ResumeOptions resume_options;
  std::string resume_checkpoint_every;
  CLI::App* resume = app.add_subcommand(
      "resume", "Continue a run from its latest checkpoint, into the same OUTDIR, as if it had not stopped");
  resume->add_option("OUTDIR", resume_options.run_directory, "Output directory of the run")->required();
  resume->add_option("--threads", resume_options.threads,
                     "OpenMP threads (default: the run's own; any count continues bit for bit)")
      ->type_name("N")
      ->check(CLI::Range(1, 4096));
  resume->add_option("--checkpoint-every", resume_checkpoint_every, checkpoint_every_help)->type_name("DURATION");
  resume->footer(
      "Uses the newest readable OUTDIR/checkpoints/checkpoint_NNNNNN.rgck (a corrupt one is reported and the one\n"
      "before it used) and the run's scenario file, which must be unchanged. The CSV files are cut back to the\n"
      "checkpoint and continued, the .pvd collections likewise. See docs/checkpoint-format.md.");

  ValidateOptions validate_options;
  CLI::App* validate = app.add_subcommand(
      "validate", "Read and check a scenario, print the plan it makes (time step, walls, stages); runs nothing");
  validate->add_option("SCENARIO", validate_options.scenario_path, "Scenario file (YAML)")
      ->required()
      ->check(CLI::ExistingFile);
  validate->add_option("--set", validate_options.overrides, set_help)
      ->type_name("KEY.PATH=VALUE")
      ->allow_extra_args(false);

  PlotOptions plot_options;
  CLI::App* plot = app.add_subcommand("plot", "PNG figures from the CSV files and snapshots of one or more runs");
  plot->add_option("OUTDIR", plot_options.run_directories, "Output directories of runs (several: overlaid)")
      ->required();
  plot->add_option("--labels", plot_options.labels, "Legend labels, comma-separated, one per OUTDIR")
      ->type_name("A,B,...");
  plot->add_option("--out", plot_options.output_directory, "Folder for the PNG files (default: FIRST_OUTDIR/plots)")
      ->type_name("DIR");
  plot->add_flag("--section", plot_options.section,
                 "Also draw the particle temperature on a plane through an axis, from the latest snapshot");
  plot->add_option("--section-axis", plot_options.section_axis, "The axis the plane holds (default z)")
      ->check(CLI::IsMember({"x", "y", "z"}));
  plot->add_option("--section-through", plot_options.section_through,
                   "A point on the axis, in metres (default 0,0,0)")
      ->type_name("X,Y,Z");
  plot->add_option("--section-thickness", plot_options.section_thickness_m,
                   "0: show the disks the plane cuts from the spheres (default); > 0: every particle within "
                   "a slab this thick, in metres")
      ->check(CLI::NonNegativeNumber);
  plot->footer(
      "Writes temperature.png, wall_temperatures.png, energy_balance.png, wall_forces.png, mechanics.png, one PNG per\n"
      "further CSV (profiles), and section.png with --section; each 960 x 600 pixels. Needs /usr/bin/python3 with\n"
      "matplotlib (REGODEM_PYTHON names another). See docs/outputs.md.");

  DoeOptions doe_options;
  CLI::App* doe = add_doe_command(app, doe_options);
  FitOptions fit_options;
  CLI::App* fit = add_fit_command(app, fit_options);
  CalibrateOptions calibrate_options;
  CLI::App* calibrate = add_calibrate_command(app, calibrate_options);
  EnvelopeOptions envelope_options;
  CLI::App* envelope = add_envelope_command(app, envelope_options);
  EstimateCommandOptions estimate_options;
  CLI::App* estimate = add_estimate_command(app, estimate_options);

  CLI::App* info = app.add_subcommand(
      "info", "Print the version, build type, compiler, OpenMP threads and library versions");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    // CLI11 reports a misspelt subcommand only as "a subcommand is required".
    const std::vector<std::string> unparsed = app.remaining();
    if (app.get_subcommands().empty() && !unparsed.empty() && !unparsed.front().starts_with('-')) {
      fmt::print(stderr, "regodem: unknown command '{}'; the commands are run, resume, validate, estimate, plot, doe, fit, calibrate, envelope and info (see regodem --help)\n",
                 unparsed.front());
      return exit_status::bad_input;
    }
    // CLI11 prints the message (or the help/version) and gives its own codes (1xx);
    // every usage error is "bad input" here.
    return app.exit(error) == 0 ? exit_status::success : exit_status::bad_input;
  }

  try {
    if (*run) {
      if (!run_checkpoint_every.empty()) run_options.checkpoint_every_s = wall_duration_s(run_checkpoint_every);
      return run_scenario(run_options);
    }
    if (*resume) {
      if (!resume_checkpoint_every.empty()) resume_options.checkpoint_every_s = wall_duration_s(resume_checkpoint_every);
      return resume_run(resume_options);
    }
    if (*validate) return validate_scenario(validate_options);
    if (*info) return print_info();
    if (*plot) return plot_runs(plot_options);
    if (*doe) return run_doe(doe_options);
    if (*fit) return run_fit(fit_options);
    if (*calibrate) return run_calibrate(calibrate_options);
    if (*envelope) return run_envelope(envelope_options);
    if (*estimate) return estimate_scenario(estimate_options);
  } catch (const regodem::InputError& error) {
    fmt::print(stderr, "regodem: error: {}\n", error.what());
    return exit_status::bad_input;
  } catch (const std::exception& error) {
    fmt::print(stderr, "regodem: internal error: {}\n", error.what());
    return exit_status::run_failed;
  }
  return exit_status::bad_input;  // unreachable: require_subcommand(1)
}
