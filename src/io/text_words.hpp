#pragma once
// Word-level parsing shared by the text readers (ASCII STL, OBJ, CSV), and text made
// safe to quote in a message.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace regodem {

/// The whitespace-separated words of a line, as views into it.
std::vector<std::string_view> split_words(std::string_view line);
/// Parses a whole word as a double ("+1.0e+00" too); false if any of it is not a number.
bool parse_double(std::string_view word, double& value);

/// The length of the UTF-8 sequence that starts at text[i] (1 for ASCII), or 0 if
/// none does there (a stray or truncated byte).
std::size_t utf8_sequence_length(std::string_view text, std::size_t i);

/// `text` for a message: control bytes and bytes that are not UTF-8 text as \xNN, at
/// most `max_characters` characters and "..." after, so that a damaged file is not
/// echoed back raw.
std::string printable_excerpt(std::string_view text, std::size_t max_characters = 60);

}  // namespace regodem
