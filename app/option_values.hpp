#pragma once
// Small parsers for option values of the form NAME=VALUE, shared by `doe` and `fit`;
// each throws InputError with the option's name and the text it could not read.
#include <string>
#include <utility>
#include <vector>

namespace regodem::app {

/// The whole of `text` as a finite number (no trailing characters).
double parse_number(const std::string& text, const std::string& option);

/// "NAME=VALUE" split at the first '=', both parts trimmed and non-empty.
std::pair<std::string, std::string> split_name_value(const std::string& text, const std::string& option,
                                                     const std::string& form);

/// Comma-separated items, trimmed; empty items are an error.
std::vector<std::string> split_list(const std::string& text, const std::string& option);

std::string trimmed(const std::string& text);

}  // namespace regodem::app
