// Scenarios from Python: read a file or text with --set values, check and build it as
// `regodem validate` does, and hand back the plan (python/regodem/scenario.py wraps these).
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <omp.h>

#include <optional>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "scenario/scenario_builder.hpp"
#include "scenario/scenario_reader.hpp"
#include "sim/simulation.hpp"
#include "sim/stage_plan.hpp"

namespace py = pybind11;

namespace regodem::python {
namespace {

ScenarioSpec read_spec(const std::string& path, const std::optional<std::string>& text,
                       const std::vector<std::string>& overrides) {
  return text ? read_scenario_string(*text, path, overrides) : read_scenario_file(path, overrides);
}

const char* stage_end_kind(const Stage& stage) {
  if (stage.until_settled) return "settled";
  if (stage.ends_at_depth()) return "depth";
  if (stage.ends_on_measurement()) return "measurement";
  return "duration";
}

/// The plan as `validate` prints it (`lines`), and its parts as values.
py::dict plan_of(const ScenarioSpec& spec, const PreparedRun& prepared) {
  py::dict plan;
  plan["name"] = spec.name;
  plan["content_hash"] = spec.content_hash;
  plan["lines"] = prepared.describe();
  plan["warnings"] = prepared.warnings();
  const Simulation& sim = prepared.simulation();
  plan["time_step_s"] = prepared.time_step_s();
  plan["heat"] = sim.heat_enabled();
  plan["particles_at_start"] = sim.particles.size();
  py::list walls;
  for (const WallBody& wall : sim.walls.bodies) walls.append(wall.name);
  plan["walls"] = walls;
  py::list insertions;
  for (const Insertion& ins : prepared.plan().insertions) {
    py::dict d;
    d["name"] = ins.name;
    d["count"] = ins.target_count;
    d["stage"] = prepared.plan().stages.at(ins.stage).name;
    insertions.append(d);
  }
  plan["insertions"] = insertions;
  py::list stages;
  for (const Stage& stage : prepared.plan().stages) {
    py::dict d;
    d["name"] = stage.name;
    d["ends_by"] = stage_end_kind(stage);
    if (!stage.until_settled && !stage.ends_at_depth() && !stage.ends_on_measurement())
      d["duration_s"] = stage.duration_s;
    else
      d["max_duration_s"] = stage.max_duration_s;
    if (stage.ends_at_depth()) d["depth_m"] = stage.depth_m;
    d["static_bed"] = stage.freezes_mechanics();
    d["forms_bonds"] = stage.form_bonds.has_value();
    stages.append(d);
  }
  plan["stages"] = stages;
  return plan;
}

}  // namespace

void bind_scenario(py::module_& m) {
  m.def(
      "validate",
      [](const std::string& path, const std::optional<std::string>& text, const std::vector<std::string>& overrides) {
        const ScenarioSpec spec = read_spec(path, text, overrides);
        const PreparedRun prepared = PreparedRun::build(spec, omp_get_max_threads());
        return plan_of(spec, prepared);
      },
      py::arg("path"), py::arg("text") = py::none(), py::arg("overrides") = std::vector<std::string>{},
      "Reads the scenario (text if given, `path` naming it), applies the overrides, builds it as "
      "`regodem validate` does and returns its plan; raises InputError with every problem found");
}

}  // namespace regodem::python
