// Shared field checks. Values in messages are quoted as the user wrote them, so that
// "must be greater than 0, got '-0.3 mm'" points at the text in the file.
#include "scenario/scenario_fields.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "scenario/key_suggestions.hpp"

namespace regodem {

bool is_positive(double value) { return value > 0.0; }
bool is_non_negative(double value) { return value >= 0.0; }
bool is_any(double) { return true; }

std::optional<std::vector<double>> read_quantity_list(const YamlValue& value, Dimension dimension,
                                                      bool (*valid)(double), std::string_view rule) {
  if (!value.node().IsSequence() || value.node().size() == 0) {
    value.error(fmt::format("expected a list of one or more values, each {} (e.g. [{}])",
                            dimension_description(dimension), dimension_example(dimension)));
    return std::nullopt;
  }
  const auto items = value.items();
  if (!items) return std::nullopt;
  std::vector<double> result;
  bool complete = true;
  for (const YamlValue& item : *items) {
    const auto quantity = item.quantity(dimension);
    if (quantity && !valid(*quantity)) {
      item.error(fmt::format("must {}, got '{}'", rule, item.node().Scalar()));
    }
    if (!quantity || !valid(*quantity)) {
      complete = false;
      continue;
    }
    result.push_back(*quantity);
  }
  if (!complete) return std::nullopt;
  return result;
}

std::optional<TableRows> read_table(const YamlValue& value, const TableColumn& x,
                                    const TableColumn& y) {
  const auto section = value.section();
  if (!section) return std::nullopt;
  section->allow_only({x.key, y.key});
  const auto x_value = section->require(x.key);
  const auto y_value = section->require(y.key);
  const auto xs = x_value ? read_quantity_list(*x_value, x.dimension, x.valid, x.rule) : std::nullopt;
  const auto ys = y_value ? read_quantity_list(*y_value, y.dimension, y.valid, y.rule) : std::nullopt;
  if (!xs || !ys) return std::nullopt;
  bool increasing = true;
  for (std::size_t k = 1; k < xs->size(); ++k) {
    if ((*xs)[k] > (*xs)[k - 1]) continue;
    // Located at the offending entry, quoted as written.
    const YAML::Node entry = x_value->node()[k];
    const YAML::Node previous = x_value->node()[k - 1];
    x_value->child(entry, entry.Mark(), fmt::format("{}[{}]", x_value->path(), k))
        .error(fmt::format("the {}s of a table must increase from row to row: '{}' follows '{}'", x.key,
                           entry.Scalar(), previous.Scalar()));
    increasing = false;
  }
  if (xs->size() != ys->size()) {
    y_value->error(fmt::format("has {} value{} but '{}' has {}: give one value per row", ys->size(),
                               ys->size() == 1 ? "" : "s", x.key, xs->size()));
    return std::nullopt;
  }
  if (!increasing) return std::nullopt;
  return TableRows{*xs, *ys};
}

std::optional<double> read_checked_quantity(const YamlSection& section, std::string_view key,
                                            Dimension dimension, Presence presence,
                                            bool (*valid)(double), std::string_view rule) {
  const auto value = presence == Presence::required ? section.require(key) : section.get(key);
  if (!value) return std::nullopt;
  const auto quantity = value->quantity(dimension);
  if (!quantity) return std::nullopt;
  if (!valid(*quantity)) {
    value->error(fmt::format("must {}, got '{}'", rule, value->node().Scalar()));
    return std::nullopt;
  }
  return quantity;
}

std::optional<double> read_radius(const YamlSection& section, std::string_view radius_key,
                                  std::string_view diameter_key, Presence presence) {
  const std::vector<std::string> keys{std::string(radius_key), std::string(diameter_key)};
  const auto chosen =
      presence == Presence::required ? section.exactly_one_of(keys) : section.at_most_one_of(keys);
  if (!chosen) return std::nullopt;
  const auto size = read_checked_quantity(section, *chosen, Dimension::length, Presence::required,
                                          is_positive, "be greater than 0");
  if (!size) return std::nullopt;
  return *chosen == radius_key ? *size : *size / 2.0;
}

std::optional<Vec3> read_direction(const YamlSection& section, std::string_view key,
                                   Presence presence) {
  const auto value = presence == Presence::required ? section.require(key) : section.get(key);
  if (!value) return std::nullopt;
  const auto direction = value->vector(Dimension::dimensionless);
  if (!direction) return std::nullopt;
  if (!(norm(*direction) > 0.0)) {
    value->error("is a direction and must not be [0, 0, 0]");
    return std::nullopt;
  }
  return normalized(*direction);
}

std::optional<std::string> read_item_name(const YamlSection& item) {
  const auto value = item.require("name");
  return value ? value->name() : std::nullopt;
}

void report_duplicate_names(const std::vector<NamedPlace>& names, std::string_view what,
                            ScenarioDiagnostics& diagnostics) {
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i].name.empty()) continue;  // a missing name is reported on its own
    for (std::size_t j = 0; j < i; ++j) {
      if (names[i].name != names[j].name) continue;
      const std::string first =
          names[j].where.line > 0 ? fmt::format(" (first used at line {})", names[j].where.line)
                                  : std::string();
      diagnostics.error(names[i].where,
                        fmt::format("duplicate {} name '{}'{}", what, names[i].name, first));
      break;
    }
  }
}

std::optional<std::string> read_reference(const YamlValue& value,
                                          const std::vector<std::string>& known,
                                          std::string_view what) {
  const auto name = value.text();
  if (!name) return std::nullopt;
  if (std::find(known.begin(), known.end(), *name) != known.end()) return name;
  std::string hint = did_you_mean(*name, known);
  if (hint.empty()) {
    std::string list;
    for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
    hint = list.empty() ? fmt::format(" (no {}s are defined)", what)
                        : fmt::format(" (defined: {})", list);
  }
  value.error(fmt::format("{} '{}' is not defined{}", what, *name, hint));
  return std::nullopt;
}

Bounds cylinder_bounds(const Vec3& base_m, const Vec3& unit_axis, double radius_m,
                       double length_m) {
  const Vec3 top_m = base_m + unit_axis * length_m;
  // A circle of radius r normal to a reaches r*sqrt(1 - a_i^2) along coordinate i.
  const Vec3 reach{radius_m * std::sqrt(std::max(0.0, 1.0 - unit_axis.x * unit_axis.x)),
                   radius_m * std::sqrt(std::max(0.0, 1.0 - unit_axis.y * unit_axis.y)),
                   radius_m * std::sqrt(std::max(0.0, 1.0 - unit_axis.z * unit_axis.z))};
  const Vec3 low{std::min(base_m.x, top_m.x), std::min(base_m.y, top_m.y),
                 std::min(base_m.z, top_m.z)};
  const Vec3 high{std::max(base_m.x, top_m.x), std::max(base_m.y, top_m.y),
                  std::max(base_m.z, top_m.z)};
  return {low - reach, high + reach};
}

void check_inside_domain(const YamlValue& at, const Bounds& extent,
                         const ScenarioReferences& references, std::string_view what) {
  if (!references.domain) return;
  const DomainSpec& domain = *references.domain;
  double largest_side_m = 0.0;
  for (int axis = 0; axis < 3; ++axis) {
    largest_side_m = std::max(largest_side_m, domain.max_m[axis] - domain.min_m[axis]);
  }
  // Shapes flush with a face of the domain are common (a floor at z = min); allow round-off.
  const double tolerance_m = 1e-9 * largest_side_m;
  std::string outside;
  constexpr const char* kAxisNames[3] = {"x", "y", "z"};
  for (int axis = 0; axis < 3; ++axis) {
    if (extent.min_m[axis] >= domain.min_m[axis] - tolerance_m &&
        extent.max_m[axis] <= domain.max_m[axis] + tolerance_m) {
      continue;
    }
    outside += fmt::format("{}{} from {:g} to {:g} m, the domain from {:g} to {:g} m",
                           outside.empty() ? "" : "; ", kAxisNames[axis], extent.min_m[axis],
                           extent.max_m[axis], domain.min_m[axis], domain.max_m[axis]);
  }
  if (!outside.empty()) {
    at.error(fmt::format("{} reaches outside the domain: {}", what, outside));
  }
}

std::optional<std::string> read_input_file(const YamlValue& value, const ScenarioReferences& references) {
  const auto file = value.text();
  if (!file) return std::nullopt;
  std::filesystem::path path(*file);
  if (path.is_relative()) path = std::filesystem::path(references.base_directory) / path;
  std::error_code ignored;
  path = std::filesystem::absolute(path, ignored).lexically_normal();
  const std::filesystem::file_status status = std::filesystem::status(path, ignored);
  if (!std::filesystem::is_regular_file(status)) {
    value.error(std::filesystem::is_directory(status)
                    ? fmt::format("'{}' is a directory; give the file in it", path.string())
                : std::filesystem::exists(status) ? fmt::format("'{}' is not a regular file", path.string())
                                                  : fmt::format("no such file: '{}'", path.string()));
    return std::nullopt;
  }
  return path.string();
}

}  // namespace regodem
