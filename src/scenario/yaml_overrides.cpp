// Navigation uses iteration and index access only: yaml-cpp's operator[] with a missing
// key would quietly add it, and a misspelt middle segment must be an error instead.
#include "scenario/yaml_overrides.hpp"

#include <charconv>
#include <optional>

#include <fmt/format.h>

#include "scenario/key_suggestions.hpp"

namespace regodem {
namespace {

/// "walls[0].radius" -> {"walls", "0", "radius"}; nullopt if a segment is empty.
std::optional<std::vector<std::string>> split_path(std::string_view path) {
  std::vector<std::string> segments;
  std::string current;
  bool after_bracket = false;  // "walls[0].x": the '.' after ']' starts no empty segment
  for (const char c : path) {
    if (c == '.' || c == '[' || c == ']') {
      if (current.empty() && !(c == '.' && after_bracket)) return std::nullopt;
      if (!current.empty()) segments.push_back(current);
      current.clear();
      after_bracket = c == ']';
      continue;
    }
    after_bracket = false;
    current += c;
  }
  if (!current.empty()) {
    segments.push_back(current);
  } else if (!after_bracket) {
    return std::nullopt;
  }
  if (segments.empty()) return std::nullopt;
  return segments;
}

std::optional<std::size_t> parse_index(std::string_view text) {
  std::size_t index = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), index);
  if (error != std::errc{} || end != text.data() + text.size()) return std::nullopt;
  return index;
}

/// The position in a list of the item with this index or `name`.
std::optional<std::size_t> find_item(const YAML::Node& list, const std::string& segment) {
  if (const auto index = parse_index(segment)) {
    if (*index < list.size()) return index;
    return std::nullopt;
  }
  for (std::size_t i = 0; i < list.size(); ++i) {
    const YAML::Node item = list[i];
    if (!item.IsMap()) continue;
    const YAML::Node item_name = item["name"];
    if (item_name.IsDefined() && item_name.IsScalar() && item_name.Scalar() == segment) return i;
  }
  return std::nullopt;
}

std::vector<std::string> item_names(const YAML::Node& list) {
  std::vector<std::string> names;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const YAML::Node item = list[i];
    const YAML::Node item_name = item.IsMap() ? item["name"] : YAML::Node();
    names.push_back(item_name.IsDefined() && item_name.IsScalar() ? item_name.Scalar()
                                                                   : std::to_string(i));
  }
  return names;
}

std::vector<std::string> map_keys(const YAML::Node& map) {
  std::vector<std::string> keys;
  for (const auto& pair : map) {
    if (pair.first.IsScalar()) keys.push_back(pair.first.Scalar());
  }
  return keys;
}

std::string listed(const std::vector<std::string>& words) {
  std::string text;
  for (const std::string& word : words) text += (text.empty() ? "" : ", ") + word;
  return text.empty() ? "none" : text;
}

/// Applies one override; returns an error message, or "" on success.
std::string apply_one(YAML::Node& root, const std::vector<std::string>& segments,
                      const YAML::Node& value) {
  YAML::Node current = root;
  std::string walked;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const std::string& segment = segments[i];
    const bool last = i + 1 == segments.size();
    const std::string where = walked.empty() ? "the top level" : "'" + walked + "'";
    if (current.IsMap() || (current.IsNull() && last)) {
      std::optional<YAML::Node> found;
      for (auto pair : current) {
        // emplace, not '=': assigning one Node to another rewrites the node in the tree.
        if (pair.first.IsScalar() && pair.first.Scalar() == segment) found.emplace(pair.second);
      }
      if (last) {
        if (found) {
          *found = value;  // rebinds the node inside the tree
        } else {
          current[segment] = value;  // a new key; the reader checks it like any other
        }
        return {};
      }
      if (!found) {
        const std::vector<std::string> keys = map_keys(current);
        return fmt::format("no key '{}' in {}{}", segment, where, did_you_mean(segment, keys));
      }
      current.reset(*found);  // moves the handle; '=' would overwrite the node
    } else if (current.IsSequence()) {
      const auto index = find_item(current, segment);
      if (!index) {
        return fmt::format("no item '{}' in {} (its items: {})", segment, where,
                           listed(item_names(current)));
      }
      if (last) {
        current[*index] = value;
        return {};
      }
      current.reset(current[*index]);
    } else {
      return fmt::format("{} is a single value, it has no '{}'", where, segment);
    }
    walked = walked.empty() ? segment : walked + "." + segment;
  }
  return {};
}

}  // namespace

void apply_overrides(YAML::Node& root, const std::vector<std::string>& overrides,
                     ScenarioReadContext& context) {
  for (const std::string& text : overrides) {
    const SourceLocation where{"--set " + text, 0, 0, ""};
    const std::size_t equals = text.find('=');
    const auto segments =
        equals == std::string::npos ? std::nullopt : split_path(std::string_view(text).substr(0, equals));
    if (!segments) {
      context.diagnostics.error(where, "expected key.path=value, e.g. materials.regolith.density=2500");
      continue;
    }
    YAML::Node value;
    try {
      value = YAML::Load(text.substr(equals + 1));
    } catch (const YAML::Exception& problem) {
      context.diagnostics.error(where, "the value is not valid YAML: " + problem.msg);
      continue;
    }
    const std::string problem = apply_one(root, *segments, value);
    if (!problem.empty()) {
      context.diagnostics.error(where, problem);
      continue;
    }
    context.overrides.push_back({value, text});
  }
}

}  // namespace regodem
