#pragma once
// Constant directional torque rolling friction on the relative spin (DESIGN.md section 2;
// Ai et al. 2011 type A, LIGGGHTS `rolling_friction cdt`): with omega_r the relative
// angular velocity less its normal component, the torque on i is
// -mu_r F_n^e R* omega_r/|omega_r|, and j feels the opposite. It is capped so that on its own it cannot reverse
// omega_r within one step (|tau| <= |omega_r| / (dt (1/I_i + 1/I_j))), which removes
// the chatter of a body at rest.
#include <algorithm>
#include <cmath>

#include "core/vec3.hpp"

namespace regodem {

struct RollingConstantTorque {
  static Vec3 evaluate(const Vec3& relative_angular_velocity, const Vec3& normal, double rolling_friction,
                       double elastic_normal_force_N, double effective_radius_m, double inv_inertia_sum,
                       double time_step_s) {
    if (rolling_friction <= 0.0) return {};
    const Vec3 rolling = relative_angular_velocity - dot(relative_angular_velocity, normal) * normal;
    const double rate = norm(rolling);
    if (rate == 0.0) return {};
    double magnitude = rolling_friction * std::max(elastic_normal_force_N, 0.0) * effective_radius_m;
    const double reverses_at = time_step_s * inv_inertia_sum;  // |d omega| per unit torque in one step
    if (magnitude * reverses_at > rate) return rolling * (-1.0 / reverses_at);
    return rolling * (-magnitude / rate);
  }
};

}  // namespace regodem
