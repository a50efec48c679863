#pragma once
// EDEM's standard rolling friction (Altair EDEM help, "Standard Rolling Friction Model"):
// each body feels a torque against its own spin,
//   tau_i = -mu_r F_n R_i omega_i/|omega_i|,
// with R_i the distance from its centre to the contact point; the two bodies' torques
// differ (neither is the other's reaction). All of a particle's contacts push against the
// same spin, so their resistances add.
//
// The law is set-valued at omega = 0 (a grain at rest holds any torque up to mu_r F_n R_i),
// and it is taken implicitly over the step, as Coulomb friction is in time-stepping
// contact dynamics (Moreau 1988; Stewart 2000): with T every other torque on the
// particle, the spin the next force evaluation would see without rolling friction is
//   omega* = omega + T dt / I;
// if the resistance can stop that within the step (|omega*| <= mu_r F_n R dt / I) the
// torque is the one that does, -(I omega*/dt), else it is the whole resistance against
// omega*. As dt -> 0, omega* -> omega: EDEM's law. Capping at I |omega| / dt alone (the
// other torques left out) lets a grain that should stay put creep at |T| dt / I, a spin
// that grows with the step: the tiny heated drill's work then fell to half when the step
// doubled twice (docs/drilling-heat.md, "What depends on the step").
#include <algorithm>
#include <cmath>

#include "core/vec3.hpp"

namespace regodem {

struct RollingOwnSpin {
  /// mu_r F_n R_i: one contact's share of the resisting torque's magnitude.
  static double resistance_N_m(double rolling_friction, double elastic_normal_force_N, double contact_arm_m) {
    return rolling_friction * std::max(elastic_normal_force_N, 0.0) * contact_arm_m;
  }
  /// The torque of a particle's summed resistance, given its spin at the force evaluation
  /// and every other torque on it this step.
  static Vec3 torque(const Vec3& angular_velocity, const Vec3& other_torque_N_m, double total_resistance_N_m,
                     double inv_inertia, double time_step_s) {
    if (total_resistance_N_m <= 0.0) return {};
    const double spin_per_torque = time_step_s * inv_inertia;  // |d omega| per unit torque in one step
    const Vec3 free_spin = angular_velocity + other_torque_N_m * spin_per_torque;
    const double rate = norm(free_spin);
    if (rate == 0.0) return {};
    if (total_resistance_N_m * spin_per_torque >= rate) return free_spin * (-1.0 / spin_per_torque);
    return free_spin * (-total_resistance_N_m / rate);
  }
};

}  // namespace regodem
