// Reading YAML values with their locations. yaml-cpp marks are 0-based; messages are
// 1-based like every editor. Map keys are never looked up with operator[], which would
// insert missing keys into the tree: the entries are collected once, in file order.
#include "scenario/yaml_section.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "core/error.hpp"
#include "io/text_words.hpp"
#include "scenario/key_suggestions.hpp"

namespace regodem {

std::string join_path(std::string_view path, std::string_view key) {
  if (path.empty()) return std::string(key);
  return fmt::format("{}.{}", path, key);
}

std::string ScenarioReadContext::override_text_of(const YAML::Node& node) const {
  for (const OverrideOrigin& origin : overrides) {
    if (origin.value.is(node)) return origin.text;
  }
  return {};
}

// ---------------------------------------------------------------------------- YamlValue

YamlValue::YamlValue(ScenarioReadContext& context, YAML::Node node, YAML::Mark mark,
                     std::string path, std::string origin)
    : context_(&context),
      node_(std::move(node)),
      mark_(mark),
      path_(std::move(path)),
      origin_(std::move(origin)) {}

SourceLocation YamlValue::where() const {
  if (!origin_.empty()) return {"--set " + origin_, 0, 0, path_};
  if (path_.empty() || mark_.is_null()) return {context_->file, 0, 0, path_};
  return {context_->file, mark_.line + 1, mark_.column + 1, path_};
}

void YamlValue::error(const std::string& message) const {
  context_->diagnostics.error(where(), message);
}

YamlValue YamlValue::child(const YAML::Node& child_node, YAML::Mark mark,
                           std::string child_path) const {
  std::string child_origin = context_->override_text_of(child_node);
  if (child_origin.empty()) child_origin = origin_;
  return YamlValue(*context_, child_node, mark, std::move(child_path), std::move(child_origin));
}

std::string YamlValue::describe_kind() const {
  if (node_.IsSequence()) return "a list";
  if (node_.IsMap()) return "a map";
  if (node_.IsNull()) return "nothing";
  return "'" + printable_excerpt(node_.Scalar()) + "'";
}

std::optional<std::string> YamlValue::text() const {
  if (!node_.IsScalar()) {
    error(fmt::format("expected a text, got {}", describe_kind()));
    return std::nullopt;
  }
  return node_.Scalar();
}

std::optional<double> YamlValue::quantity(Dimension dimension) const {
  if (!node_.IsScalar()) {
    error(fmt::format("expected {} (e.g. {}), got {}", dimension_description(dimension),
                      dimension_example(dimension), describe_kind()));
    return std::nullopt;
  }
  try {
    return parse_quantity(node_.Scalar(), dimension);
  } catch (const InputError& problem) {
    error(problem.what());
    return std::nullopt;
  }
}

std::optional<Vec3> YamlValue::vector(Dimension dimension) const {
  if (!node_.IsSequence() || node_.size() != 3) {
    error(fmt::format("expected a list of three components, each {} (e.g. [0, 0, {}]), got {}",
                      dimension_description(dimension), dimension_example(dimension),
                      node_.IsSequence() ? fmt::format("a list of {}", node_.size())
                                         : describe_kind()));
    return std::nullopt;
  }
  double components[3] = {0.0, 0.0, 0.0};
  bool all_read = true;
  for (std::size_t i = 0; i < 3; ++i) {
    const YAML::Node element = node_[i];
    const auto value = child(element, element.Mark(), fmt::format("{}[{}]", path_, i))
                           .quantity(dimension);
    if (value) {
      components[i] = *value;
    } else {
      all_read = false;
    }
  }
  if (!all_read) return std::nullopt;
  return Vec3{components[0], components[1], components[2]};
}

std::optional<bool> YamlValue::boolean() const {
  bool result = false;
  if (node_.IsScalar() && YAML::convert<bool>::decode(node_, result)) return result;
  error(fmt::format("expected true or false, got {}", describe_kind()));
  return std::nullopt;
}

std::optional<std::uint64_t> YamlValue::whole_number() const {
  const auto value = quantity(Dimension::dimensionless);
  if (!value) return std::nullopt;
  // 2^53: beyond it doubles skip integers, and no count or seed needs more.
  constexpr double kLargestExact = 9007199254740992.0;
  if (*value < 0.0 || *value != std::floor(*value) || *value > kLargestExact) {
    error(fmt::format("expected a whole number of 0 or more, got {}", describe_kind()));
    return std::nullopt;
  }
  return static_cast<std::uint64_t>(*value);
}

std::optional<std::string> YamlValue::choice(const std::vector<std::string>& allowed) const {
  const auto chosen = text();
  if (!chosen) return std::nullopt;
  for (const std::string& option : allowed) {
    if (*chosen == option) return chosen;
  }
  std::string options;
  for (std::size_t i = 0; i < allowed.size(); ++i) {
    if (i > 0) options += i + 1 == allowed.size() ? " or " : ", ";
    options += allowed[i];
  }
  error(fmt::format("'{}' is not one of {}{}", *chosen, options, did_you_mean(*chosen, allowed)));
  return std::nullopt;
}

namespace {

/// Line and column (1-based) of byte `offset` of `text`.
std::pair<int, int> line_and_column(std::string_view text, std::size_t offset) {
  int line = 1, column = 1;
  for (std::size_t i = 0; i < offset; ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return {line, column};
}

/// A scenario is UTF-8 text: a NUL, another control character or a byte that is not
/// UTF-8 means a binary or damaged file, which the YAML parser would otherwise report
/// as an "unknown escape character" or echo back raw.
void check_is_text(std::string_view text, const std::string& file) {
  for (std::size_t i = 0; i < text.size();) {
    const auto byte = static_cast<unsigned char>(text[i]);
    const std::size_t length = utf8_sequence_length(text, i);
    const bool control = byte < 0x20 && byte != '\t' && byte != '\n' && byte != '\r';
    if (length == 0 || control || byte == 0x7f) {
      const auto [line, column] = line_and_column(text, i);
      throw InputError(fmt::format("{}:{}:{}: {} (byte 0x{:02x}): this is not a text file (a scenario is YAML, as UTF-8 "
                                   "text)",
                                   file, line, column,
                                   byte == 0 ? "a NUL byte" : length == 0 ? "not UTF-8" : "a control character",
                                   byte));
    }
    i += length;
  }
}

/// Lists and maps nested deeper than any scenario needs ("[[[[..."): the parser would
/// recurse until it gives up with "bad file".
void check_nesting(std::string_view text, const std::string& file) {
  constexpr int kMaxDepth = 64;
  int depth = 0;
  char quote = 0;
  bool comment = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') comment = false;
    if (comment) continue;
    if (quote) {
      if (c == quote) quote = 0;
      continue;
    }
    // A quote opens a quoted scalar only where one can start (don't is plain text).
    const char before = i == 0 ? '\n' : text[i - 1];
    const bool scalar_start = before == ' ' || before == '\n' || before == '\t' || before == '[' ||
                              before == '{' || before == ',' || before == ':' || before == '-';
    if ((c == '"' || c == '\'') && scalar_start) quote = c;
    else if (c == '#' && (i == 0 || text[i - 1] == ' ' || text[i - 1] == '\n')) comment = true;
    else if (c == '[' || c == '{') {
      if (++depth > kMaxDepth) {
        const auto [line, column] = line_and_column(text, i);
        throw InputError(fmt::format("{}:{}:{}: lists or maps nested more than {} deep; no scenario needs that", file,
                                     line, column, kMaxDepth));
      }
    } else if (c == ']' || c == '}') {
      depth = std::max(0, depth - 1);
    }
  }
}

}  // namespace

YAML::Node load_yaml(const std::string& text, const std::string& file) {
  check_is_text(text, file);
  check_nesting(text, file);
  std::vector<YAML::Node> documents;
  try {
    documents = YAML::LoadAll(text);
  } catch (const YAML::ParserException& problem) {
    // yaml-cpp says "bad file" when its nesting guard trips (block lists thousands deep).
    const std::string what = problem.msg == YAML::ErrorMsg::BAD_FILE
                                 ? std::string("lists or maps nested too deep to read; no scenario needs that")
                                 : "YAML syntax error: " + problem.msg;
    throw InputError(fmt::format("{}:{}:{}: {}", file, problem.mark.line + 1, problem.mark.column + 1, what));
  }
  // A second document ("---" and more) would be silently ignored: refuse it.
  for (std::size_t k = 1; k < documents.size(); ++k)
    if (!documents[k].IsNull())
      throw InputError(fmt::format("{}:{}: a second YAML document (after '---'): a scenario is one document; remove "
                                   "it, or put it in a file of its own",
                                   file, documents[k].Mark().line + 1));
  return documents.empty() ? YAML::Node() : documents.front();
}

bool is_valid_name(std::string_view name) {
  if (name.empty()) return false;
  for (const char c : name) {
    const bool allowed = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
                         (c >= '0' && c <= '9') || c == '_' || c == '-';
    if (!allowed) return false;
  }
  return true;
}

std::optional<std::string> YamlValue::name() const {
  const auto value = text();
  if (!value) return std::nullopt;
  if (!is_valid_name(*value)) {
    error(fmt::format("'{}' is not a valid name: use letters, digits, '_' and '-'", *value));
    return std::nullopt;
  }
  return value;
}

std::optional<YamlSection> YamlValue::section() const {
  if (!node_.IsMap() && !node_.IsNull()) {
    error(fmt::format("expected a map of 'key: value' entries, got {}", describe_kind()));
    return std::nullopt;
  }
  return YamlSection(*this);
}

std::optional<std::vector<YamlValue>> YamlValue::items() const {
  if (node_.IsNull()) return std::vector<YamlValue>{};
  if (!node_.IsSequence()) {
    error(fmt::format("expected a list (entries starting with '- '), got {}", describe_kind()));
    return std::nullopt;
  }
  std::vector<YamlValue> result;
  for (std::size_t i = 0; i < node_.size(); ++i) {
    const YAML::Node item = node_[i];
    std::string item_path = fmt::format("{}[{}]", path_, i);
    if (item.IsMap()) {
      const YAML::Node item_name = item["name"];  // const access: inserts nothing
      if (item_name.IsDefined() && item_name.IsScalar() && is_valid_name(item_name.Scalar())) {
        item_path = join_path(path_, item_name.Scalar());
      }
    }
    result.push_back(child(item, item.Mark(), std::move(item_path)));
  }
  return result;
}

// -------------------------------------------------------------------------- YamlSection

YamlSection::YamlSection(const YamlValue& map_value) : self_(map_value) {
  if (!self_.node().IsMap()) return;  // null: an empty section
  for (const auto& pair : self_.node()) {
    const YAML::Node& key_node = pair.first;
    const YAML::Node& value_node = pair.second;
    if (!key_node.IsScalar()) {
      self_.child(key_node, key_node.Mark(), self_.path())
          .error("keys must be plain words, not lists or maps");
      continue;
    }
    const std::string key = key_node.Scalar();
    // A scalar is located where it is written. A section (map or list) is located at the
    // key that names it: a block map's own mark is its first key, on the next line, and
    // a null value's mark is past the key's line.
    const YAML::Mark value_mark = value_node.IsScalar() ? value_node.Mark() : key_node.Mark();
    YamlValue value = self_.child(value_node, value_mark, join_path(self_.path(), key));
    if (has(key)) {
      value.error(fmt::format("duplicate key '{}'", key));
      continue;
    }
    entries_.push_back({key, std::move(value)});
    key_marks_.push_back(key_node.Mark());
  }
}

void YamlSection::allow_only(
    const std::vector<std::string>& allowed,
    const std::vector<std::pair<std::string, std::string>>& misplaced_hint) const {
  for (std::size_t i = 0; i < entries_.size(); ++i) {
    const Entry& entry = entries_[i];
    bool known = false;
    for (const std::string& key : allowed) known = known || key == entry.key;
    if (known) continue;
    std::string hint;
    for (const auto& [key, explanation] : misplaced_hint) {
      if (key == entry.key) hint = " (" + explanation + ")";
    }
    if (hint.empty()) {
      if (const auto suggestion = closest_match(entry.key, allowed)) {
        hint = " (did you mean '" + *suggestion + "'?)";
        suggested_keys_.push_back(*suggestion);
      }
    }
    // Located at the key itself (a --set override keeps its own description).
    SourceLocation where = entry.value.where();
    if (where.line > 0 && !key_marks_[i].is_null()) {
      where.line = key_marks_[i].line + 1;
      where.column = key_marks_[i].column + 1;
    }
    self_.context().diagnostics.error(where, "unknown key" + hint);
  }
}

bool YamlSection::has(std::string_view key) const {
  for (const Entry& entry : entries_) {
    if (entry.key == key) return true;
  }
  return false;
}

std::optional<YamlValue> YamlSection::get(std::string_view key) const {
  for (const Entry& entry : entries_) {
    if (entry.key == key) return entry.value;
  }
  return std::nullopt;
}

bool YamlSection::was_suggested(std::string_view key) const {
  for (const std::string& suggested : suggested_keys_) {
    if (suggested == key) return true;
  }
  return false;
}

std::optional<YamlValue> YamlSection::require(std::string_view key) const {
  auto value = get(key);
  if (!value && !was_suggested(key)) error(fmt::format("missing required key '{}'", key));
  return value;
}

namespace {

std::string quoted_list(const std::vector<std::string>& keys) {
  std::string text;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    if (i > 0) text += i + 1 == keys.size() ? " or " : ", ";
    text += "'" + keys[i] + "'";
  }
  return text;
}

}  // namespace

std::optional<std::string> YamlSection::at_most_one_of(const std::vector<std::string>& keys) const {
  std::vector<std::string> present;
  for (const std::string& key : keys) {
    if (has(key)) present.push_back(key);
  }
  if (present.size() > 1) {
    error(fmt::format("give only one of {}", quoted_list(present)));
    return std::nullopt;
  }
  if (present.empty()) return std::nullopt;
  return present.front();
}

std::optional<std::string> YamlSection::exactly_one_of(const std::vector<std::string>& keys) const {
  bool any = false;
  bool suggested = false;
  for (const std::string& key : keys) {
    any = any || has(key);
    suggested = suggested || was_suggested(key);
  }
  if (!any) {
    if (suggested) return std::nullopt;
    error(fmt::format("missing {}: give one of them", quoted_list(keys)));
    return std::nullopt;
  }
  return at_most_one_of(keys);
}

std::optional<double> YamlSection::quantity(std::string_view key, Dimension dimension) const {
  const auto value = get(key);
  return value ? value->quantity(dimension) : std::nullopt;
}

std::optional<double> YamlSection::required_quantity(std::string_view key,
                                                     Dimension dimension) const {
  const auto value = require(key);
  return value ? value->quantity(dimension) : std::nullopt;
}

std::optional<Vec3> YamlSection::vector(std::string_view key, Dimension dimension) const {
  const auto value = get(key);
  return value ? value->vector(dimension) : std::nullopt;
}

std::optional<Vec3> YamlSection::required_vector(std::string_view key, Dimension dimension) const {
  const auto value = require(key);
  return value ? value->vector(dimension) : std::nullopt;
}

std::optional<std::string> YamlSection::text(std::string_view key) const {
  const auto value = get(key);
  return value ? value->text() : std::nullopt;
}

std::optional<bool> YamlSection::boolean(std::string_view key) const {
  const auto value = get(key);
  return value ? value->boolean() : std::nullopt;
}

}  // namespace regodem
