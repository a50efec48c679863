#pragma once
// Numbers as a person reads them on a terminal: short, with units, no more digits
// than matter. Files (CSV, JSON) carry full precision; this is for messages only.
#include <initializer_list>
#include <string>

namespace regodem::app {

/// Wall-clock durations: "0.42 s", "93.4 s", "12 min 05 s", "2 h 03 min".
std::string format_wall_duration(double seconds);

/// Simulated times, which span microseconds to minutes: "0.0125 s", "1.5e-05 s".
std::string format_simulated_time(double seconds);

/// With heat.time_scale_factor S != 1, the real-time equivalents (x S) of simulated
/// times, joined by `separator`: " (165.4 s real, S = 80)", " (0 s to 400 s real, S = 80)".
/// Empty with S = 1.
std::string real_time_note(double time_scale_factor, std::initializer_list<double> simulated_s,
                           const char* separator = " / ");

/// Rates and counts, short: "2.1e7", "4630", "12.5", "0.0031", "4.2e-5", "0".
std::string format_compact(double value);

}  // namespace regodem::app
