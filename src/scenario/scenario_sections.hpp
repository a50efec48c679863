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
  std::vector<std::string> static_stage_names;  // stages that freeze the mechanics
  std::optional<DomainSpec> domain;  // absent when the domain is missing or wrong
  std::string base_directory;        // relative paths in the file are relative to this
  bool heat_section = false;         // the file has a top-level `heat` section
  bool heat_enabled = false;         // ... and it does not say `enabled: false`
};

void read_materials(const YamlSection& root, ScenarioSpec& spec);                 // read_materials.cpp
void read_interactions(const YamlSection& root, const ScenarioReferences& references,
                       ScenarioSpec& spec);                                         // read_materials.cpp
void read_stages(const YamlSection& root, const ScenarioReferences& references,
                 ScenarioSpec& spec);                                               // read_stages.cpp
void read_output(const YamlSection& root, ScenarioSpec& spec);                    // read_stages.cpp
void read_snapshots(const YamlValue& value, OutputSpec& output);                  // read_snapshots.cpp
void read_heat(const YamlSection& root, ScenarioReferences& references,
               ScenarioSpec& spec);                                                 // read_heat.cpp
/// Checks that span sections once all are read: thermal properties of the particle
/// materials and initial temperatures when heat is on, no insertion in a static stage.
void check_heat_requirements(const ScenarioSpec& spec, const ScenarioReferences& references,
                             ScenarioDiagnostics& diagnostics);                     // read_heat.cpp
void read_walls(const YamlSection& root, const ScenarioReferences& references,
                ScenarioSpec& spec);                                                // read_walls.cpp
/// A `type: mesh` wall's file, scale, placement and grid (read_mesh_wall.cpp).
void read_mesh_shape(const YamlSection& section, const ScenarioReferences& references, WallSpec& wall);
/// An STL or OBJ file, by its extension; throws InputError.
TriangleMesh read_mesh_file(const std::string& path);
MeshTransform mesh_transform(const MeshPlacementSpec& placement);
/// The `bonds` list (bond kinds per material pair) and a stage's `form_bonds`.
void read_bonds(const YamlSection& root, const ScenarioReferences& references,
                ScenarioSpec& spec);                                                // read_bonds.cpp
std::optional<BondFormationSpec> read_bond_formation(const YamlValue& value,
                                                     const ScenarioReferences& references);  // read_bonds.cpp
void read_insertions(const YamlSection& root, const ScenarioReferences& references,
                     ScenarioSpec& spec);                                           // read_insertions.cpp
/// The `measurements` section; after the walls, which it names.
void read_measurements(const YamlSection& root, const ScenarioReferences& references,
                       ScenarioSpec& spec);                                         // read_measurements.cpp

}  // namespace regodem
