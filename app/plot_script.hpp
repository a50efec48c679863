#pragma once
// The plot script (scripts/regodem_plot.py) and the Python that runs it, for `regodem
// plot` and `regodem envelope`: found, and run with its arguments as given (no shell).
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace regodem::app {

/// Plotting cannot run here (no python3, matplotlib or script): not bad input, a setup problem.
class ToolError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// $REGODEM_PLOT_SCRIPT, else beside the executable (the build tree), else
/// PREFIX/share/regodem (installed), else the source tree this was built from.
std::filesystem::path find_plot_script();

/// $REGODEM_PYTHON, else Debian's /usr/bin/python3; ToolError if it is not there.
std::string python_interpreter();

/// Runs arguments[0] with the rest; its exit status (128 + signal if one ended it).
int run_and_wait(const std::vector<std::string>& arguments);

}  // namespace regodem::app
