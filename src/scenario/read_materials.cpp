// The `materials` map and the `interactions` list (contact properties per pair).
#include <algorithm>
#include <utility>

#include <fmt/format.h>

#include "scenario/scenario_fields.hpp"
#include "scenario/scenario_sections.hpp"

namespace regodem {
namespace {

bool is_physical_poisson_ratio(double value) { return value > -1.0 && value < 0.5; }
bool is_restitution(double value) { return value > 0.0 && value <= 1.0; }

/// A thermal property: a constant ("14.76 W/(m K)") or a table over temperature
/// ({temperature: [100 K, 350 K], value: [300, 900]}). Zero is refused as well as
/// negative values: no conductivity means no conduction (use `conduction: none`), and
/// no heat capacity means an infinite temperature change.
std::optional<TemperatureCurveSpec> read_temperature_curve(const YamlSection& section,
                                                           std::string_view key,
                                                           Dimension dimension) {
  const auto value = section.get(key);
  if (!value) return std::nullopt;
  // A value given but wrong still returns a (blank) curve: its problem is reported and
  // stops the read, and heat's check must not call it missing as well.
  TemperatureCurveSpec curve;
  curve.where = value->where();
  if (!value->node().IsMap()) {
    const auto constant = read_checked_quantity(section, key, dimension, Presence::required,
                                                is_positive, "be greater than 0");
    curve.constant = constant.value_or(0.0);
    return curve;
  }
  const auto rows = read_table(*value, {"temperature", Dimension::temperature, is_any, ""},
                               {"value", dimension, is_positive, "be greater than 0"});
  if (!rows) return curve;
  curve.temperature_K = rows->x;
  curve.value = rows->y;
  return curve;
}

/// Always returns the material, complete or not, so that references to it are not
/// reported as undefined as well; an incomplete one has already been reported.
MaterialSpec read_material(const std::string& name, const YamlValue& value) {
  MaterialSpec material;
  material.name = name;
  material.where = value.where();
  const auto section = value.section();
  if (!section) return material;
  section->allow_only({"density", "shear_modulus", "youngs_modulus", "poisson_ratio",
                       "conductivity", "specific_heat", "real_shear_modulus",
                       "real_youngs_modulus"});
  const auto density = read_checked_quantity(*section, "density", Dimension::density,
                                             Presence::required, is_positive,
                                             "be greater than 0");
  const auto poisson = read_checked_quantity(*section, "poisson_ratio", Dimension::dimensionless,
                                             Presence::required, is_physical_poisson_ratio,
                                             "lie between -1 and 0.5 (exclusive)");
  // EDEM users give the shear modulus, LIGGGHTS users Young's modulus: accept either.
  const auto modulus_key = section->exactly_one_of({"shear_modulus", "youngs_modulus"});
  std::optional<double> modulus;
  if (modulus_key) {
    modulus = read_checked_quantity(*section, *modulus_key, Dimension::pressure,
                                    Presence::required, is_positive, "be greater than 0");
  }
  material.density_kg_per_m3 = density.value_or(0.0);
  material.poisson_ratio = poisson.value_or(0.0);
  if (modulus && poisson) {
    // G = E / (2 (1 + nu))
    material.shear_modulus_Pa =
        *modulus_key == "shear_modulus" ? *modulus : *modulus / (2.0 * (1.0 + *poisson));
  }
  material.conductivity_W_per_mK =
      read_temperature_curve(*section, "conductivity", Dimension::thermal_conductivity);
  material.specific_heat_J_per_kgK =
      read_temperature_curve(*section, "specific_heat", Dimension::specific_heat);
  // The modulus of the real material, when the simulated one is reduced for a larger
  // time step: conduction's contact radius uses it. Either form, like the modulus.
  if (const auto real_key = section->at_most_one_of({"real_shear_modulus", "real_youngs_modulus"})) {
    material.real_modulus_stated = true;
    // `same`: the simulated modulus is the real one (a wall given its real stiffness).
    const auto given = section->get(*real_key);
    if (given && given->node().IsScalar() && given->node().Scalar() == "same") return material;
    const auto real = read_checked_quantity(*section, *real_key, Dimension::pressure,
                                            Presence::required, is_positive, "be greater than 0");
    if (real && poisson) {
      material.real_shear_modulus_Pa =
          *real_key == "real_shear_modulus" ? *real : *real / (2.0 * (1.0 + *poisson));
    }
  }
  return material;
}

/// The two material names of an interaction, e.g. [regolith, steel].
std::optional<std::pair<std::string, std::string>> read_material_pair(
    const YamlValue& value, const std::vector<std::string>& known_materials) {
  if (!value.node().IsSequence() || value.node().size() != 2) {
    value.error("expected a list of two material names, e.g. [regolith, steel]");
    return std::nullopt;
  }
  const auto items = value.items();
  if (!items) return std::nullopt;
  const auto first = read_reference((*items)[0], known_materials, "material");
  const auto second = read_reference((*items)[1], known_materials, "material");
  if (!first || !second) return std::nullopt;
  return std::pair{*first, *second};
}

/// `conduction` and, for the area law, `heat_transfer_coefficient`; false on a problem.
bool read_conduction(const YamlSection& section, InteractionSpec& interaction) {
  bool complete = true;
  if (const auto law_value = section.get("conduction")) {
    const auto law = law_value->choice({"force", "radius", "area", "none"});
    if (!law) return false;
    interaction.conduction = *law == "force"    ? ConductionLawSpec::force
                             : *law == "radius" ? ConductionLawSpec::radius
                             : *law == "area"   ? ConductionLawSpec::area
                                                : ConductionLawSpec::none;
  }
  const auto coefficient =
      read_checked_quantity(section, "heat_transfer_coefficient",
                            Dimension::heat_transfer_coefficient, Presence::optional,
                            is_positive, "be greater than 0");
  if (section.has("heat_transfer_coefficient") && !coefficient) complete = false;
  if (interaction.conduction == ConductionLawSpec::area) {
    if (!section.has("heat_transfer_coefficient")) {
      section.get("conduction")->error(
          "the area law (G = h pi a^2) needs 'heat_transfer_coefficient', e.g. 5e4 W/(m^2 K)");
      complete = false;
    }
    interaction.heat_transfer_coefficient_W_per_m2K = coefficient.value_or(0.0);
  } else if (section.has("heat_transfer_coefficient")) {
    section.get("heat_transfer_coefficient")
        ->error("is only used with 'conduction: area' (the force and radius laws use the "
                "materials' conductivity)");
    complete = false;
  }
  return complete;
}

bool same_pair(const InteractionSpec& a, const InteractionSpec& b) {
  return (a.material_a == b.material_a && a.material_b == b.material_b) ||
         (a.material_a == b.material_b && a.material_b == b.material_a);
}

}  // namespace

void read_materials(const YamlSection& root, ScenarioSpec& spec) {
  const auto value = root.require("materials");
  if (!value) return;
  const auto section = value->section();
  if (!section) return;
  if (section->entries().empty()) {
    value->error("define at least one material");
    return;
  }
  for (const YamlSection::Entry& entry : section->entries()) {
    if (!is_valid_name(entry.key)) {
      entry.value.error(fmt::format(
          "'{}' is not a valid material name: use letters, digits, '_' and '-'", entry.key));
      continue;
    }
    spec.materials.push_back(read_material(entry.key, entry.value));
  }
}

void read_interactions(const YamlSection& root, const ScenarioReferences& references,
                       ScenarioSpec& spec) {
  const auto value = root.get("interactions");
  if (!value) return;
  const auto items = value->items();
  if (!items) return;
  for (const YamlValue& item : *items) {
    const auto section = item.section();
    if (!section) continue;
    section->allow_only({"materials", "restitution", "sliding_friction", "rolling_friction",
                         "rolling_model", "clamp_attractive_normal_force", "conduction",
                         "heat_transfer_coefficient"});
    InteractionSpec interaction;
    interaction.where = item.where();
    const auto materials_value = section->require("materials");
    const auto pair = materials_value
                          ? read_material_pair(*materials_value, references.material_names)
                          : std::nullopt;
    const auto restitution =
        read_checked_quantity(*section, "restitution", Dimension::dimensionless,
                              Presence::required, is_restitution,
                              "be greater than 0 and at most 1");
    const auto sliding =
        read_checked_quantity(*section, "sliding_friction", Dimension::dimensionless,
                              Presence::required, is_non_negative, "be 0 or more");
    const auto rolling =
        read_checked_quantity(*section, "rolling_friction", Dimension::dimensionless,
                              Presence::optional, is_non_negative, "be 0 or more");
    std::optional<std::string> rolling_model = std::string("relative_spin");
    if (const auto model = section->get("rolling_model")) rolling_model = model->choice({"relative_spin", "own_spin"});
    const auto clamp = section->boolean("clamp_attractive_normal_force");
    const bool conduction_read = read_conduction(*section, interaction);
    if (!pair || !restitution || !sliding || !rolling_model || !conduction_read) continue;
    interaction.material_a = pair->first;
    interaction.material_b = pair->second;
    interaction.restitution = *restitution;
    interaction.sliding_friction = *sliding;
    interaction.rolling_friction = rolling.value_or(0.0);
    interaction.rolling_own_spin = *rolling_model == "own_spin";
    interaction.clamp_attractive_normal_force = clamp.value_or(false);

    const auto earlier = std::find_if(spec.interactions.begin(), spec.interactions.end(),
                                      [&](const InteractionSpec& other) {
                                        return same_pair(other, interaction);
                                      });
    if (earlier != spec.interactions.end()) {
      item.error(fmt::format("the pair [{}, {}] is already given{}", interaction.material_a,
                             interaction.material_b,
                             earlier->where.line > 0
                                 ? fmt::format(" at line {}", earlier->where.line)
                                 : std::string()));
      continue;
    }
    spec.interactions.push_back(std::move(interaction));
  }
}

}  // namespace regodem
