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

}  // namespace regodem
