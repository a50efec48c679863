// The `stages` list (end conditions, temporary contact overrides, how heat advances)
// and the `output` section.
#include <cmath>

#include <fmt/format.h>

#include "scenario/scenario_fields.hpp"
#include "scenario/scenario_sections.hpp"

namespace regodem {
namespace {

bool is_restitution(double value) { return value > 0.0 && value <= 1.0; }

const std::vector<std::string> kSettledKeys{"kinetic_energy_per_particle", "min_duration",
                                            "max_duration"};

std::optional<OverrideSpec> read_override(const YamlValue& item,
                                          const ScenarioReferences& references) {
  const auto section = item.section();
  if (!section) return std::nullopt;
  section->allow_only({"materials", "restitution", "sliding_friction", "rolling_friction"});
  OverrideSpec contact_override;
  contact_override.where = item.where();
  bool complete = true;
  if (const auto materials = section->get("materials")) {
    if (!materials->node().IsSequence() || materials->node().size() != 2) {
      materials->error("expected a list of two material names, e.g. [regolith, steel]");
      complete = false;
    } else if (const auto names = materials->items()) {
      const auto first = read_reference((*names)[0], references.material_names, "material");
      const auto second = read_reference((*names)[1], references.material_names, "material");
      if (first && second) {
        contact_override.material_a = *first;
        contact_override.material_b = *second;
      } else {
        complete = false;
      }
    }
  }
  const auto read_property = [&](const char* key, bool (*valid)(double), const char* rule) {
    const auto value = read_checked_quantity(*section, key, Dimension::dimensionless,
                                             Presence::optional, valid, rule);
    if (section->has(key) && !value) complete = false;
    return value;
  };
  contact_override.restitution =
      read_property("restitution", is_restitution, "be greater than 0 and at most 1");
  contact_override.sliding_friction =
      read_property("sliding_friction", is_non_negative, "be 0 or more");
  contact_override.rolling_friction =
      read_property("rolling_friction", is_non_negative, "be 0 or more");
  if (!section->has("restitution") && !section->has("sliding_friction") &&
      !section->has("rolling_friction")) {
    item.error("an override changes at least one of 'restitution', 'sliding_friction' or "
               "'rolling_friction'");
    complete = false;
  }
  if (!complete) return std::nullopt;
  return contact_override;
}

void read_settled_end(const YamlSection& section, StageSpec& stage) {
  stage.end = StageEnd::settled;
  stage.settled_kinetic_energy_J =
      read_checked_quantity(section, "kinetic_energy_per_particle", Dimension::energy,
                            Presence::required, is_positive, "be greater than 0")
          .value_or(0.0);
  stage.min_duration_s = read_checked_quantity(section, "min_duration", Dimension::time,
                                               Presence::optional, is_non_negative, "be 0 or more")
                             .value_or(0.0);
  if (const auto max_duration = read_checked_quantity(
          section, "max_duration", Dimension::time, Presence::optional, is_positive,
          "be greater than 0")) {
    if (*max_duration <= stage.min_duration_s) {
      section.get("max_duration")->error("must be greater than min_duration");
    }
    stage.max_duration_s = *max_duration;
  }
}

/// `until: {wall: drill, depth: 100 mm}`: until that wall's depth (its motion's
/// depth_at_start plus the distance fed along its velocity) reaches the value.
void read_depth_end(const YamlValue& value, StageSpec& stage) {
  stage.end = StageEnd::depth;
  const auto section = value.section();
  if (!section) return;
  section->allow_only({"wall", "depth"});
  if (const auto wall = section->require("wall")) stage.depth_wall = wall->text().value_or("");
  stage.depth_m = section->required_quantity("depth", Dimension::length).value_or(0.0);
}

/// `until: {measurement: w0, quantity: T_in, rises_to: 446.8 K}` (or `falls_to`): until
/// a region's or band's temperature gets there; `max_duration` bounds the wait. The
/// measurement's name and kind are checked when the run is built.
void read_measured_end(const YamlValue& value, const YamlSection& stage_section, StageSpec& stage) {
  stage.end = StageEnd::measurement;
  const auto section = value.section();
  if (!section) return;
  section->allow_only({"measurement", "quantity", "rises_to", "falls_to"});
  if (const auto name = section->require("measurement")) stage.until_measurement = name->text().value_or("");
  if (const auto quantity = section->require("quantity"))
    stage.until_quantity = quantity->choice({"mean", "min", "max", "T_in", "T_out", "T_d"}).value_or("");
  if (const auto direction = section->exactly_one_of({"rises_to", "falls_to"})) {
    stage.until_rising = *direction == "rises_to";
    stage.until_value_K = section->required_quantity(*direction, Dimension::temperature).value_or(0.0);
  }
  if (const auto max_duration = read_checked_quantity(stage_section, "max_duration", Dimension::time,
                                                      Presence::required, is_positive, "be greater than 0"))
    stage.max_duration_s = *max_duration;
}

bool is_measured_end(const YamlValue& until) { return until.node().IsMap() && until.node()["measurement"]; }

const std::vector<std::string> kStaticStageKeys{"thermal_time_step", "stability_fraction"};

bool is_fraction_of_one(double value) { return value > 0.0 && value <= 1.0; }

/// `heat_stepping` and, for the static-bed methods, their step. A static stage freezes
/// the mechanics, so it ends by time and changes no contact property.
void read_heat_stepping(const YamlSection& section, const ScenarioReferences& references,
                        StageSpec& stage) {
  const auto value = section.get("heat_stepping");
  if (!value) return;
  const auto method = value->choice(
      {"coupled", "static_explicit", "static_backward_euler", "static_crank_nicolson"});
  if (!method) return;
  stage.heat_stepping = *method == "coupled"                 ? ThermalStepping::coupled
                        : *method == "static_explicit"       ? ThermalStepping::static_explicit
                        : *method == "static_backward_euler" ? ThermalStepping::static_backward_euler
                                                             : ThermalStepping::static_crank_nicolson;
  if (stage.heat_stepping == ThermalStepping::coupled) return;
  if (!references.heat_enabled) {
    value->error(references.heat_section
                     ? "a static-bed stage only moves heat, but heat is off (`heat: {enabled: false}`)"
                     : "a static-bed stage only moves heat, but heat transfer is off: add a top-level "
                       "`heat:` section (e.g. `heat: {}`)");
  }
  if (section.has("until") && !is_measured_end(*section.get("until"))) {
    section.get("until")->error(fmt::format(
        "a static-bed stage ({}) does not move particles, so it cannot wait for them to settle or for a "
        "depth: give its 'duration', or wait for a measurement (until: {{measurement: ..., quantity: ..., "
        "rises_to: ...}})",
        *method));
  }
  if (section.has("overrides")) {
    section.get("overrides")->error(fmt::format(
        "a static-bed stage ({}) freezes the mechanics: contact overrides would change nothing",
        *method));
  }
  section.at_most_one_of(kStaticStageKeys);
  stage.thermal_time_step_s = read_checked_quantity(section, "thermal_time_step", Dimension::time,
                                                    Presence::optional, is_positive,
                                                    "be greater than 0")
                                  .value_or(0.0);
  stage.stability_fraction =
      read_checked_quantity(section, "stability_fraction", Dimension::dimensionless,
                            Presence::optional, is_fraction_of_one, "be greater than 0 and at most 1")
          .value_or(stage.stability_fraction);
}

/// Always returns the stage, complete or not, so that insertions naming it are not
/// reported as well; an incomplete one has already been reported.
StageSpec read_stage(const YamlValue& item, const ScenarioReferences& references) {
  StageSpec stage;
  stage.where = item.where();
  const auto section = item.section();
  if (!section) return stage;
  const auto until = section->get("until");
  const bool settled = until && !until->node().IsMap();
  const bool measured = until && is_measured_end(*until);
  // Judged from the text so that the keys can be checked before the value is.
  const auto stepping = section->get("heat_stepping");
  const bool frozen = stepping && stepping->node().IsScalar() &&
                      stepping->node().Scalar().starts_with("static_");
  std::vector<std::string> allowed{"name", "duration", "until", "overrides", "heat_stepping", "form_bonds"};
  std::vector<std::pair<std::string, std::string>> misplaced;
  for (const std::string& key : kSettledKeys) {
    if (settled || (measured && key == "max_duration")) {
      allowed.push_back(key);
    } else {
      misplaced.emplace_back(key, until ? "only with 'until: settled'; a stage that ends at a depth takes none"
                                        : "only with 'until: settled'");
    }
  }
  for (const std::string& key : kStaticStageKeys) {
    if (frozen) {
      allowed.push_back(key);
    } else {
      misplaced.emplace_back(key, "only for a static-bed stage (heat_stepping: static_...); a "
                                  "coupled stage moves heat at every mechanical step");
    }
  }
  section->allow_only(allowed, misplaced);
  if (const auto name = read_item_name(*section)) stage.name = *name;

  const auto end_key = section->exactly_one_of({"duration", "until"});
  if (end_key && *end_key == "duration") {
    stage.end = StageEnd::time;
    stage.duration_s = read_checked_quantity(*section, "duration", Dimension::time,
                                             Presence::required, is_positive,
                                             "be greater than 0")
                           .value_or(0.0);
  } else if (end_key && *end_key == "until") {
    if (measured)
      read_measured_end(*until, *section, stage);
    else if (until->node().IsMap())
      read_depth_end(*until, stage);
    else if (until->choice({"settled"}))
      read_settled_end(*section, stage);
  }

  read_heat_stepping(*section, references, stage);
  if (const auto bonding = section->get("form_bonds")) stage.form_bonds = read_bond_formation(*bonding, references);
  if (const auto overrides = section->get("overrides")) {
    if (const auto items = overrides->items()) {
      for (const YamlValue& override_item : *items) {
        if (auto contact_override = read_override(override_item, references)) {
          stage.overrides.push_back(std::move(*contact_override));
        }
      }
    }
  }
  return stage;
}

}  // namespace

void read_stages(const YamlSection& root, const ScenarioReferences& references,
                 ScenarioSpec& spec) {
  const auto value = root.require("stages");
  if (!value) return;
  const auto items = value->items();
  if (!items) return;
  if (items->empty()) {
    value->error("define at least one stage, e.g. '- {name: settle, duration: 0.5 s}'");
    return;
  }
  std::vector<NamedPlace> names;
  for (const YamlValue& item : *items) {
    StageSpec stage = read_stage(item, references);
    names.push_back({stage.name, stage.where});
    spec.stages.push_back(std::move(stage));
  }
  report_duplicate_names(names, "stage", value->context().diagnostics);
}

void read_output(const YamlSection& root, ScenarioSpec& spec) {
  const auto value = root.get("output");
  if (!value) return;
  const auto section = value->section();
  if (!section) return;
  section->allow_only({"interval", "progress_interval", "energy_audit", "snapshots"});
  spec.output.energy_audit = section->boolean("energy_audit").value_or(false);
  spec.output.interval_s = read_checked_quantity(*section, "interval", Dimension::time,
                                                 Presence::optional, is_positive,
                                                 "be greater than 0")
                               .value_or(spec.output.interval_s);
  spec.output.progress_interval_s =
      read_checked_quantity(*section, "progress_interval", Dimension::time, Presence::optional,
                            is_positive, "be greater than 0")
          .value_or(spec.output.progress_interval_s);
  if (const auto snapshots = section->get("snapshots")) read_snapshots(*snapshots, spec.output);
}

}  // namespace regodem
