// Top level of the scenario reader: load the YAML, apply --set overrides, read the
// global keys and the domain, then the sections in an order that lets each check its
// references (materials and stages first), and report every problem at once.
#include "scenario/scenario_reader.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <fmt/format.h>

#include "core/error.hpp"
#include "scenario/content_hash.hpp"
#include "scenario/scenario_fields.hpp"
#include "scenario/scenario_sections.hpp"
#include "scenario/yaml_overrides.hpp"
#include "scenario/yaml_section.hpp"

namespace regodem {
namespace {

const std::vector<std::string> kTopLevelKeys{
    "name",          "description", "seed",   "gravity",    "domain",
    "time_step",     "rayleigh_fraction",     "max_rayleigh_fraction",
    "neighbor_skin", "materials",   "interactions",         "walls",
    "insertions",    "stages",      "output",               "heat",
    "bonds",         "measurements", "initial_state"};

/// `auto` (returned as 0, the builder's cue to choose) or a quantity greater than 0.
double read_auto_or_positive(const YamlSection& root, std::string_view key, Dimension dimension) {
  const auto value = root.get(key);
  if (!value) return 0.0;
  if (value->node().IsScalar() && value->node().Scalar() == "auto") return 0.0;
  const auto quantity = value->quantity(dimension);
  if (!quantity) return 0.0;
  if (*quantity <= 0.0) {
    value->error(fmt::format("must be greater than 0 (or auto), got '{}'", value->node().Scalar()));
    return 0.0;
  }
  return *quantity;
}

std::optional<DomainSpec> read_domain(const YamlSection& root) {
  const auto value = root.require("domain");
  if (!value) return std::nullopt;
  const auto section = value->section();
  if (!section) return std::nullopt;
  section->allow_only({"min", "max", "lost_particles"});
  DomainSpec domain;
  domain.where = value->where();
  const auto low = section->required_vector("min", Dimension::length);
  const auto high = section->required_vector("max", Dimension::length);
  if (!low || !high) return std::nullopt;
  domain.min_m = *low;
  domain.max_m = *high;
  if (const auto lost = section->get("lost_particles")) {
    const auto policy = lost->choice({"stop", "remove"});
    if (!policy) return std::nullopt;
    domain.remove_lost_particles = *policy == "remove";
  }
  for (int axis = 0; axis < 3; ++axis) {
    if (!(domain.min_m[axis] < domain.max_m[axis])) {
      section->get("max")->error(fmt::format(
          "must be above 'min' along every axis ({}: min {:g} m, max {:g} m)", "xyz"[axis],
          domain.min_m[axis], domain.max_m[axis]));
      return std::nullopt;
    }
  }
  return domain;
}

void read_time_stepping(const YamlSection& root, ScenarioSpec& spec) {
  spec.time_step_s = read_auto_or_positive(root, "time_step", Dimension::time);
  spec.neighbor_skin_m = read_auto_or_positive(root, "neighbor_skin", Dimension::length);
  const auto is_fraction_of_one = [](double value) { return value > 0.0 && value <= 1.0; };
  spec.max_rayleigh_fraction =
      read_checked_quantity(root, "max_rayleigh_fraction", Dimension::dimensionless,
                            Presence::optional, is_fraction_of_one,
                            "be greater than 0 and at most 1")
          .value_or(spec.max_rayleigh_fraction);
  if (const auto fraction = read_checked_quantity(root, "rayleigh_fraction",
                                                  Dimension::dimensionless, Presence::optional,
                                                  is_positive, "be greater than 0")) {
    if (*fraction > spec.max_rayleigh_fraction) {
      root.get("rayleigh_fraction")
          ->error(fmt::format("must be at most max_rayleigh_fraction ({:g}); larger steps are "
                              "unstable",
                              spec.max_rayleigh_fraction));
    }
    spec.rayleigh_fraction = *fraction;
  }
}

void read_globals(const YamlSection& root, ScenarioSpec& spec) {
  if (const auto name = root.text("name")) spec.name = *name;
  if (const auto description = root.text("description")) spec.description = *description;
  if (const auto seed = root.get("seed")) spec.seed = seed->whole_number().value_or(spec.seed);
  spec.gravity_m_per_s2 =
      root.vector("gravity", Dimension::acceleration).value_or(spec.gravity_m_per_s2);
  read_time_stepping(root, spec);
}

/// initial_state: {checkpoint: FILE or OUTDIR}, relative to the scenario file.
void read_initial_state(const YamlSection& root, const ScenarioReferences& references, ScenarioSpec& spec) {
  const auto value = root.get("initial_state");
  if (!value) return;
  const auto section = value->section();
  if (!section) return;
  section->allow_only({"checkpoint", "temperature"});
  if (section->has("temperature")) {
    if (!references.heat_enabled)
      section->get("temperature")->error("a starting temperature needs heat on: add a top-level `heat:` section");
    else
      spec.initial_state_temperature_K = read_checked_quantity(*section, "temperature", Dimension::temperature,
                                                               Presence::required, is_positive,
                                                               "be above absolute zero");
  }
  const auto checkpoint = section->get("checkpoint");
  if (!checkpoint) {
    section->error("initial_state needs `checkpoint`: a checkpoint file or a run's output directory");
    return;
  }
  const auto text = checkpoint->text();
  if (!text) return;
  std::filesystem::path path(*text);
  if (path.is_relative()) path = std::filesystem::path(references.base_directory) / path;
  std::error_code ignored;
  path = std::filesystem::absolute(path, ignored).lexically_normal();
  if (!std::filesystem::exists(path, ignored)) {
    checkpoint->error(fmt::format("no such file or directory: '{}'", path.string()));
    return;
  }
  spec.initial_state_checkpoint = path.string();
  spec.initial_state_where = checkpoint->where();
}

ScenarioSpec read_tree(const YAML::Node& tree, ScenarioReadContext& context) {
  ScenarioSpec spec;
  spec.name = std::filesystem::path(context.file).stem().string();
  const YamlValue root_value(context, tree, tree.Mark(), "", "");
  if (tree.IsNull()) {
    root_value.error("the scenario is empty; it needs at least 'materials', 'domain' and 'stages'");
    return spec;
  }
  const auto root = root_value.section();
  if (!root) return spec;
  root->allow_only(kTopLevelKeys,
                   {{"calibration", "this is a calibration file, not a scenario: run it with `regodem calibrate FILE`"}});

  ScenarioReferences references;
  references.base_directory = std::filesystem::path(context.file).parent_path().string();
  read_globals(*root, spec);
  references.domain = read_domain(*root);
  if (references.domain) spec.domain = *references.domain;
  // Heat first: walls, stages and insertions ask of it whether heat is on.
  read_heat(*root, references, spec);
  read_materials(*root, spec);
  for (const MaterialSpec& material : spec.materials) {
    references.material_names.push_back(material.name);
  }
  read_stages(*root, references, spec);
  for (const StageSpec& stage : spec.stages) {
    references.stage_names.push_back(stage.name);
    if (stage.heat_stepping != ThermalStepping::coupled) {
      references.static_stage_names.push_back(stage.name);
    }
  }
  read_interactions(*root, references, spec);
  read_bonds(*root, references, spec);
  read_walls(*root, references, spec);
  read_insertions(*root, references, spec);
  read_output(*root, spec);
  read_measurements(*root, references, spec);
  read_initial_state(*root, references, spec);
  check_heat_requirements(spec, references, context.diagnostics);
  return spec;
}

}  // namespace

ScenarioSpec read_scenario_string(const std::string& yaml_text,
                                  const std::string& file_name_for_messages,
                                  const std::vector<std::string>& set_overrides) {
  ScenarioReadContext context;
  context.file = file_name_for_messages;
  YAML::Node tree = load_yaml(yaml_text, file_name_for_messages);
  apply_overrides(tree, set_overrides, context);
  ScenarioSpec spec = read_tree(tree, context);
  context.diagnostics.throw_if_any();
  spec.file = file_name_for_messages;
  spec.content_hash = scenario_content_hash(yaml_text, set_overrides);
  return spec;
}

ScenarioSpec read_scenario_file(const std::string& path,
                                const std::vector<std::string>& set_overrides) {
  std::error_code error;
  if (!std::filesystem::exists(path, error)) {
    throw InputError(fmt::format("{}: no such scenario file", path));
  }
  if (!std::filesystem::is_regular_file(path, error)) {
    throw InputError(fmt::format("{}: not a scenario file (a directory or device?)", path));
  }
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.is_open() || in.bad()) {
    throw InputError(fmt::format("{}: cannot read the scenario file ({})", path,
                                 std::strerror(errno)));
  }
  return read_scenario_string(text, path, set_overrides);
}

}  // namespace regodem
