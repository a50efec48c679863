#pragma once
// What a run can be asked to do at all. A value that passes every per-key check can
// still make a plan no machine meets — `shear_modulus: 1e300 Pa` gives a time step of
// 1e-152 s and 1e151 steps — and such a plan is refused with its numbers before it
// starts, rather than run for ever or overflow a step counter.
#include <string>
#include <vector>

#include "scenario/scenario_spec.hpp"
#include "sim/stage_plan.hpp"  // max_steps_per_stage

namespace regodem {

/// The most particles one insertion may ask for: exact as a double and as a count, so
/// that converting it cannot overflow (the memory check then applies).
inline constexpr double max_particles_per_insertion = 1e15;

/// Bytes a particle needs at the least: its fields in the particle store alone
/// (~19 arrays, 200 B), before neighbour lists and contacts.
inline constexpr double min_bytes_per_particle = 200.0;

struct PlannedStage {
  std::string name;
  std::string span;         // what bounds it: "its duration", "its max_duration", ...
  double simulated_s = 0.0;  // the span in simulated time
  double step_s = 0.0;      // the step it advances by
  std::string step_origin;  // where the step comes from, when not the run's time step
  SourceLocation where;     // the stage in the file
};

/// Throws InputError, located at the stage, when it plans more than
/// max_steps_per_stage steps or its step is not a positive finite number. `step_origin`
/// says where the run's time step comes from (the Rayleigh time of which material and
/// radius), so that the message points at the value to correct.
void check_stage_step_counts(const std::vector<PlannedStage>& stages, const std::string& step_origin);

/// Throws InputError, located at `where`, when `particles` need more than this
/// machine's physical memory at min_bytes_per_particle.
void check_particle_memory(double particles, const SourceLocation& where);

/// This machine's physical memory, in bytes (0 where unknown).
double physical_memory_bytes();

}  // namespace regodem
