#pragma once
// Word-level parsing shared by the text mesh readers (ASCII STL, OBJ).
#include <string_view>
#include <vector>

namespace regodem {

/// The whitespace-separated words of a line, as views into it.
std::vector<std::string_view> split_words(std::string_view line);
/// Parses a whole word as a double ("+1.0e+00" too); false if any of it is not a number.
bool parse_double(std::string_view word, double& value);

}  // namespace regodem
