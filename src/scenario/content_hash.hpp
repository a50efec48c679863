#pragma once
// A fingerprint of what a run was asked to do: the scenario file's bytes plus the
// --set overrides, so two summary.json files with the same hash ran the same input.
#include <string>
#include <string_view>
#include <vector>

namespace regodem {

/// FNV-1a 64 of the bytes, then of each override (each preceded by a 0 byte so that
/// "a=1","b" and "a=1b" differ), as 16 lower-case hex digits.
std::string scenario_content_hash(std::string_view file_bytes,
                                  const std::vector<std::string>& overrides);

}  // namespace regodem
