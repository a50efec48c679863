// `regodem plot`: PNG figures from runs' CSV files and snapshots. The drawing is done by
// scripts/regodem_plot.py with Debian's /usr/bin/python3 and matplotlib (a real
// plotting tool, as issue 8 asks); this file checks the arguments, finds the script and
// the interpreter, and runs it with the arguments as given (no shell in between).
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include <fmt/format.h>

#include "commands.hpp"
#include "plot_script.hpp"
#include "core/error.hpp"

namespace regodem::app {
namespace {

namespace fs = std::filesystem;

void check_options(const PlotOptions& options) {
  for (const std::string& directory : options.run_directories) {
    std::error_code error;
    if (!fs::is_directory(directory, error))
      throw InputError(fmt::format("'{}' is not a directory; give the OUTDIR of a `regodem run`", directory));
    const bool has_output = fs::exists(fs::path(directory) / "time_series.csv", error) ||
                            fs::exists(fs::path(directory) / "particles.pvd", error);
    if (!has_output)
      throw InputError(fmt::format("'{}' holds no time_series.csv and no particles.pvd; is it the OUTDIR of a "
                                   "`regodem run`?",
                                   directory));
  }
  if (!options.labels.empty()) {
    std::size_t count = 1;
    for (const char c : options.labels) count += c == ',' ? 1 : 0;
    if (count != options.run_directories.size())
      throw InputError(fmt::format("--labels gives {} label{} for {} run{} (comma-separated, one per OUTDIR)", count,
                                   count == 1 ? "" : "s", options.run_directories.size(),
                                   options.run_directories.size() == 1 ? "" : "s"));
  }
}

}  // namespace

int plot_runs(const PlotOptions& options) {
  check_options(options);
  fs::path script;
  std::string python;
  try {
    script = find_plot_script();
    python = python_interpreter();
  } catch (const ToolError& error) {
    fmt::print(stderr, "regodem: error: {}\n", error.what());
    return exit_status::run_failed;
  }
  std::vector<std::string> arguments = {python, script.string()};
  arguments.insert(arguments.end(), options.run_directories.begin(), options.run_directories.end());
  if (!options.labels.empty()) arguments.insert(arguments.end(), {"--labels", options.labels});
  if (!options.output_directory.empty()) arguments.insert(arguments.end(), {"--out", options.output_directory});
  if (options.section) {
    arguments.insert(arguments.end(), {"--section", "--section-axis", options.section_axis, "--section-through",
                                       options.section_through, "--section-thickness",
                                       fmt::format("{:.17g}", options.section_thickness_m)});
  }
  int status = 0;
  try {
    status = run_and_wait(arguments);
  } catch (const ToolError& error) {
    fmt::print(stderr, "regodem: error: {}\n", error.what());
    return exit_status::run_failed;
  }
  switch (status) {
    case 0: return exit_status::success;
    case 2: return exit_status::bad_input;  // the script printed what was wrong
    case 3:  // matplotlib or numpy missing: the script said which
      return exit_status::run_failed;
    default:
      fmt::print(stderr, "regodem: error: the plot script {} ended with status {}\n", script.string(), status);
      return exit_status::run_failed;
  }
}

}  // namespace regodem::app
