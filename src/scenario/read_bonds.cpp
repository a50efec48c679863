// The `bonds` list (parallel bond kinds per material pair, DESIGN.md section 2) and a
// stage's `form_bonds` (which particles bond, at the stage start).
#include <algorithm>

#include <fmt/format.h>

#include "contact/parallel_bond.hpp"
#include "scenario/scenario_fields.hpp"
#include "scenario/scenario_sections.hpp"

namespace regodem {
namespace {

bool is_fraction_up_to_one(double value) { return value >= 0.0 && value <= 1.0; }

/// A list of names, each one of `known` (materials) or any valid name (region tags,
/// checked by the builder once the insertions are known).
std::optional<std::vector<std::string>> read_name_list(const YamlValue& value, const std::vector<std::string>* known,
                                                       std::string_view what) {
  if (!value.node().IsSequence()) {
    value.error(fmt::format("expected a list of {} names, e.g. [regolith]", what));
    return std::nullopt;
  }
  const auto items = value.items();
  if (!items) return std::nullopt;
  std::vector<std::string> names;
  bool complete = true;
  for (const YamlValue& item : *items) {
    const auto name = known ? read_reference(item, *known, what) : item.name();
    if (name)
      names.push_back(*name);
    else
      complete = false;
  }
  if (!complete) return std::nullopt;
  return names;
}

std::optional<BondSpec> read_bond(const YamlValue& item, const ScenarioReferences& references) {
  const auto section = item.section();
  if (!section) return std::nullopt;
  section->allow_only({"materials", "preset", "normal_stiffness", "shear_stiffness", "tensile_strength",
                       "shear_strength", "radius_multiplier", "damping_ratio", "conduction"});
  BondSpec bond;
  bond.where = item.where();
  bool complete = true;
  if (const auto materials = section->require("materials")) {
    if (!materials->node().IsSequence() || materials->node().size() != 2) {
      materials->error("expected a list of two material names, e.g. [regolith, regolith]");
      complete = false;
    } else if (const auto names = read_name_list(*materials, &references.material_names, "material")) {
      bond.material_a = (*names)[0];
      bond.material_b = (*names)[1];
    } else {
      complete = false;
    }
  } else {
    complete = false;
  }
  BondParameters preset = icy_regolith_bond_parameters();
  if (const auto name = section->get("preset")) {
    const auto choice = name->choice({"icy_regolith", "zhao2023"});
    if (choice) {
      bond.preset = *choice;
      if (*choice == "zhao2023") preset = zhao2023_bond_parameters();
    } else {
      complete = false;
    }
  }
  const auto value_or = [&](const char* key, Dimension dimension, double fallback, bool (*valid)(double),
                            const char* rule) {
    const auto value = read_checked_quantity(*section, key, dimension, Presence::optional, valid, rule);
    if (section->has(key) && !value) complete = false;
    return value.value_or(fallback);
  };
  bond.normal_stiffness_Pa_per_m = value_or("normal_stiffness", Dimension::stiffness_per_area,
                                            preset.normal_stiffness_Pa_per_m, is_positive, "be greater than 0");
  bond.shear_stiffness_Pa_per_m = value_or("shear_stiffness", Dimension::stiffness_per_area,
                                           preset.shear_stiffness_Pa_per_m, is_positive, "be greater than 0");
  bond.tensile_strength_Pa =
      value_or("tensile_strength", Dimension::pressure, preset.tensile_strength_Pa, is_positive, "be greater than 0");
  bond.shear_strength_Pa =
      value_or("shear_strength", Dimension::pressure, preset.shear_strength_Pa, is_positive, "be greater than 0");
  bond.radius_multiplier = value_or("radius_multiplier", Dimension::dimensionless, preset.radius_multiplier,
                                    is_positive, "be greater than 0");
  bond.damping_ratio = value_or("damping_ratio", Dimension::dimensionless, 0.0, is_non_negative, "be 0 or more");
  if (section->has("conduction")) {
    const auto conducts = section->boolean("conduction");
    if (conducts)
      bond.conduction = *conducts;
    else
      complete = false;
  }
  if (!complete) return std::nullopt;
  return bond;
}

}  // namespace

void read_bonds(const YamlSection& root, const ScenarioReferences& references, ScenarioSpec& spec) {
  const auto value = root.get("bonds");
  if (!value) return;
  const auto items = value->items();
  if (!items) return;
  for (const YamlValue& item : *items) {
    auto bond = read_bond(item, references);
    if (!bond) continue;
    const auto earlier = std::find_if(spec.bonds.begin(), spec.bonds.end(), [&](const BondSpec& other) {
      return (other.material_a == bond->material_a && other.material_b == bond->material_b) ||
             (other.material_a == bond->material_b && other.material_b == bond->material_a);
    });
    if (earlier != spec.bonds.end()) {
      item.error(fmt::format("the pair [{}, {}] already has a bond kind{}", bond->material_a, bond->material_b,
                             earlier->where.line > 0 ? fmt::format(" at line {}", earlier->where.line) : std::string()));
      continue;
    }
    spec.bonds.push_back(std::move(*bond));
  }
}

std::optional<BondFormationSpec> read_bond_formation(const YamlValue& value, const ScenarioReferences& references) {
  const auto section = value.section();
  if (!section) return std::nullopt;
  section->allow_only({"gap", "materials", "regions"});
  BondFormationSpec formation;
  formation.where = value.where();
  bool complete = true;
  const auto gap = read_checked_quantity(*section, "gap", Dimension::dimensionless, Presence::optional,
                                         is_fraction_up_to_one, "lie between 0 and 1 (a fraction of the radius)");
  if (section->has("gap") && !gap) complete = false;
  formation.gap_fraction = gap.value_or(0.0);
  if (const auto materials = section->get("materials")) {
    if (const auto names = read_name_list(*materials, &references.material_names, "material"))
      formation.materials = *names;
    else
      complete = false;
  }
  if (const auto regions = section->get("regions")) {
    if (const auto names = read_name_list(*regions, nullptr, "region tag"))
      formation.region_tags = *names;
    else
      complete = false;
  }
  if (!complete) return std::nullopt;
  return formation;
}

}  // namespace regodem
