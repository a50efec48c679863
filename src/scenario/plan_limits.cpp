#include "scenario/plan_limits.hpp"

#include <unistd.h>

#include <cmath>

#include <fmt/format.h>

#include "core/error.hpp"

namespace regodem {

void check_stage_step_counts(const std::vector<PlannedStage>& stages, const std::string& run_step_origin) {
  for (const PlannedStage& stage : stages) {
    const SourceLocation& where = stage.where;
    const std::string& step_origin = stage.step_origin.empty() ? run_step_origin : stage.step_origin;
    if (!(stage.step_s > 0.0) || !std::isfinite(stage.step_s))
      throw InputError(fmt::format("{}: stage '{}': the time step is {:.4g} s ({}); it must be a positive number",
                                   where.describe(), stage.name, stage.step_s, step_origin));
    const double steps = stage.simulated_s / stage.step_s;
    if (!std::isfinite(stage.simulated_s) || steps <= max_steps_per_stage) continue;
    throw InputError(fmt::format(
        "{}: stage '{}' would take {:.3g} steps ({:.4g} s of simulated time, {}, at a step of {:.4g} s: {}); at most "
        "{:.0e} steps a stage can be run (the paper's full drilling case takes ~2e9). Check the values that set the "
        "step (a material's shear modulus, density, a particle's radius) and the stage's length",
        where.describe(), stage.name, steps, stage.simulated_s, stage.span, stage.step_s, step_origin,
        max_steps_per_stage));
  }
}

double physical_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  const long page_size = ::sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page_size > 0 ? static_cast<double>(pages) * static_cast<double>(page_size) : 0.0;
}

void check_particle_memory(double particles, const SourceLocation& where) {
  const double memory = physical_memory_bytes();
  const double needed = particles * min_bytes_per_particle;
  if (memory <= 0.0 || needed <= memory) return;
  throw InputError(fmt::format(
      "{}: the run would hold {:.4g} particles, which need at least {:.3g} GB ({:.0f} B each for their fields alone), "
      "more than this machine's {:.3g} GB of memory",
      where.describe(), particles, needed / 1e9, min_bytes_per_particle, memory / 1e9));
}

}  // namespace regodem
