#pragma once
// Mindlin no-slip tangential spring with Coulomb limit (DESIGN.md section 2):
//   S_t = 8 G* sqrt(R* delta_n), F_t = -S_t xi - gamma_t v_t, |F_t| <= mu_s max(F_n, 0).
// The history xi is the accumulated tangential displacement, rotated into the current
// tangent plane each step with its length kept (as LAMMPS does), and truncated while
// sliding so that the spring alone carries the Coulomb force.
#include <cmath>

#include "core/vec3.hpp"

namespace regodem {

struct MindlinTangential {
  static double stiffness(double effective_shear_Pa, double contact_radius_m) {
    return 8.0 * effective_shear_Pa * contact_radius_m;
  }

  /// Updates the history and returns the tangential force on i; `sliding` says whether
  /// the Coulomb limit cut it (friction then dissipates |F_t . v_t|).
  static Vec3 evaluate(Vec3& history_m, const Vec3& normal, const Vec3& tangential_velocity,
                       double stiffness_N_per_m, double damping_N_s_per_m, double coulomb_limit_N,
                       double time_step_s, bool& sliding) {
    const double off_plane = dot(history_m, normal);
    if (off_plane != 0.0) {
      const double length2 = norm2(history_m);
      history_m -= off_plane * normal;
      const double new_length2 = norm2(history_m);
      if (new_length2 > 0.0) history_m *= std::sqrt(length2 / new_length2);
    }
    history_m += tangential_velocity * time_step_s;
    const Vec3 damping_force = tangential_velocity * damping_N_s_per_m;
    Vec3 force = -(history_m * stiffness_N_per_m) - damping_force;
    const double force2 = norm2(force);
    sliding = force2 > coulomb_limit_N * coulomb_limit_N;
    if (sliding) {
      force *= coulomb_limit_N / std::sqrt(force2);
      history_m = -(force + damping_force) / stiffness_N_per_m;
    }
    return force;
  }
};

}  // namespace regodem
