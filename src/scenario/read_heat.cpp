// The top-level `heat` section (DESIGN.md section 2, "Conduction", "Thermal stepping")
// and the checks that need every section read: what heat transfer asks of materials.
#include <fmt/format.h>

#include "scenario/scenario_fields.hpp"
#include "scenario/scenario_sections.hpp"

namespace regodem {
namespace {

bool is_partition(double value) { return value >= 0.0 && value <= 1.0; }

}  // namespace

void read_heat(const YamlSection& root, ScenarioReferences& references, ScenarioSpec& spec) {
  const auto value = root.get("heat");
  if (!value) return;
  // Present, even if malformed: its own problem is reported, not its absence elsewhere.
  references.heat_section = true;
  references.heat_enabled = true;
  spec.heat.enabled = true;
  const auto section = value->section();
  if (!section) return;
  section->allow_only({"enabled", "time_scale_factor", "friction_heating", "dissipation_heating", "heat_partition",
                       "friction_partition"});
  HeatSpec& heat = spec.heat;
  heat.where = value->where();
  // The section's presence turns heat on; `enabled: false` keeps the settings but
  // switches heat off for one run (e.g. --set heat.enabled=false to time the mechanics).
  heat.enabled = section->boolean("enabled").value_or(true);
  heat.time_scale_factor =
      read_checked_quantity(*section, "time_scale_factor", Dimension::dimensionless,
                            Presence::optional, is_positive, "be greater than 0")
          .value_or(heat.time_scale_factor);
  heat.friction_heating = section->boolean("friction_heating").value_or(false);
  heat.dissipation_heating = section->boolean("dissipation_heating").value_or(false);
  if (heat.friction_heating && heat.dissipation_heating)
    if (const auto key = section->get("dissipation_heating"))
      key->error("friction_heating and dissipation_heating are both on: dissipation heating already turns the "
                 "sliding power into heat, with every other loss; keep one");
  if (const auto partition = section->get("heat_partition"))
    heat.heat_partition = partition->choice({"equal", "fixed", "conductivity", "effusivity"}).value_or(heat.heat_partition);
  heat.friction_partition =
      read_checked_quantity(*section, "friction_partition", Dimension::dimensionless,
                            Presence::optional, is_partition, "lie between 0 and 1")
          .value_or(heat.friction_partition);
  references.heat_enabled = heat.enabled;
}

void check_heat_requirements(const ScenarioSpec& spec, const ScenarioReferences& references,
                             ScenarioDiagnostics& diagnostics) {
  if (!references.heat_enabled) return;
  // Only the materials that particles are made of: a wall's material needs no heat
  // capacity (its thermal block says what it does).
  for (const MaterialSpec& material : spec.materials) {
    bool used_by_particles = false;
    for (const InsertionSpec& insertion : spec.insertions) {
      used_by_particles = used_by_particles || insertion.material == material.name;
    }
    if (!used_by_particles) continue;
    std::string missing;
    if (!material.conductivity_W_per_mK) missing = "'conductivity' (e.g. 14.76 W/(m K))";
    if (!material.specific_heat_J_per_kgK) {
      missing += fmt::format("{}'specific_heat' (e.g. 800 J/(kg K))", missing.empty() ? "" : " and ");
    }
    if (missing.empty()) continue;
    diagnostics.error(material.where,
                      fmt::format("heat is on, so the particle material '{}' needs {}", material.name,
                                  missing));
  }
  // A partition by conductivity or effusivity weighs the wall too: a wall that takes heat
  // (fixed or lumped) needs the properties of its material (its own conductivity will do).
  const std::string& partition = spec.heat.heat_partition;
  if (!(spec.heat.friction_heating || spec.heat.dissipation_heating) ||
      (partition != "conductivity" && partition != "effusivity"))
    return;
  for (const WallSpec& wall : spec.walls) {
    if (wall.thermal.mode == WallThermalModeSpec::adiabatic) continue;
    // A wall that names none is of the first material (docs/scenario-format.md, `walls`).
    const std::string material_name =
        wall.material.empty() && !spec.materials.empty() ? spec.materials.front().name : wall.material;
    for (const MaterialSpec& material : spec.materials) {
      if (material.name != material_name) continue;
      std::string missing;
      if (!material.conductivity_W_per_mK && !wall.thermal.conductivity_W_per_mK) missing = "'conductivity'";
      if (partition == "effusivity" && !material.specific_heat_J_per_kgK)
        missing += fmt::format("{}'specific_heat'", missing.empty() ? "" : " and ");
      if (missing.empty()) continue;
      diagnostics.error(wall.where, fmt::format("heat.heat_partition: {} weighs the wall '{}' by its material '{}', "
                                                "which needs {}",
                                                partition, wall.name, material.name, missing));
    }
  }
}

}  // namespace regodem
