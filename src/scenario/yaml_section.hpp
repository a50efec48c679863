#pragma once
// Typed, located reading of the scenario's YAML tree. Every value knows its key path
// and where it came from (a line of the file, or a --set override), and every read
// reports its own problems to the diagnostics and yields nothing, so the reader can go
// on and collect all problems of a file in one pass.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "core/vec3.hpp"
#include "scenario/scenario_diagnostics.hpp"
#include "scenario/scenario_spec.hpp"
#include "scenario/units.hpp"

namespace regodem {

/// A value node that a --set override put into the tree, with the override's text.
struct OverrideOrigin {
  YAML::Node value;
  std::string text;  // "materials.regolith.density=2500"
};

/// Shared by all values of one scenario read.
struct ScenarioReadContext {
  std::string file;  // as named in messages
  ScenarioDiagnostics diagnostics;
  std::vector<OverrideOrigin> overrides;

  /// The override text if `node` is the value of a --set override, else "".
  std::string override_text_of(const YAML::Node& node) const;
};

class YamlSection;

/// One node of the tree with its key path and origin.
class YamlValue {
 public:
  /// origin: the --set text that supplied this node or an ancestor, or "" for the file.
  YamlValue(ScenarioReadContext& context, YAML::Node node, YAML::Mark mark, std::string path,
            std::string origin);

  const YAML::Node& node() const { return node_; }
  const std::string& path() const { return path_; }
  SourceLocation where() const;
  void error(const std::string& message) const;
  bool is_null() const { return node_.IsNull(); }
  ScenarioReadContext& context() const { return *context_; }

  /// A child of this node: its path is path() + "." + key (or "[i]"), its origin this
  /// one's unless the child itself came from a --set override.
  YamlValue child(const YAML::Node& child_node, YAML::Mark mark, std::string child_path) const;

  std::optional<std::string> text() const;
  std::optional<double> quantity(Dimension dimension) const;
  /// A list of three quantities, e.g. [0, 0, -9.81 m/s^2].
  std::optional<Vec3> vector(Dimension dimension) const;
  std::optional<bool> boolean() const;
  /// A non-negative whole number ("2000", "2e3").
  std::optional<std::uint64_t> whole_number() const;
  /// One of `allowed`; otherwise an error that lists them and suggests the closest.
  std::optional<std::string> choice(const std::vector<std::string>& allowed) const;
  /// A name of a material, wall, stage...: letters, digits, '_' and '-'.
  std::optional<std::string> name() const;
  std::optional<YamlSection> section() const;
  /// The items of a list; each item's path uses its `name` when it has one
  /// ("walls.barrel"), else its index ("walls[0]"). An absent (null) list is empty.
  std::optional<std::vector<YamlValue>> items() const;

 private:
  std::string describe_kind() const;

  ScenarioReadContext* context_;
  YAML::Node node_;
  YAML::Mark mark_;
  std::string path_;
  std::string origin_;
};

/// A YAML map. Keys are declared with allow_only(); the rest are reported as unknown
/// with the closest allowed key as a suggestion. Duplicate keys are reported too.
class YamlSection {
 public:
  explicit YamlSection(const YamlValue& map_value);

  const YamlValue& value() const { return self_; }
  const std::string& path() const { return self_.path(); }
  SourceLocation where() const { return self_.where(); }
  void error(const std::string& message) const { self_.error(message); }

  /// Reports every key not in `allowed`. `misplaced_hint` may explain keys that belong
  /// elsewhere ("'normal' is for plane and disk walls; a cylinder takes 'axis'").
  void allow_only(const std::vector<std::string>& allowed,
                  const std::vector<std::pair<std::string, std::string>>& misplaced_hint = {}) const;

  bool has(std::string_view key) const;
  /// The value under `key` if present (a null value counts as present).
  std::optional<YamlValue> get(std::string_view key) const;
  /// Like get(), but a missing key is reported, unless allow_only() already suggested
  /// it for a misspelt key (one problem, one message).
  std::optional<YamlValue> require(std::string_view key) const;

  /// Reports that none or more than one of `keys` is present ("give exactly one of...").
  /// Returns the one present, if exactly one is. Missing ones are not reported when a
  /// misspelt key was suggested as one of them.
  std::optional<std::string> exactly_one_of(const std::vector<std::string>& keys) const;
  /// Reports more than one of `keys`; returns the one present, if any.
  std::optional<std::string> at_most_one_of(const std::vector<std::string>& keys) const;

  std::optional<double> quantity(std::string_view key, Dimension dimension) const;
  std::optional<double> required_quantity(std::string_view key, Dimension dimension) const;
  std::optional<Vec3> vector(std::string_view key, Dimension dimension) const;
  std::optional<Vec3> required_vector(std::string_view key, Dimension dimension) const;
  std::optional<std::string> text(std::string_view key) const;
  std::optional<bool> boolean(std::string_view key) const;

  struct Entry {
    std::string key;
    YamlValue value;
  };
  const std::vector<Entry>& entries() const { return entries_; }

 private:
  bool was_suggested(std::string_view key) const;

  YamlValue self_;
  std::vector<Entry> entries_;
  mutable std::vector<std::string> suggested_keys_;  // by allow_only, for misspelt keys
  std::vector<YAML::Mark> key_marks_;  // parallel to entries_
};

/// Parses YAML text; a syntax error is an InputError "file:line:column: YAML syntax
/// error: ..." (`file` as named in messages). Refused as well, located: text that is
/// not UTF-8 or holds a NUL or control character (a binary file), lists or maps nested
/// more than 64 deep, and a second document after '---' (which would be ignored).
YAML::Node load_yaml(const std::string& text, const std::string& file);

/// Names of materials, walls, stages...: letters, digits, '_' and '-' (they appear in
/// --set paths and, later, in output file names).
bool is_valid_name(std::string_view name);

/// path + "." + key, or key at the top level.
std::string join_path(std::string_view path, std::string_view key);

}  // namespace regodem
