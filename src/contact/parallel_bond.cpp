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

namespace {

using bond_kernel::V3;
V3<double> lanes(const Vec3& v) { return {v.x, v.y, v.z}; }
Vec3 vec(const V3<double>& v) { return {v.x, v.y, v.z}; }

}  // namespace

bond_kernel::SeriesRotation<double> bond_spin_rotation(const V3<double>& phi) {
  bond_kernel::SeriesRotation<double> r = bond_kernel::series_rotation(phi);
  const double a2 = dot(phi, phi);
  if (!(a2 < bond_kernel::kSeriesLimit)) {
    const double a = std::sqrt(a2);
    r.c = std::cos(a);
    r.s1 = std::sin(a) / a;
    r.c1 = (1.0 - r.c) / a2;
  }
  return r;
}

Vec3 rotate_by(const Vec3& v, const Vec3& phi) { return vec(bond_spin_rotation(lanes(phi))(lanes(v))); }

Vec3 rotate_between(const Vec3& v, const Vec3& a, const Vec3& b) {
  return vec(bond_kernel::smallest_rotation(lanes(a), lanes(b))(lanes(v)));
}

bond_kernel::BondStepInput<double> bond_step_input(const BondParameters& p, const BondSection& section,
                                                   double rest_length_m, const BondKinematics& k,
                                                   const Vec3& normal, const BondLoads& loads) {
  bond_kernel::BondStepInput<double> in;
  in.separation = lanes(k.position_j_m - k.position_i_m);
  in.centre_velocity = lanes(k.velocity_j_m_per_s - k.velocity_i_m_per_s);
  in.spin_i = lanes(k.angular_velocity_i_rad_per_s);
  in.spin_j = lanes(k.angular_velocity_j_rad_per_s);
  in.radius_i = k.radius_i_m;
  in.radius_j = k.radius_j_m;
  in.rest_length = rest_length_m;
  in.normal = lanes(normal);
  in.normal_force = loads.normal_force_N;
  in.twist_moment = loads.twist_moment_N_m;
  in.shear_force = lanes(loads.shear_force_N);
  in.bend_moment = lanes(loads.bend_moment_N_m);
  in.normal_stiffness = p.normal_stiffness_Pa_per_m * section.area_m2;
  in.shear_stiffness = p.shear_stiffness_Pa_per_m * section.area_m2;
  in.twist_stiffness = p.shear_stiffness_Pa_per_m * section.polar_inertia_m4;
  in.bend_stiffness = p.normal_stiffness_Pa_per_m * section.inertia_m4;
  return in;
}

BondAction update_bond(const BondParameters& p, const BondSection& section, double rest_length_m,
                       const BondKinematics& k, double dt_s, double effective_mass_kg,
                       double effective_inertia_kg_m2, Vec3& normal, BondLoads& loads) {
  // Steps 1-3 (turn the stored loads with the pair, the relative motion at the bond, the
  // increments) are bond_kernel::bond_step, which the batched pass runs on lanes too.
  const bond_kernel::BondStepInput<double> in = bond_step_input(p, section, rest_length_m, k, normal, loads);
  // The pair's mean spin over the step (exact for a rigid rotation of the pair, whatever its axis).
  const bond_kernel::BondStepOutput<double> s =
      bond_kernel::bond_step(in, bond_spin_rotation((in.spin_i + in.spin_j) * (0.5 * dt_s)), dt_s);
  normal = vec(s.normal);
  loads.normal_force_N = s.normal_force;
  loads.shear_force_N = vec(s.shear_force);
  loads.twist_moment_N_m = s.twist_moment;
  loads.bend_moment_N_m = vec(s.bend_moment);

  // 4. Forces, with the optional viscous damping of each component.
  double normal_force = s.normal_force, twist = s.twist_moment;
  V3<double> shear_force = s.shear_force, bend_moment = s.bend_moment;
  BondAction out;
  if (p.damping_ratio > 0.0) {
    const double c = 2.0 * p.damping_ratio;
    const double c_normal = c * std::sqrt(in.normal_stiffness * effective_mass_kg),
                 c_shear = c * std::sqrt(in.shear_stiffness * effective_mass_kg);
    const double c_twist = c * std::sqrt(in.twist_stiffness * effective_inertia_kg_m2),
                 c_bend = c * std::sqrt(in.bend_stiffness * effective_inertia_kg_m2);
    normal_force += c_normal * s.normal_speed;
    shear_force = shear_force + s.shear_velocity * c_shear;
    twist += c_twist * s.twist_rate;
    bend_moment = bend_moment + s.bend_rate * c_bend;
    // Each damper opposes its own rate, and takes c rate^2 from the motion.
    out.loss_W = c_normal * s.normal_speed * s.normal_speed + c_shear * dot(s.shear_velocity, s.shear_velocity) +
                 c_twist * s.twist_rate * s.twist_rate + c_bend * dot(s.bend_rate, s.bend_rate);
  }
  const bond_kernel::BondForces<double> f =
      bond_kernel::bond_forces(s.normal, normal_force, shear_force, twist, bend_moment, s.arm_i, s.arm_j);
  out.force_on_i_N = vec(f.force_on_i);
  out.torque_on_i_N_m = vec(f.torque_on_i);
  out.torque_on_j_N_m = vec(f.torque_on_j);
  return out;
}

}  // namespace regodem
