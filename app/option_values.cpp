#include "option_values.hpp"

#include <charconv>
#include <cmath>

#include <fmt/format.h>

#include "core/error.hpp"

namespace regodem::app {

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  const auto last = text.find_last_not_of(" \t");
  return text.substr(first, last - first + 1);
}

double parse_number(const std::string& text, const std::string& option) {
  const std::string number = trimmed(text);
  double value = 0.0;
  const char* end = number.data() + number.size();
  const auto [stop, error] = std::from_chars(number.data(), end, value);
  if (number.empty() || error != std::errc() || stop != end || !std::isfinite(value))
    throw InputError(fmt::format("{}: '{}' is not a number", option, text));
  return value;
}

std::pair<std::string, std::string> split_name_value(const std::string& text, const std::string& option,
                                                     const std::string& form) {
  const auto equals = text.find('=');
  if (equals == std::string::npos)
    throw InputError(fmt::format("{} '{}': expected {}", option, text, form));
  std::pair<std::string, std::string> parts{trimmed(text.substr(0, equals)), trimmed(text.substr(equals + 1))};
  if (parts.first.empty() || parts.second.empty())
    throw InputError(fmt::format("{} '{}': expected {}", option, text, form));
  return parts;
}

std::vector<std::string> split_list(const std::string& text, const std::string& option) {
  std::vector<std::string> items;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    items.push_back(trimmed(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start)));
    if (items.back().empty()) throw InputError(fmt::format("{} '{}': an empty item in the list", option, text));
    if (comma == std::string::npos) return items;
    start = comma + 1;
  }
}

}  // namespace regodem::app
