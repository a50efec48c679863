#pragma once
// Viscous damping tuned to a restitution coefficient (EDEM / Tsuji form, DESIGN.md
// section 2): magnitude 2 sqrt(5/6) |beta| sqrt(S m*) |v|, opposing v, with S the
// normal stiffness S_n for the normal part and the tangential S_t for the tangential
// part. With Hertz and no force clamping the rebound speed ratio equals e exactly.
#include <cmath>

namespace regodem {

struct RestitutionDamping {
  /// Damping coefficient (N s/m) for stiffness S and effective mass m*.
  static double coefficient(double damping_factor, double stiffness_N_per_m, double effective_mass_kg) {
    return damping_factor * std::sqrt(stiffness_N_per_m * effective_mass_kg);
  }
};

}  // namespace regodem
