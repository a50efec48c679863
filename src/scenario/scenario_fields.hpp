#pragma once
// Checks shared by several sections: names, references to materials and stages, sizes,
// directions and extents inside the domain.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/vec3.hpp"
#include "scenario/scenario_sections.hpp"
#include "scenario/yaml_section.hpp"

namespace regodem {

enum class Presence { optional, required };

/// Reads `key` as a quantity and checks it with `valid`; `rule` completes "must ..."
/// in the message ("be greater than 0").
std::optional<double> read_checked_quantity(const YamlSection& section, std::string_view key,
                                            Dimension dimension, Presence presence,
                                            bool (*valid)(double), std::string_view rule);

bool is_positive(double value);
bool is_non_negative(double value);
bool is_any(double value);

/// A non-empty list of quantities, each checked with `valid` ("must `rule`").
std::optional<std::vector<double>> read_quantity_list(const YamlValue& value, Dimension dimension,
                                                      bool (*valid)(double), std::string_view rule);

/// Rows of a table written as two lists of equal length under `x_key` and `y_key`,
/// e.g. {temperature: [100 K, 350 K], value: [300, 900 J/(kg K)]}; x strictly increases.
struct TableColumn {
  std::string key;
  Dimension dimension;
  bool (*valid)(double);
  std::string_view rule;
};
struct TableRows {
  std::vector<double> x, y;
};
std::optional<TableRows> read_table(const YamlValue& value, const TableColumn& x,
                                    const TableColumn& y);

/// A length given as `radius_key` or as `diameter_key` (exactly one when required),
/// greater than 0; returns the radius.
std::optional<double> read_radius(const YamlSection& section, std::string_view radius_key,
                                  std::string_view diameter_key, Presence presence);

/// A direction (list of three numbers), normalised; zero length is an error.
std::optional<Vec3> read_direction(const YamlSection& section, std::string_view key,
                                   Presence presence);

/// The item's required `name`.
std::optional<std::string> read_item_name(const YamlSection& item);

/// Reports every name used a second time in one list; `what` is "wall", "stage"...
struct NamedPlace {
  std::string name;
  SourceLocation where;
};
void report_duplicate_names(const std::vector<NamedPlace>& names, std::string_view what,
                            ScenarioDiagnostics& diagnostics);

/// A name that must be one of `known` (materials, stages); otherwise an error that
/// says so with a suggestion. `what` is "material" or "stage".
std::optional<std::string> read_reference(const YamlValue& value,
                                          const std::vector<std::string>& known,
                                          std::string_view what);

/// An input file named by `value`: relative to the scenario file (so a scenario and its
/// files travel together), returned absolute (so whoever opens it later need not know
/// where the scenario was); a missing file is reported.
std::optional<std::string> read_input_file(const YamlValue& value, const ScenarioReferences& references);

/// An axis-aligned box around a shape.
struct Bounds {
  Vec3 min_m, max_m;
};

/// Bounds of a solid cylinder from the centre of its bottom end along the unit axis.
Bounds cylinder_bounds(const Vec3& base_m, const Vec3& unit_axis, double radius_m,
                       double length_m);

/// Reports a shape that reaches outside the domain (touching its faces is fine).
void check_inside_domain(const YamlValue& at, const Bounds& extent,
                         const ScenarioReferences& references, std::string_view what);

}  // namespace regodem
