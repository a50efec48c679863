#include "measure/thermal_history.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace regodem {

double ThermalHistorySummary::crossed_fraction() const {
  return particles > 0 ? static_cast<double>(crossed) / static_cast<double>(particles)
                       : std::numeric_limits<double>::quiet_NaN();
}

void ThermalHistorySums::add(double peak_K, double time_above_s, bool crossed) {
  ++particles_;
  crossed_ += crossed ? 1 : 0;
  peak_max_K_ = std::max(peak_max_K_, peak_K);
  time_sum_s_.add(time_above_s);
  time_max_s_ = std::max(time_max_s_, time_above_s);
}

void ThermalHistorySums::merge(const ThermalHistorySums& other) {
  particles_ += other.particles_;
  crossed_ += other.crossed_;
  peak_max_K_ = std::max(peak_max_K_, other.peak_max_K_);
  time_sum_s_.merge(other.time_sum_s_);
  time_max_s_ = std::max(time_max_s_, other.time_max_s_);
}

ThermalHistorySummary ThermalHistorySums::result() const {
  ThermalHistorySummary s;
  s.particles = particles_;
  s.crossed = crossed_;
  if (particles_ == 0) {
    s.peak_temperature_max_K = s.time_above_threshold_mean_s = s.time_above_threshold_max_s =
        std::numeric_limits<double>::quiet_NaN();
    return s;
  }
  s.peak_temperature_max_K = peak_max_K_;
  s.time_above_threshold_mean_s = time_sum_s_.value() / static_cast<double>(particles_);
  s.time_above_threshold_max_s = time_max_s_;
  return s;
}

void ThermalHistorySums::append_to(std::vector<double>& out) const {
  out.insert(out.end(), {static_cast<double>(particles_), static_cast<double>(crossed_), peak_max_K_, time_max_s_});
  time_sum_s_.append_to(out);
}

ThermalHistorySums ThermalHistorySums::read_from(std::span<const double> in, std::size_t& at) {
  if (at + 4 > in.size())
    throw std::invalid_argument("a thermal history record at " + std::to_string(at) + " is cut short");
  ThermalHistorySums s;
  s.particles_ = static_cast<std::size_t>(in[at]);
  s.crossed_ = static_cast<std::size_t>(in[at + 1]);
  s.peak_max_K_ = in[at + 2];
  s.time_max_s_ = in[at + 3];
  at += 4;
  s.time_sum_s_ = ExactSum::read_from(in, at);
  return s;
}

ThermalHistorySums thermal_history_sums(const ParticleStore& particles, double threshold_K, LeftOut left_out) {
  ThermalHistorySums sums;
  for (std::size_t i = 0; i < particles.size(); ++i)
    if (left_out.empty() || !left_out[i])
      sums.add(particles.peak_temperature_K[i], particles.time_above_threshold_s[i],
               particles.peak_temperature_K[i] > threshold_K);
  return sums;
}

ThermalHistorySummary thermal_history_summary(const ParticleStore& particles, double threshold_K) {
  return thermal_history_sums(particles, threshold_K).result();
}

}  // namespace regodem
