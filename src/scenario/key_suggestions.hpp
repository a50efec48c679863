#pragma once
// "did you mean 'density'?": the closest allowed word to a misspelt key, value or name.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace regodem {

/// Edit distance (insertions, deletions, substitutions and swaps of neighbours each
/// count 1), ignoring ASCII case.
std::size_t edit_distance(std::string_view a, std::string_view b);

/// The candidate closest to `typed`, if it is close enough to be a plausible typo
/// (at most a third of the longer word, and at least one edit allowed).
std::optional<std::string> closest_match(std::string_view typed,
                                         const std::vector<std::string>& candidates);

/// " (did you mean 'density'?)" or "" when nothing is close.
std::string did_you_mean(std::string_view typed, const std::vector<std::string>& candidates);

}  // namespace regodem
