// `regodem plot`: PNG figures from runs' CSV files and snapshots. The drawing is done by
// scripts/regodem_plot.py with Debian's /usr/bin/python3 and matplotlib (a real
// plotting tool, as issue 8 asks); this file checks the arguments, finds the script and
// the interpreter, and runs it with the arguments as given (no shell in between).
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include <fmt/format.h>

#include "commands.hpp"
#include "core/error.hpp"

extern char** environ;

namespace regodem::app {
namespace {

namespace fs = std::filesystem;

/// Plotting cannot run here (no python3, matplotlib or script): not bad input, a setup problem.
class ToolError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

constexpr const char* script_name = "regodem_plot.py";
constexpr const char* default_python = "/usr/bin/python3";  // Debian's, where python3-matplotlib goes

fs::path executable_directory() {
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  return error ? fs::path() : self.parent_path();
}

/// The plot script: $REGODEM_PLOT_SCRIPT, else beside the executable (the build tree),
/// else PREFIX/share/regodem (installed), else the source tree this was built from.
fs::path find_plot_script() {
  if (const char* given = std::getenv("REGODEM_PLOT_SCRIPT"); given != nullptr && *given != '\0') {
    if (!fs::is_regular_file(given))
      throw InputError(fmt::format("REGODEM_PLOT_SCRIPT names '{}', which is not a file", given));
    return given;
  }
  std::vector<fs::path> candidates;
  if (const fs::path dir = executable_directory(); !dir.empty()) {
    candidates.push_back(dir / script_name);
    candidates.push_back(dir.parent_path() / "share" / "regodem" / script_name);
  }
#ifdef REGODEM_SOURCE_DIR
  candidates.push_back(fs::path(REGODEM_SOURCE_DIR) / "scripts" / script_name);
#endif
  std::string looked;
  for (const fs::path& candidate : candidates) {
    std::error_code error;
    if (fs::is_regular_file(candidate, error)) return candidate;
    looked += fmt::format("\n  {}", candidate.string());
  }
  throw ToolError(fmt::format(
      "cannot find the plot script {}; looked in:{}\nset REGODEM_PLOT_SCRIPT to its path (scripts/{} in the sources)",
      script_name, looked, script_name));
}

std::string python_interpreter() {
  const char* given = std::getenv("REGODEM_PYTHON");
  const std::string python = given != nullptr && *given != '\0' ? given : default_python;
  if (::access(python.c_str(), X_OK) != 0)
    throw ToolError(fmt::format(
        "plotting needs {} with matplotlib, and {} is not there; on Debian: apt-get install python3 "
        "python3-matplotlib (scripts/setup-debian.sh installs them), or set REGODEM_PYTHON to a python3 that has "
        "matplotlib",
        python, python));
  return python;
}

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

int run_and_wait(const std::vector<std::string>& arguments) {
  std::vector<char*> argv;
  for (const std::string& a : arguments) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t child = 0;
  if (const int error = ::posix_spawn(&child, argv[0], nullptr, nullptr, argv.data(), environ); error != 0)
    throw ToolError(fmt::format("cannot start {}: {}", arguments[0], std::strerror(error)));
  int status = 0;
  while (::waitpid(child, &status, 0) < 0)
    if (errno != EINTR) throw ToolError(fmt::format("waiting for {}: {}", arguments[0], std::strerror(errno)));
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
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
