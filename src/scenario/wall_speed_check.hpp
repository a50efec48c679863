#pragma once
// How well the step resolves the impacts of moving walls, said before a run: a fast
// wall (a drill's flutes) strikes a grain at rest at up to its fastest point's speed,
// and the Hertz contact that follows lasts t_c (sim/time_step.hpp). A contact resolved
// in few steps gets its force history, and so its damping and friction losses (the heat
// of `dissipation_heating`), coarsely and step-dependently. The Rayleigh bound of the
// step says nothing about this: it depends on the wall's speed, not only on the grain.
#include <string>
#include <vector>

#include "core/material.hpp"
#include "geometry/wall_set.hpp"
#include "sim/impact_record.hpp"

namespace regodem {

/// The worst-resolved impact of one moving wall body.
struct WallImpact {
  std::uint32_t body = 0;
  double fastest_speed_m_per_s = 0.0;
  double contact_time_s = 0.0;  // the shortest Hertz contact it can make at that speed
  double steps = 0.0;           // contact_time_s / the time step
};

struct WallSpeedReport {
  std::vector<WallImpact> impacts;    // one per moving wall body that can strike a grain
  std::vector<std::string> lines;     // one per moving wall body
  std::vector<std::string> warnings;  // one per wall whose impacts get too few steps
};

/// For each moving wall body (a warning under kMinimumStepsPerImpact steps): its fastest surface point's speed, how far it moves in a
/// step against the smallest radius, and the shortest Hertz contact of a grain at rest
/// it strikes at that speed (the smallest grain of each particle material against each
/// material of the body, the mechanics' E*), in steps. smallest_radius_m[material] is
/// infinite for a material no particle has. rayleigh_fraction: the scenario's, or 0 when
/// it gives a time step (the advice then names a time step only).
WallSpeedReport wall_speed_report(WallSet& walls, const MaterialTable& materials,
                                  const std::vector<double>& smallest_radius_m, double time_step_s,
                                  double rayleigh_fraction);

}  // namespace regodem
