#pragma once
// The Rayleigh time: how long a Rayleigh surface wave takes to cross a particle, the
// usual DEM bound for a stable explicit step (DESIGN.md section 2):
//   T_R = pi R sqrt(rho/G) / (0.1631 nu + 0.8766).
#include <cmath>
#include <numbers>

namespace regodem {

inline double rayleigh_time_s(double radius_m, double density_kg_per_m3, double shear_modulus_Pa,
                              double poisson_ratio) {
  return std::numbers::pi * radius_m * std::sqrt(density_kg_per_m3 / shear_modulus_Pa) /
         (0.1631 * poisson_ratio + 0.8766);
}

/// The duration of an elastic Hertz impact at normal speed v (Johnson, Contact Mechanics,
/// 1985, ch. 11): t_c = 2.87 (m*^2 / (R* E*^2 v))^(1/5), with the effective mass,
/// radius and modulus of the pair. LIGGGHTS' check/timestep/gran calls it the Hertz time
/// and warns when the step exceeds a fraction of it (0.1 in its example): below ~10
/// steps a contact's force history, and so its damping loss, is resolved coarsely.
/// Written through the impact's key K = v R* E*^2 / m*^2, t_c = 2.87 K^(-1/5): the
/// shortest contact of many is the one of the largest key, which a contact pass finds
/// with a few multiplications a contact (sim/impact_record.hpp) and one power at the end.
inline double hertz_impact_key(double inverse_effective_mass_per_kg, double effective_radius_m,
                               double effective_youngs_modulus_Pa, double impact_speed_m_per_s) {
  return impact_speed_m_per_s * effective_radius_m * effective_youngs_modulus_Pa * effective_youngs_modulus_Pa *
         inverse_effective_mass_per_kg * inverse_effective_mass_per_kg;
}
inline double hertz_contact_time_from_key_s(double key) { return 2.87 * std::pow(key, -0.2); }
inline double hertz_contact_time_s(double effective_mass_kg, double effective_radius_m,
                                   double effective_youngs_modulus_Pa, double impact_speed_m_per_s) {
  return hertz_contact_time_from_key_s(
      hertz_impact_key(1.0 / effective_mass_kg, effective_radius_m, effective_youngs_modulus_Pa, impact_speed_m_per_s));
}

}  // namespace regodem
