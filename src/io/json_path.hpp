#pragma once
// Dotted key paths into a JSON document such as a run's summary.json:
// "measurements.bands.sieve.final.T_d_K", "stages.heat.end_time_s". A segment names a
// key of an object, or an element of an array by its index ("stages.2", "stages[2]") or
// by its "name" field ("stages.heat"), as --set names list items in a scenario.
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace regodem {

/// The value at `path`. Throws InputError saying which segment was not found and what
/// was there instead (the keys of the object, the names of the array's elements).
const nlohmann::ordered_json& json_at_path(const nlohmann::ordered_json& root, std::string_view path);

/// The number at `path`; a null (an empty region's mean), a text or an object is an
/// InputError that says so.
double json_number_at_path(const nlohmann::ordered_json& root, std::string_view path);

}  // namespace regodem
