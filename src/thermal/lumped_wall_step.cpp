#include "thermal/lumped_wall_step.hpp"

#include <fmt/format.h>

#include <limits>

#include "core/error.hpp"

namespace regodem {

namespace {

/// The linear conductance node s of n has to its neighbours and the held end.
double linear_conductance_W_per_K(std::size_t s, std::size_t n, const WallRod& rod) {
  double g = 0.0;
  if (s > 0) g += rod.link_conductance_W_per_K;
  if (s + 1 < n) g += rod.link_conductance_W_per_K;
  if (s + 1 == n && rod.held_end_K) g += rod.held_end_conductance_W_per_K;
  return g;
}

}  // namespace

WallBoundaryHeat step_lumped_wall(std::span<double> temperature_K, std::span<const double> heat_capacity_J_per_K,
                                  std::span<const double> area_m2, std::span<const double> contact_heat_W,
                                  const WallRod& rod, double dt_s, double time_scale) {
  WallBoundaryHeat out;
  const std::size_t n = temperature_K.size();
  const double link_W_per_K = rod.link_conductance_W_per_K * time_scale;
  const double radiation = rod.emissivity * kStefanBoltzmann_W_per_m2K4 * time_scale;
  const double surroundings4 = rod.surroundings_K * rod.surroundings_K * rod.surroundings_K * rod.surroundings_K;
  double previous_K = 0.0;  // node s-1's temperature before this step
  for (std::size_t s = 0; s < n; ++s) {
    const double t = temperature_K[s];
    double flow_W = contact_heat_W[s];
    if (s > 0) flow_W += link_W_per_K * (previous_K - t);
    if (s + 1 < n) flow_W += link_W_per_K * (temperature_K[s + 1] - t);
    if (radiation > 0.0) {
      const double t3 = t * t * t;
      // Explicit Euler on the radiation is stable while dt 4 eps sigma A T^3 S / C < 1
      // (with the linear exchanges beside it): a wall too light for its surface.
      const double rate_per_s =
          (4.0 * radiation * area_m2[s] * t3 + linear_conductance_W_per_K(s, n, rod) * time_scale) /
          heat_capacity_J_per_K[s];
      if (rate_per_s * dt_s >= 1.0)
        throw SimulationError(fmt::format(
            "a lumped wall's node {} of {} at {:.4g} K radiates too fast for the time step ({:.3g} s against a "
            "stable {:.3g} s): give the wall more mass, fewer segments or a lower emissivity",
            s + 1, n, t, dt_s, 1.0 / rate_per_s));
      const double radiated_W = radiation * area_m2[s] * (t3 * t - surroundings4);
      flow_W -= radiated_W;
      out.radiated_J += radiated_W * dt_s;
    }
    if (s + 1 == n && rod.held_end_K) {
      const double in_W = rod.held_end_conductance_W_per_K * time_scale * (*rod.held_end_K - t);
      flow_W += in_W;
      out.held_end_in_J += in_W * dt_s;
    }
    previous_K = t;
    temperature_K[s] += flow_W * dt_s / heat_capacity_J_per_K[s];
  }
  return out;
}

double lumped_wall_stability_limit_s(std::span<const double> heat_capacity_J_per_K, const WallRod& rod,
                                     double time_scale) {
  double limit = std::numeric_limits<double>::infinity();
  const std::size_t n = heat_capacity_J_per_K.size();
  for (std::size_t s = 0; s < n; ++s) {
    const double g = linear_conductance_W_per_K(s, n, rod) * time_scale;
    if (g > 0.0) limit = std::min(limit, heat_capacity_J_per_K[s] / g);
  }
  return limit;
}

}  // namespace regodem
