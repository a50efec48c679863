// The files of design studies, calibration and envelope: the same located,
// collect-everything reading as scenarios (yaml_section.hpp), so a user sees every
// problem of the file in one go. Factors, designs and run counts read alike in both.
#include "scenario/calibration_reader.hpp"

#include <filesystem>
#include <fstream>
#include <iterator>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "core/error.hpp"
#include "doe/polynomial_model.hpp"
#include "scenario/yaml_section.hpp"

namespace regodem {
namespace {

namespace fs = std::filesystem;
using doe::CalibrationSpec;

std::string located(const YamlValue& value) { return value.where().describe(); }

/// The text of a study's file; `what` names it in the message ("calibration").
std::string read_study_file(const std::string& path, const char* what) {
  std::error_code error;
  if (!fs::is_regular_file(path, error)) throw InputError(fmt::format("{}: no such {} file", path, what));
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.is_open() || in.bad()) throw InputError(fmt::format("{}: cannot read the {} file", path, what));
  return text;
}

/// A scenario file named relative to the calibration file, returned absolute.
std::optional<std::string> read_scenario_path(const YamlSection& section, const std::string& base_directory) {
  const auto value = section.require("scenario");
  if (!value) return std::nullopt;
  const auto text = value->text();
  if (!text) return std::nullopt;
  fs::path path(*text);
  if (path.is_relative()) path = fs::path(base_directory) / path;
  std::error_code ignored;
  path = fs::absolute(path, ignored).lexically_normal();
  if (!fs::is_regular_file(path, ignored)) {
    value->error(fmt::format("no such scenario file: '{}'", path.string()));
    return std::nullopt;
  }
  return path.string();
}

/// A non-empty text without spaces: a key path into summary.json or into the scenario.
std::optional<std::string> read_key_path(const YamlValue& value) {
  const auto text = value.text();
  if (!text) return std::nullopt;
  if (text->empty() || text->find_first_of(" \t=") != std::string::npos) {
    value.error(fmt::format("'{}' is not a key path: dotted keys without spaces or '=', e.g. a.b.c", *text));
    return std::nullopt;
  }
  return text;
}

std::optional<std::string> read_key_path(const YamlSection& section, std::string_view key) {
  const auto value = section.require(key);
  return value ? read_key_path(*value) : std::nullopt;
}

/// A list of "key.path=value" texts, as --set takes them.
std::vector<std::string> read_set_list(const YamlSection& section, std::string_view key) {
  std::vector<std::string> result;
  const auto value = section.get(key);
  if (!value) return result;
  const auto items = value->items();
  if (!items) return result;
  for (const YamlValue& item : *items) {
    const auto text = item.text();
    if (!text) continue;
    if (text->find('=') == std::string::npos || text->front() == '=') {
      item.error(fmt::format("'{}' is not a --set override: write key.path=value", *text));
      continue;
    }
    result.push_back(*text);
  }
  return result;
}

/// A plain number (a value in the unit the entry states).
std::optional<double> read_number(const YamlSection& section, std::string_view key, bool required) {
  const auto value = required ? section.require(key) : section.get(key);
  if (!value) return std::nullopt;
  return value->quantity(Dimension::dimensionless);
}

void read_reference(const YamlSection& root, const std::string& base, CalibrationSpec& spec) {
  const auto value = root.require("reference");
  if (!value) return;
  const auto section = value->section();
  if (!section) return;
  section->allow_only({"scenario", "set", "pass_on"});
  spec.reference.scenario = read_scenario_path(*section, base).value_or("");
  spec.reference.set = read_set_list(*section, "set");
  const auto pass_on = section->get("pass_on");
  if (!pass_on) return;
  for (const YamlValue& item : pass_on->items().value_or(std::vector<YamlValue>{})) {
    const auto entry = item.section();
    if (!entry) continue;
    entry->allow_only({"from", "set", "unit"});
    doe::PassOn p;
    p.from_json_path = read_key_path(*entry, "from").value_or("");
    p.set_path = read_key_path(*entry, "set").value_or("");
    p.unit = entry->text("unit").value_or("");
    p.where = located(item);
    spec.reference.pass_on.push_back(p);
  }
}

/// The items of a list that must have at least one.
std::vector<YamlValue> required_items(const YamlSection& root, std::string_view key, std::string_view what) {
  const auto value = root.require(key);
  if (!value) return {};
  const auto items = value->items();
  if (items && items->empty()) value->error(fmt::format("give at least one {}", what));
  return items.value_or(std::vector<YamlValue>{});
}

void read_factors(const YamlSection& root, std::vector<doe::CalibrationFactor>& factors) {
  for (const YamlValue& item : required_items(root, "factors", "factor")) {
    const auto entry = item.section();
    if (!entry) continue;
    entry->allow_only({"name", "set", "centre", "step", "unit", "value"});
    doe::CalibrationFactor f;
    if (const auto name_value = entry->require("name")) f.design.name = name_value->name().value_or("");
    f.set_path = read_key_path(*entry, "set").value_or("");
    f.design.unit = entry->text("unit").value_or("");
    f.design.centre = read_number(*entry, "centre", true).value_or(0.0);
    if (const auto step = read_number(*entry, "step", true)) {
      if (*step > 0.0) {
        f.design.step = *step;
      } else {
        entry->get("step")->error("must be greater than 0 (the actual change per coded unit)");
      }
    }
    if (const auto value = entry->get("value")) {
      f.value_template = value->text().value_or("");
      const std::size_t at = f.value_template.find("{}");
      if (at == std::string::npos || f.value_template.find("{}", at + 2) != std::string::npos)
        value->error(fmt::format("'{}' must hold `{{}}` once, where the number goes (e.g. \"[0, 0, -{{}} mm/s]\")",
                                 f.value_template));
      else if (entry->has("unit") && f.value_template.find(f.design.unit) == std::string::npos)
        value->error("the template gives the unit itself; `unit` then only names it, and it is not in the template");
    }
    for (const doe::CalibrationFactor& other : factors) {
      if (!f.design.name.empty() && other.design.name == f.design.name)
        item.error(fmt::format("a second factor named '{}'", f.design.name));
      if (!f.set_path.empty() && other.set_path == f.set_path)
        item.error(
            fmt::format("factors '{}' and '{}' set the same key '{}'", other.design.name, f.design.name, f.set_path));
    }
    factors.push_back(f);
  }
}

void read_design(const YamlSection& root, doe::CcdOptions& design) {
  design.centre_points = 3;  // as the paper
  const auto value = root.get("design");
  if (!value) return;
  const auto section = value->section();
  if (!section) return;
  section->allow_only({"alpha", "centre_points"});
  if (const auto alpha = section->get("alpha")) {
    const auto text = alpha->text();
    if (text && *text == "rotatable") {
      design.alpha_kind = doe::AlphaKind::rotatable;
    } else if (text && *text == "face") {
      design.alpha_kind = doe::AlphaKind::face;
    } else if (text) {
      try {
        design.alpha = parse_quantity(*text, Dimension::dimensionless);
        design.alpha_kind = doe::AlphaKind::given;
        if (!(design.alpha > 0.0)) alpha->error("α must be greater than 0");
      } catch (const InputError&) {
        alpha->error(fmt::format("'{}' is not rotatable, face or a number", *text));
      }
    }
  }
  if (const auto points = section->get("centre_points"))
    design.centre_points = static_cast<int>(points->whole_number().value_or(3));
}

/// A response's `terms` (as `regodem fit --terms`), checked against the factors; "" for the full quadratic.
std::string read_terms(const YamlSection& entry, const std::vector<std::string>& factor_names) {
  const auto terms = entry.get("terms");
  if (!terms) return "";
  const std::string text = terms->text().value_or("full");
  if (text == "full") return "";
  try {
    doe::parse_terms(text, factor_names);
    return text;
  } catch (const InputError& problem) {
    terms->error(problem.what());
  }
  return "";
}

/// A response's name is new among the responses and is no factor's.
template <typename Response>
void check_response_name(const YamlValue& item, const std::string& name, const std::vector<Response>& responses,
                         const std::vector<std::string>& factor_names) {
  if (name.empty()) return;
  for (const auto& other : responses)
    if (other.name == name) item.error(fmt::format("a second response named '{}'", name));
  for (const auto& factor : factor_names)
    if (factor == name) item.error(fmt::format("'{}' is a factor's name too", name));
}

void read_target(const YamlValue& value, doe::CalibrationResponse& response) {
  if (value.node().IsScalar() && value.node().Scalar() == "reference") {
    response.target_reference_path = response.json_path;  // the same key in the reference's summary
    return;
  }
  const auto section = value.section();
  if (!section || !value.node().IsMap()) {
    if (section) value.error("expected `reference` or {reference: KEY.PATH} or {value: NUMBER}");
    return;
  }
  section->allow_only({"reference", "value"});
  const auto which = section->exactly_one_of({"reference", "value"});
  if (!which) return;
  if (*which == "reference") {
    response.target_reference_path = read_key_path(*section->get("reference"));
  } else {
    response.target_value = read_number(*section, "value", true);
  }
}

void read_responses(const YamlSection& root, CalibrationSpec& spec) {
  std::vector<std::string> factor_names;
  for (const auto& f : spec.factors) factor_names.push_back(f.design.name);
  for (const YamlValue& item : required_items(root, "responses", "response")) {
    const auto entry = item.section();
    if (!entry) continue;
    entry->allow_only({"name", "value", "unit", "target", "terms"});
    doe::CalibrationResponse r;
    r.where = located(item);
    if (const auto name_value = entry->require("name")) r.name = name_value->name().value_or("");
    r.json_path = read_key_path(*entry, "value").value_or("");
    r.unit = entry->text("unit").value_or("");
    if (const auto target = entry->require("target")) read_target(*target, r);
    r.terms = read_terms(*entry, factor_names);
    check_response_name(item, r.name, spec.responses, factor_names);
    spec.responses.push_back(r);
  }
}

bool is_factor(const CalibrationSpec& spec, const std::string& name) {
  for (const auto& f : spec.factors)
    if (f.design.name == name) return true;
  return false;
}

bool is_response(const CalibrationSpec& spec, const std::string& name) {
  for (const auto& r : spec.responses)
    if (r.name == name) return true;
  return false;
}

void read_solve(const YamlSection& root, CalibrationSpec& spec) {
  doe::CalibrationSolve& solve = spec.solve;
  const auto value = root.get("solve");
  std::optional<YamlSection> section;
  if (value) section = value->section();
  if (section) {
    section->allow_only({"mode", "fix", "steps"});
    if (const auto mode = section->get("mode")) {
      if (mode->choice({"simultaneous", "sequential"}).value_or("") == "sequential")
        solve.mode = doe::CalibrationSolveMode::sequential;
    }
    if (const auto fix = section->get("fix")) {
      if (const auto fixed = fix->section()) {
        for (const auto& entry : fixed->entries()) {
          if (!is_factor(spec, entry.key)) {
            entry.value.error(fmt::format("'{}' is not one of the factors", entry.key));
            continue;
          }
          if (const auto number = entry.value.quantity(Dimension::dimensionless))
            solve.fixed.emplace_back(entry.key, *number);
        }
      }
    }
    if (const auto steps = section->get("steps")) {
      if (solve.mode != doe::CalibrationSolveMode::sequential)
        steps->error("steps belong to mode: sequential (simultaneous solves every response together)");
      for (const YamlValue& item : steps->items().value_or(std::vector<YamlValue>{})) {
        const auto step = item.section();
        if (!step) continue;
        step->allow_only({"response", "factor"});
        doe::CalibrationSolveStep s;
        if (const auto r = step->require("response")) {
          s.response = r->text().value_or("");
          if (!s.response.empty() && !is_response(spec, s.response))
            r->error(fmt::format("'{}' is not one of the responses", s.response));
        }
        if (const auto f = step->require("factor")) {
          s.factor = f->text().value_or("");
          if (!s.factor.empty() && !is_factor(spec, s.factor))
            f->error(fmt::format("'{}' is not one of the factors", s.factor));
        }
        solve.steps.push_back(s);
      }
    }
  }
  const YamlValue& where = section ? section->value() : root.value();
  if (solve.mode == doe::CalibrationSolveMode::sequential) {
    if (solve.steps.empty()) where.error("a sequential solve needs `steps`: [{response: R, factor: F}, ...]");
    return;
  }
  const std::size_t free_factors = spec.factors.size() - solve.fixed.size();
  if (!spec.factors.empty() && !spec.responses.empty() && spec.responses.size() != free_factors)
    where.error(
        fmt::format("a simultaneous solve needs as many responses as free factors: {} responses, {} free "
                    "factors (hold factors with `fix`, or solve sequentially)",
                    spec.responses.size(), free_factors));
}

/// A whole number of 1 or more under `key`, if given.
std::optional<int> read_count(const YamlSection& root, std::string_view key) {
  const auto value = root.get(key);
  if (!value) return std::nullopt;
  // More than any machine has cores; checked before the conversion (1e18 overflowed an
  // int and reached the runs as a negative --threads).
  constexpr std::uint64_t kLargest = 4096;
  const auto n = value->whole_number();
  if (n && *n >= 1 && *n <= kLargest) return static_cast<int>(*n);
  if (n) value->error(fmt::format("must be at least 1 and at most {}, got {}", kLargest, *n));
  return std::nullopt;
}

void read_runs(const YamlSection& root, int& processes, int& threads_per_run, int& ranks_per_run) {
  processes = read_count(root, "processes").value_or(processes);
  threads_per_run = read_count(root, "threads_per_run").value_or(threads_per_run);
  ranks_per_run = read_count(root, "ranks_per_run").value_or(ranks_per_run);
}

/// Envelope responses: a summary.json value, or a column of one of the run's CSV files reduced.
void read_envelope_responses(const YamlSection& root, doe::EnvelopeSpec& spec) {
  std::vector<std::string> factor_names;
  for (const auto& f : spec.factors) factor_names.push_back(f.design.name);
  for (const YamlValue& item : required_items(root, "responses", "response")) {
    const auto entry = item.section();
    if (!entry) continue;
    entry->allow_only({"name", "value", "series", "unit", "terms"});
    doe::EnvelopeResponse r;
    r.where = located(item);
    if (const auto name_value = entry->require("name")) r.name = name_value->name().value_or("");
    r.unit = entry->text("unit").value_or("");
    const auto which = entry->exactly_one_of({"value", "series"});
    if (which && *which == "value") r.json_path = read_key_path(*entry, "value").value_or("");
    if (which && *which == "series") {
      if (const auto series = entry->get("series")->section()) {
        series->allow_only({"file", "column", "reduce"});
        r.series_file = series->text("file").value_or("time_series.csv");
        if (const auto column = series->require("column")) r.series_column = column->text().value_or("");
        if (const auto reduce = series->get("reduce")) {
          const std::string how = reduce->choice({"max", "min", "mean", "final"}).value_or("max");
          r.reduction = how == "min"    ? doe::SeriesReduction::min
                        : how == "mean" ? doe::SeriesReduction::mean
                        : how == "final" ? doe::SeriesReduction::final
                                         : doe::SeriesReduction::max;
        }
        if (fs::path(r.series_file).is_absolute() || r.series_file.find("..") != std::string::npos)
          series->get("file")->error("a file of the run's own folder: a relative path without '..'");
      }
    }
    r.terms = read_terms(*entry, factor_names);
    check_response_name(item, r.name, spec.responses, factor_names);
    spec.responses.push_back(r);
  }
}

void read_envelope_map(const YamlSection& root, doe::EnvelopeSpec& spec) {
  const auto value = root.require("map");
  if (!value) return;
  const auto map = value->section();
  if (!map) return;
  map->allow_only({"x", "y", "response", "threshold", "grid"});
  doe::EnvelopeMap& m = spec.map;
  m.where = located(*value);
  const auto name_of = [&](std::string_view key, bool factor) {
    const auto v = map->require(key);
    if (!v) return std::string();
    const std::string name = v->text().value_or("");
    bool known = false;
    if (factor)
      for (const auto& f : spec.factors) known = known || f.design.name == name;
    else
      for (const auto& r : spec.responses) known = known || r.name == name;
    if (!name.empty() && !known)
      v->error(fmt::format("'{}' is not one of the {}", name, factor ? "factors" : "responses"));
    return name;
  };
  m.x = name_of("x", true);
  m.y = name_of("y", true);
  if (!m.x.empty() && m.x == m.y) map->get("y")->error("the map needs two different factors");
  m.response = name_of("response", false);
  if (const auto threshold = map->require("threshold")) m.threshold = threshold->quantity(Dimension::dimensionless).value_or(0.0);
  if (const auto grid = map->get("grid")) {
    const auto n = grid->whole_number();
    if (n && (*n < 5 || *n > 1001)) grid->error(fmt::format("must be 5 to 1001, got {}", *n));
    if (n && *n >= 5 && *n <= 1001) m.grid = static_cast<int>(*n);
  }
}

}  // namespace

doe::EnvelopeSpec read_envelope_string(const std::string& yaml_text, const std::string& file_name_for_messages) {
  ScenarioReadContext context;
  context.file = file_name_for_messages;
  const YAML::Node tree = load_yaml(yaml_text, file_name_for_messages);
  doe::EnvelopeSpec spec;
  spec.file = file_name_for_messages;
  const YamlValue top(context, tree, tree.Mark(), "", "");
  const auto top_section = top.section();
  if (!tree.IsMap() || !top_section || !top_section->has("envelope")) {
    top.error("not an envelope file: it needs a top-level `envelope:` section (docs/drilling-heat.md)");
    context.diagnostics.throw_if_any();
  }
  top_section->allow_only({"envelope"});
  const auto root = top_section->get("envelope")->section();
  if (root) {
    root->allow_only({"scenario", "set", "factors", "design", "responses", "map", "processes", "threads_per_run",
                      "ranks_per_run"});
    const std::string base = fs::path(file_name_for_messages).parent_path().string();
    spec.scenario = read_scenario_path(*root, base).value_or("");
    spec.set = read_set_list(*root, "set");
    read_factors(*root, spec.factors);
    if (spec.factors.size() < 2 && root->has("factors"))
      root->get("factors")->error("an envelope maps over two factors at least (feed and speed)");
    read_design(*root, spec.design);
    read_envelope_responses(*root, spec);
    read_envelope_map(*root, spec);
    read_runs(*root, spec.processes, spec.threads_per_run, spec.ranks_per_run);
  }
  context.diagnostics.throw_if_any();
  return spec;
}

doe::EnvelopeSpec read_envelope_file(const std::string& path) {
  return read_envelope_string(read_study_file(path, "envelope"), path);
}

doe::CalibrationSpec read_calibration_string(const std::string& yaml_text, const std::string& file_name_for_messages) {
  ScenarioReadContext context;
  context.file = file_name_for_messages;
  const YAML::Node tree = load_yaml(yaml_text, file_name_for_messages);
  CalibrationSpec spec;
  spec.file = file_name_for_messages;
  const YamlValue top(context, tree, tree.Mark(), "", "");
  const auto top_section = top.section();
  if (!tree.IsMap() || !top_section || !top_section->has("calibration")) {
    top.error("not a calibration file: it needs a top-level `calibration:` section (docs/calibration.md)");
    context.diagnostics.throw_if_any();
  }
  top_section->allow_only({"calibration"});
  const auto root = top_section->get("calibration")->section();
  if (root) {
    root->allow_only(
        {"scenario", "reference", "set", "factors", "design", "responses", "solve", "processes", "threads_per_run",
         "ranks_per_run"});
    const std::string base = fs::path(file_name_for_messages).parent_path().string();
    spec.scenario = read_scenario_path(*root, base).value_or("");
    read_reference(*root, base, spec);
    spec.set = read_set_list(*root, "set");
    read_factors(*root, spec.factors);
    read_design(*root, spec.design);
    read_responses(*root, spec);
    read_solve(*root, spec);
    read_runs(*root, spec.processes, spec.threads_per_run, spec.ranks_per_run);
  }
  context.diagnostics.throw_if_any();
  return spec;
}

doe::CalibrationSpec read_calibration_file(const std::string& path) {
  return read_calibration_string(read_study_file(path, "calibration"), path);
}

}  // namespace regodem
