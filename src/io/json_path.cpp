#include "io/json_path.hpp"

#include <charconv>
#include <vector>

#include <fmt/format.h>

#include "core/error.hpp"

namespace regodem {
namespace {

/// "a.b[2].c" -> {"a", "b", "2", "c"}; empty segments are kept so that they are refused.
std::vector<std::string> segments_of(std::string_view path) {
  std::vector<std::string> segments(1);
  for (const char c : path) {
    if (c == '.' || c == '[') {
      segments.emplace_back();
    } else if (c != ']') {
      segments.back() += c;
    }
  }
  return segments;
}

std::string listing(const nlohmann::ordered_json& node) {
  std::string text;
  if (node.is_object()) {
    for (const auto& [key, value] : node.items()) text += (text.empty() ? "" : ", ") + key;
    return text.empty() ? "no keys" : "the keys " + text;
  }
  for (std::size_t i = 0; i < node.size(); ++i) {
    const auto& element = node[i];
    const bool named = element.is_object() && element.contains("name") && element["name"].is_string();
    text += (text.empty() ? "" : ", ") + (named ? element["name"].get<std::string>() : std::to_string(i));
  }
  return text.empty() ? "an empty list" : "the elements " + text;
}

const nlohmann::ordered_json* array_element(const nlohmann::ordered_json& array, const std::string& segment) {
  for (const auto& element : array)
    if (element.is_object() && element.contains("name") && element["name"] == segment) return &element;
  std::size_t index = 0;
  const auto [end, error] = std::from_chars(segment.data(), segment.data() + segment.size(), index);
  if (error == std::errc() && end == segment.data() + segment.size() && index < array.size()) return &array[index];
  return nullptr;
}

}  // namespace

const nlohmann::ordered_json& json_at_path(const nlohmann::ordered_json& root, std::string_view path) {
  const nlohmann::ordered_json* node = &root;
  std::string so_far;
  for (const std::string& segment : segments_of(path)) {
    const nlohmann::ordered_json* next = nullptr;
    if (node->is_object() && node->contains(segment)) next = &(*node)[segment];
    if (node->is_array()) next = array_element(*node, segment);
    if (!next || segment.empty()) {
      const std::string where = so_far.empty() ? "the top level" : "'" + so_far + "'";
      if (!node->is_object() && !node->is_array())
        throw InputError(fmt::format("'{}': {} is a value, not an object or a list", path, where));
      throw InputError(fmt::format("'{}': no '{}' in {}, which has {}", path, segment, where, listing(*node)));
    }
    so_far += (so_far.empty() ? "" : ".") + segment;
    node = next;
  }
  return *node;
}

double json_number_at_path(const nlohmann::ordered_json& root, std::string_view path) {
  const nlohmann::ordered_json& value = json_at_path(root, path);
  if (value.is_number()) return value.get<double>();
  if (value.is_null())
    throw InputError(fmt::format("'{}' is null: no value (an empty region or band has no mean temperature)", path));
  throw InputError(fmt::format("'{}' is not a number: {}", path, value.dump()));
}

}  // namespace regodem
