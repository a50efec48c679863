#include "measure/thermal_history.hpp"

#include <algorithm>
#include <limits>

namespace regodem {

double ThermalHistorySummary::crossed_fraction() const {
  return particles > 0 ? static_cast<double>(crossed) / static_cast<double>(particles)
                       : std::numeric_limits<double>::quiet_NaN();
}

ThermalHistorySummary thermal_history_summary(const ParticleStore& particles, double threshold_K) {
  ThermalHistorySummary s;
  s.particles = particles.size();
  if (s.particles == 0) {
    s.peak_temperature_max_K = s.time_above_threshold_mean_s = s.time_above_threshold_max_s =
        std::numeric_limits<double>::quiet_NaN();
    return s;
  }
  double peak = -std::numeric_limits<double>::infinity(), time_sum = 0.0, time_max = 0.0;
  for (std::size_t i = 0; i < s.particles; ++i) {
    peak = std::max(peak, particles.peak_temperature_K[i]);
    s.crossed += particles.peak_temperature_K[i] > threshold_K ? 1 : 0;
    time_sum += particles.time_above_threshold_s[i];
    time_max = std::max(time_max, particles.time_above_threshold_s[i]);
  }
  s.peak_temperature_max_K = peak;
  s.time_above_threshold_mean_s = time_sum / static_cast<double>(s.particles);
  s.time_above_threshold_max_s = time_max;
  return s;
}

}  // namespace regodem
