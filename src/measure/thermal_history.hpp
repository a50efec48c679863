#pragma once
// The mission's question, per particle: the highest temperature it reached and how long
// it spent above a threshold (by default -70 degC = 203.15 K, where water ice starts to
// sublimate in vacuum). Both are ParticleStore fields (peak_temperature_K,
// time_above_threshold_s), so they travel with the particles through sorting and
// checkpoints; the heat update calls record_thermal_history() for each particle.
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>
#include <vector>

#include "core/exact_sum.hpp"
#include "core/particle_store.hpp"
#include "measure/measure_region.hpp"

namespace regodem {

constexpr double kDefaultThermalThreshold_K = 203.15;  // -70 degC

/// One heat step of one particle from old_K to new_K over dt_s. The temperature is
/// taken as linear over the step, so the time above the threshold is exact for a
/// piecewise-linear path sampled at the steps (a crossing counts the part of its step
/// beyond the threshold).
inline void record_thermal_history(double old_K, double new_K, double dt_s, double threshold_K, double& peak_K,
                                   double& time_above_s) {
  if (new_K > peak_K) peak_K = new_K;
  const bool old_above = old_K > threshold_K, new_above = new_K > threshold_K;
  if (old_above && new_above)
    time_above_s += dt_s;
  else if (old_above != new_above)  // crossed within the step: new_K != old_K
    time_above_s += dt_s * ((old_above ? old_K : new_K) - threshold_K) / std::abs(new_K - old_K);
}

/// Over all particles: the highest peak, how many peaked above the threshold, and the
/// mean time above it.
struct ThermalHistorySummary {
  std::size_t particles = 0;
  std::size_t crossed = 0;
  double peak_temperature_max_K = 0.0;  // NaN without particles
  double time_above_threshold_mean_s = 0.0;
  double time_above_threshold_max_s = 0.0;
  double crossed_fraction() const;
};
ThermalHistorySummary thermal_history_summary(const ParticleStore& particles, double threshold_K);

/// The summary's parts, which several MPI ranks' merge (the sum of times is exact, so
/// the mean does not depend on the particles' order).
class ThermalHistorySums {
 public:
  void add(double peak_K, double time_above_s, bool crossed);
  void merge(const ThermalHistorySums& other);
  ThermalHistorySummary result() const;
  /// For a message between ranks (as ExactSum's).
  void append_to(std::vector<double>& out) const;
  static ThermalHistorySums read_from(std::span<const double> in, std::size_t& at);

 private:
  std::size_t particles_ = 0, crossed_ = 0;
  double peak_max_K_ = -std::numeric_limits<double>::infinity(), time_max_s_ = 0.0;
  ExactSum time_sum_s_;
};
/// Over the particles not flagged in left_out (measure_region.hpp).
ThermalHistorySums thermal_history_sums(const ParticleStore& particles, double threshold_K, LeftOut left_out = {});

}  // namespace regodem
