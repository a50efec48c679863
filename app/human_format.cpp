#include "human_format.hpp"

#include <cmath>

#include <fmt/format.h>

#include "sim/time_scale.hpp"

namespace regodem::app {

std::string format_wall_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0.0) return "?";
  if (seconds < 10.0) return fmt::format("{:.2f} s", seconds);
  if (seconds < 600.0) return fmt::format("{:.1f} s", seconds);
  const auto whole_s = static_cast<long long>(std::llround(seconds));
  if (whole_s < 3600) return fmt::format("{} min {:02} s", whole_s / 60, whole_s % 60);
  return fmt::format("{} h {:02} min", whole_s / 3600, (whole_s % 3600) / 60);
}

std::string format_simulated_time(double seconds) {
  if (!std::isfinite(seconds)) return fmt::format("{} s", seconds);
  return fmt::format("{:.4g} s", seconds);
}

std::string real_time_note(double time_scale_factor, std::initializer_list<double> simulated_s,
                           const char* separator) {
  const TimeScale scale{time_scale_factor};
  if (!scale.compressed() || simulated_s.size() == 0) return "";
  std::string times;
  for (const double t : simulated_s) {
    if (!times.empty()) times += separator;
    times += format_simulated_time(scale.real_time_s(t));
  }
  return fmt::format(" ({} real, S = {:.4g})", times, time_scale_factor);
}

std::string format_compact(double value) {
  if (!std::isfinite(value)) return fmt::format("{}", value);
  if (value == 0.0) return "0";
  const double magnitude = std::fabs(value);
  if (magnitude >= 100.0 && magnitude < 1e4) return fmt::format("{:.0f}", value);
  if (magnitude >= 1e-3 && magnitude < 100.0) return fmt::format("{:.3g}", value);
  // "2.1e7" rather than printf's "2.1e+07".
  const int exponent = static_cast<int>(std::floor(std::log10(std::fabs(value))));
  double mantissa = value / std::pow(10.0, exponent);
  int shown_exponent = exponent;
  if (std::fabs(std::round(mantissa * 10.0) / 10.0) >= 10.0) {  // 9.96e6 rounds to 1.0e7
    mantissa /= 10.0;
    ++shown_exponent;
  }
  return fmt::format("{:.1f}e{}", mantissa, shown_exponent);
}

}  // namespace regodem::app
