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
  Vec3 angular_velocity_i_rad_per_s;
  Vec3 angular_velocity_j_rad_per_s;  // the wall's for a wall
  double contact_arm_i_m = 0.0;     // centre of i to the contact point (R_i - delta/2; R_i - delta at a wall)
  double contact_arm_j_m = 0.0;     // 0 for a wall
  double inv_inertia_i = 0.0;       // 1/I_i, for the rolling cap
  double inv_inertia_j = 0.0;       // 1/I_j (0 for a wall)
  double time_step_s = 0.0;
  // Time over which the tangential spring accumulates slip: the step, or 0 when forces
  // are re-evaluated at an unchanged state (after an insertion) so no slip is counted twice.
  double slip_time_s = 0.0;
};

/// m* = 1/(1/m_i + 1/m_j); 0 when neither body can move (two held particles, or a held
/// one at a wall), so that damping, which acts on a relative motion there cannot be,
/// gives 0 and not infinity times 0.
inline double effective_mass_kg(double inverse_mass_sum_per_kg) {
  return inverse_mass_sum_per_kg > 0.0 ? 1.0 / inverse_mass_sum_per_kg : 0.0;
}

struct ContactForces {
  Vec3 force_on_i_N;               // normal + tangential force on i (j feels the opposite)
  Vec3 tangential_force_on_i_N;    // its tangential part, which makes torques
  Vec3 rolling_torque_on_i_N_m;    // relative-spin model; j feels the opposite
  // Own-spin model (EDEM's): mu_r F_n R_i and R_j; each particle's torque comes from the
  // sum over its contacts (RollingOwnSpin::torque). 0 for j at a wall.
  double own_spin_resistance_i_N_m = 0.0;
  double own_spin_resistance_j_N_m = 0.0;
  double elastic_normal_force_N = 0.0;  // F_n^e, also what conduction uses (DESIGN.md Eq. 1)
  double contact_radius_m = 0.0;        // a = sqrt(R* delta_n) for Hertz, the conduction laws' a
  double sliding_power_W = 0.0;         // |F_t . v_t| while sliding (Coulomb-limited), else 0
  double approach_speed_m_per_s = 0.0;  // v . n, > 0 while closing (sim/impact_record.hpp)
  // The contact's losses but rolling's (docs/physics.md, "Energy audit"): normal damping
  // (F_n - F_n^e) v_n and what the tangential force takes less what its spring keeps.
  // Rolling torques are capped to stop a spin within a step, so their loss is found per
  // particle at the spin the step ends with (Simulation::book_rolling_losses).
  double dissipated_power_W = 0.0;
  // Stored in the springs after this evaluation: Hertz 2/5 F_n^e delta_n + k_t |xi|^2 / 2.
  double elastic_energy_J = 0.0;
  // What the tangential spring's energy gained over the step that no force's work put in:
  // its stiffening with the overlap and its reset while sliding (contact_law.hpp).
  double spring_source_W = 0.0;
};

}  // namespace regodem
