#pragma once
// One time step of a lumped wall's nodes (docs/drilling-heat.md, "The drill as a thermal
// body"): node s of N takes its contacts' heat, conducts to its neighbours along the rod,
// radiates, and the last one exchanges with a held end:
//   C_s dT_s/dt = Q_s + G (T_{s-1} - T_s) + G (T_{s+1} - T_s)
//                 - eps sigma A_s (T_s^4 - T_sur^4) + [s = N-1] G_h (T_h - T_s),
// stepped by explicit Euler, every exchange scaled by the time-scale factor S as the
// contact conductances are. One node with no exchanges is T += Q dt / C, as before.
#include <span>

#include "thermal/thermal_wall.hpp"

namespace regodem {

inline constexpr double kStefanBoltzmann_W_per_m2K4 = 5.670374419e-8;

/// Heat the step took across the wall's own boundaries (J): out by radiation, in
/// through the held end.
struct WallBoundaryHeat {
  double radiated_J = 0.0;
  double held_end_in_J = 0.0;
};

/// Steps the nodes T (in place); contact_heat_W[s] is what node s takes from its
/// contacts (conducted and generated). Throws SimulationError when a step would be unstable
/// (the radiation's 4 eps sigma A T^3 grows with T).
WallBoundaryHeat step_lumped_wall(std::span<double> temperature_K, std::span<const double> heat_capacity_J_per_K,
                                  std::span<const double> area_m2, std::span<const double> contact_heat_W,
                                  const WallRod& rod, double dt_s, double time_scale);

/// The largest step explicit Euler takes stably for the rod's linear exchanges (links
/// and held end; radiation is checked as it runs): min_s C_s / sum_s G.
double lumped_wall_stability_limit_s(std::span<const double> heat_capacity_J_per_K, const WallRod& rod,
                                     double time_scale);

}  // namespace regodem
