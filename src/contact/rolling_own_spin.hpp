#pragma once
// EDEM's standard rolling friction (Altair EDEM help, "Standard Rolling Friction Model"):
// each body feels a torque against its own spin,
//   tau_i = -mu_r F_n R_i omega_i/|omega_i|,
// with R_i the distance from its centre to the contact point; the two bodies' torques
// differ (neither is the other's reaction). All of a particle's contacts push against the
// same spin, so their resistances add, and the sum is capped so that it cannot reverse
// omega_i within one step (|tau| <= |omega_i| / (dt / I_i)); capping each contact alone
// would let n contacts reverse it n times over, and the spin of a grain at rest chatter.
#include <algorithm>
#include <cmath>

#include "core/vec3.hpp"

namespace regodem {

struct RollingOwnSpin {
  /// mu_r F_n R_i: one contact's share of the resisting torque's magnitude.
  static double resistance_N_m(double rolling_friction, double elastic_normal_force_N, double contact_arm_m) {
    return rolling_friction * std::max(elastic_normal_force_N, 0.0) * contact_arm_m;
  }
  /// The torque of a particle's summed resistance against its spin, capped.
  static Vec3 torque(const Vec3& angular_velocity, double total_resistance_N_m, double inv_inertia,
                     double time_step_s) {
    const double rate = norm(angular_velocity);
    if (rate == 0.0 || total_resistance_N_m <= 0.0) return {};
    const double reverses_at = time_step_s * inv_inertia;  // |d omega| per unit torque in one step
    if (total_resistance_N_m * reverses_at > rate) return angular_velocity * (-1.0 / reverses_at);
    return angular_velocity * (-total_resistance_N_m / rate);
  }
};

}  // namespace regodem
