// `regodem validate`: everything `run` checks before it starts (reading, units, the
// built model, the time step), then the plan, and nothing run.
#include <omp.h>

#include <fmt/format.h>

#include "commands.hpp"
#include "core/error.hpp"
#include "scenario/scenario_builder.hpp"
#include "scenario/scenario_reader.hpp"

namespace regodem::app {

int validate_scenario(const ValidateOptions& options) {
  try {
    const ScenarioSpec spec = read_scenario_file(options.scenario_path, options.overrides);
    const PreparedRun prepared = PreparedRun::build(spec, omp_get_max_threads());
    for (const std::string& line : prepared.describe()) fmt::print("{}\n", line);
  } catch (const InputError& error) {
    fmt::print(stderr, "regodem: error: {}\n", error.what());
    return exit_status::bad_input;
  }
  fmt::print("scenario OK: {}\n", options.scenario_path);
  return exit_status::success;
}

}  // namespace regodem::app
