#pragma once
// Command-line "--set key.path=value" overrides, applied to the YAML tree before the
// scenario is read, so an overridden value is checked exactly like one in the file.
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "scenario/yaml_section.hpp"

namespace regodem {

/// Applies each "key.path=value" in order. Path segments are map keys, list indices
/// ("walls.0.radius" or "walls[0].radius") or the `name` of a list item
/// ("stages.settle.duration"). The value is YAML ("20 mm", "[0, 0, -1.62]"). Every
/// segment but the last must exist; the last may add a key to a map (checked later like
/// any key). Each applied value is recorded in context.overrides so that problems in it
/// name the --set; problems with the overrides themselves go to context.diagnostics.
void apply_overrides(YAML::Node& root, const std::vector<std::string>& overrides,
                     ScenarioReadContext& context);

}  // namespace regodem
