#include "contact/parallel_bond.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace regodem {

BondParameters zhao2023_bond_parameters() {
  BondParameters p;
  p.normal_stiffness_Pa_per_m = 3e10;
  p.shear_stiffness_Pa_per_m = 1.5e9;
  p.tensile_strength_Pa = 1.2e11;
  p.shear_strength_Pa = 6e10;
  p.radius_multiplier = 1.0;
  return p;
}

BondParameters icy_regolith_bond_parameters() {
  BondParameters p;
  // Stiff enough that the bond is no softer than the Hertz contacts of 0.6 mm grains
  // (a bond modulus k_n 2R ~ 0.6 GPa), soft enough that six bonds per grain stay stable
  // at 0.2 of the Rayleigh step (omega dt ~ 0.5); k_n/k_s = 2.5 as is usual for PFC.
  p.normal_stiffness_Pa_per_m = 1e12;
  p.shear_stiffness_Pa_per_m = 4e11;
  p.tensile_strength_Pa = 30e6;
  p.shear_strength_Pa = 30e6;
  p.radius_multiplier = 1.0;
  return p;
}

BondSection BondSection::of_radius(double radius_m) {
  BondSection s;
  s.radius_m = radius_m;
  const double r2 = radius_m * radius_m;
  s.area_m2 = std::numbers::pi * r2;
  s.inertia_m4 = 0.25 * std::numbers::pi * r2 * r2;
  s.polar_inertia_m4 = 2.0 * s.inertia_m4;
  s.inv_area_per_m2 = 1.0 / s.area_m2;
  s.radius_over_inertia_per_m3 = radius_m / s.inertia_m4;
  s.radius_over_polar_inertia_per_m3 = radius_m / s.polar_inertia_m4;
  return s;
}

double bond_elastic_energy_J(const BondParameters& p, const BondSection& section, const BondLoads& loads) {
  const double kn_area = p.normal_stiffness_Pa_per_m * section.area_m2;
  const double ks_area = p.shear_stiffness_Pa_per_m * section.area_m2;
  const double kt = p.shear_stiffness_Pa_per_m * section.polar_inertia_m4;
  const double kb = p.normal_stiffness_Pa_per_m * section.inertia_m4;
  return 0.5 * (loads.normal_force_N * loads.normal_force_N / kn_area + norm2(loads.shear_force_N) / ks_area +
                loads.twist_moment_N_m * loads.twist_moment_N_m / kt + norm2(loads.bend_moment_N_m) / kb);
}

}  // namespace regodem
