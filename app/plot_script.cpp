#include "plot_script.hpp"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <system_error>

#include <fmt/format.h>

#include "core/error.hpp"

extern char** environ;

namespace regodem::app {

namespace fs = std::filesystem;

namespace {

constexpr const char* script_name = "regodem_plot.py";
constexpr const char* default_python = "/usr/bin/python3";  // Debian's, where python3-matplotlib goes

fs::path executable_directory() {
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  return error ? fs::path() : self.parent_path();
}

}  // namespace

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

}  // namespace regodem::app
