#pragma once
// Hertz elastic normal force (DESIGN.md section 2):
//   F_n = 4/3 E* sqrt(R*) delta^{3/2},  S_n = dF/d(delta) = 2 E* sqrt(R* delta).
#include <cmath>

namespace regodem {

struct HertzNormal {
  struct Result {
    double elastic_force_N;
    double normal_stiffness_N_per_m;  // S_n
    double contact_radius_m;          // a = sqrt(R* delta)
  };
  /// a = sqrt(R* delta): the contact radius of the force law, which conduction uses.
  static double contact_radius_m(double effective_radius_m, double overlap_m) {
    return std::sqrt(effective_radius_m * overlap_m);
  }
  /// The elastic energy of the overlap, the integral of F_n d(delta) = 2/5 F_n delta.
  static double stored_energy_J(double elastic_force_N, double overlap_m) { return 0.4 * elastic_force_N * overlap_m; }
  static Result evaluate(double effective_youngs_Pa, double effective_radius_m, double overlap_m) {
    const double a = contact_radius_m(effective_radius_m, overlap_m);
    return {4.0 / 3.0 * effective_youngs_Pa * a * overlap_m, 2.0 * effective_youngs_Pa * a, a};
  }
};

}  // namespace regodem
