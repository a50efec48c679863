#pragma once
// Reads a scenario file (YAML) into a ScenarioSpec: every value in SI units and kelvin,
// every problem reported as "file:line:column: key.path: message". The format is
// documented key by key in docs/scenario-format.md.
#include <string>
#include <vector>

#include "scenario/scenario_spec.hpp"

namespace regodem {

/// Reads and checks the scenario file. `set_overrides` are "key.path=value" texts
/// (from --set), applied to the YAML tree before checking: path segments are map keys,
/// list indices or the `name` of a list item ("materials.regolith.density=2500",
/// "stages.settle.duration=0.5 s", "walls.0.radius=20 mm"). Throws InputError naming
/// every problem found (one per line), or the file that cannot be read.
ScenarioSpec read_scenario_file(const std::string& path,
                                const std::vector<std::string>& set_overrides = {});

/// The same for text in memory; `file_name_for_messages` also anchors relative paths
/// in the scenario (its directory).
ScenarioSpec read_scenario_string(const std::string& yaml_text,
                                  const std::string& file_name_for_messages,
                                  const std::vector<std::string>& set_overrides = {});

}  // namespace regodem
