#pragma once
// The readers of the scenario's sections. Each fills its part of the ScenarioSpec and
// reports problems to the diagnostics; scenario_reader calls them so that names and the
// domain are known before the sections that refer to them.
#include <optional>
#include <string>
#include <vector>

#include "scenario/scenario_spec.hpp"
#include "scenario/yaml_section.hpp"

namespace regodem {

/// What later sections check names and extents against.
struct ScenarioReferences {
  std::vector<std::string> material_names;
  std::vector<std::string> stage_names;
  std::optional<DomainSpec> domain;  // absent when the domain is missing or wrong
  std::string base_directory;        // relative paths in the file are relative to this
};

void read_materials(const YamlSection& root, ScenarioSpec& spec);                 // read_materials.cpp
void read_interactions(const YamlSection& root, const ScenarioReferences& references,
                       ScenarioSpec& spec);                                         // read_materials.cpp
void read_stages(const YamlSection& root, const ScenarioReferences& references,
                 ScenarioSpec& spec);                                               // read_stages.cpp
void read_output(const YamlSection& root, ScenarioSpec& spec);                    // read_stages.cpp
void read_walls(const YamlSection& root, const ScenarioReferences& references,
                ScenarioSpec& spec);                                                // read_walls.cpp
void read_insertions(const YamlSection& root, const ScenarioReferences& references,
                     ScenarioSpec& spec);                                           // read_insertions.cpp

}  // namespace regodem
