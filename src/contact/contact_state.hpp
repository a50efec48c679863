#pragma once
// The immutable description of one contact handed to a contact law, and what the
// law returns. Body j is another particle or a wall (R = infinity, m = infinity).
#include "core/vec3.hpp"

namespace regodem {

struct ContactGeometry {
  Vec3 normal;                    // unit, from the centre of i towards j
  double overlap_m = 0.0;         // delta_n > 0 in contact
  double effective_radius_m = 0.0;  // R* (R_i for a wall)
  double effective_mass_kg = 0.0;   // m* (m_i for a wall)
  Vec3 relative_velocity_m_per_s;   // velocity of i's surface relative to j's at the contact point
  Vec3 relative_angular_velocity_rad_per_s;  // omega_i - omega_j
  double inv_inertia_sum = 0.0;     // 1/I_i + 1/I_j (1/I_i for a wall), for the rolling cap
  double time_step_s = 0.0;
  // Time over which the tangential spring accumulates slip: the step, or 0 when forces
  // are re-evaluated at an unchanged state (after an insertion) so no slip is counted twice.
  double slip_time_s = 0.0;
};

struct ContactForces {
  Vec3 force_on_i_N;               // normal + tangential force on i (j feels the opposite)
  Vec3 tangential_force_on_i_N;    // its tangential part, which makes torques
  Vec3 rolling_torque_on_i_N_m;    // j feels the opposite
  double elastic_normal_force_N = 0.0;  // F_n^e, also what conduction uses (DESIGN.md Eq. 1)
  double contact_radius_m = 0.0;        // a = sqrt(R* delta_n) for Hertz, the conduction laws' a
  double sliding_power_W = 0.0;         // |F_t . v_t| while sliding (Coulomb-limited), else 0
};

}  // namespace regodem
