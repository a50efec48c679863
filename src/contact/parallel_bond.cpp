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

/// A rotation by the rotation vector phi in Rodrigues form, v' = v c + (phi x v) s1 +
/// phi (phi.v) c1 with c = cos a, s1 = sin(a)/a, c1 = (1 - cos a)/a^2, a = |phi|. The
/// bond pass turns three vectors by one spin per bond per step, where a is tiny: the
/// series (error a^8/9! < 1e-21 for a < 0.01) then replaces sin, cos and the square root.
struct Rotation {
  Vec3 phi;
  double c = 1.0, s1 = 1.0, c1 = 0.5;

  explicit Rotation(const Vec3& rotation_vector) : phi(rotation_vector) {
    const double a2 = norm2(phi);
    if (a2 < 1e-4) {
      s1 = 1.0 - a2 / 6.0 * (1.0 - a2 / 20.0 * (1.0 - a2 / 42.0));
      c1 = 0.5 * (1.0 - a2 / 12.0 * (1.0 - a2 / 30.0 * (1.0 - a2 / 56.0)));
      c = 1.0 - a2 * c1;
    } else {
      const double a = std::sqrt(a2);
      c = std::cos(a);
      s1 = std::sin(a) / a;
      c1 = (1.0 - c) / a2;
    }
  }
  Vec3 operator()(const Vec3& v) const { return v * c + cross(phi, v) * s1 + phi * (dot(phi, v) * c1); }
};

}  // namespace

Vec3 rotate_by(const Vec3& v, const Vec3& phi) { return Rotation(phi)(v); }

namespace {

/// The smallest rotation taking unit vector a onto unit vector b, about a x b, without
/// trigonometry: v' = v c + (k x v) + k (k.v)/(1 + c), k = a x b (|k| = sin), c = a.b.
struct MinimalRotation {
  Vec3 k;
  double c = 1.0, c1 = 0.5;
  bool flip = false;  // a half turn: the bond flipped, no meaningful frame

  MinimalRotation(const Vec3& a, const Vec3& b) : k(cross(a, b)), c(dot(a, b)) {
    flip = c <= -1.0 + 1e-12;
    if (!flip) c1 = 1.0 / (1.0 + c);
  }
  Vec3 operator()(const Vec3& v) const { return flip ? -v : v * c + cross(k, v) + k * (dot(k, v) * c1); }
};

}  // namespace

Vec3 rotate_between(const Vec3& v, const Vec3& a, const Vec3& b) { return MinimalRotation(a, b)(v); }

BondAction update_bond(const BondParameters& p, const BondSection& section, double rest_length_m,
                       const BondKinematics& k, double dt_s, double effective_mass_kg,
                       double effective_inertia_kg_m2, Vec3& normal, BondLoads& loads) {
  const Vec3 d = k.position_j_m - k.position_i_m;
  const double length = norm(d), inv_length = 1.0 / length;
  const Vec3 n = d * inv_length;

  // 1. Turn the stored loads with the pair: first with the mean spin of the two
  // particles over the step (exact for a rigid rotation of the pair, whatever its axis),
  // then by the smallest rotation that takes the spun old normal onto the new one (the
  // part of the normal's change that relative translation made).
  const Rotation spin((k.angular_velocity_i_rad_per_s + k.angular_velocity_j_rad_per_s) * (0.5 * dt_s));
  const MinimalRotation align(spin(normal), n);
  Vec3 shear = align(spin(loads.shear_force_N));
  Vec3 bend = align(spin(loads.bend_moment_N_m));
  // Round-off leaves a tiny normal component; the in-plane loads stay in the plane.
  shear -= n * dot(shear, n);
  bend -= n * dot(bend, n);
  normal = n;

  // 2. Relative motion of j with respect to i at the bond, whose centre lies on the
  // line of centres at arm_i from i (midway into the gap or overlap, as for contacts).
  // The velocities are those that moved the centres over the step, so the lever arms
  // are taken at mid-step, d_mid = d - (v_j - v_i) dt/2: for a rigid rotation by theta
  // per step the contact points then slip by theta^3/12 of the arm instead of
  // theta^2/2 (the Cayley form of a rotation), so a spinning pair loads no spring.
  const double arm_i = 0.5 * (length + k.radius_i_m - k.radius_j_m);
  const double arm_j = length - arm_i;
  const Vec3 wi = k.angular_velocity_i_rad_per_s, wj = k.angular_velocity_j_rad_per_s;
  const Vec3 centre_velocity = k.velocity_j_m_per_s - k.velocity_i_m_per_s;
  const Vec3 d_mid = d - centre_velocity * (0.5 * dt_s);
  const Vec3 n_mid = normalized(d_mid);
  const Vec3 relative_velocity =
      centre_velocity - cross(wj, d_mid * (arm_j * inv_length)) - cross(wi, d_mid * (arm_i * inv_length));
  const double normal_speed = dot(relative_velocity, n_mid);
  Vec3 shear_velocity = relative_velocity - n_mid * normal_speed;
  shear_velocity -= n * dot(shear_velocity, n);  // into the new bond plane
  const Vec3 relative_spin = wj - wi;
  const double twist_rate = dot(relative_spin, n_mid);
  Vec3 bend_rate = relative_spin - n_mid * twist_rate;
  bend_rate -= n * dot(bend_rate, n);

  // 3. Increments (Potyondy & Cundall 2004 Eq. 10, 11; DESIGN.md section 2), and the
  // normal force from the total stretch.
  const double kn_area = p.normal_stiffness_Pa_per_m * section.area_m2;
  const double ks_area = p.shear_stiffness_Pa_per_m * section.area_m2;
  const double kt = p.shear_stiffness_Pa_per_m * section.polar_inertia_m4;
  const double kb = p.normal_stiffness_Pa_per_m * section.inertia_m4;
  loads.normal_force_N = kn_area * (length - rest_length_m);
  loads.shear_force_N = shear + shear_velocity * (ks_area * dt_s);
  loads.twist_moment_N_m += kt * twist_rate * dt_s;
  loads.bend_moment_N_m = bend + bend_rate * (kb * dt_s);

  // 4. Forces, with the optional viscous damping of each component.
  double normal_force = loads.normal_force_N, twist = loads.twist_moment_N_m;
  Vec3 shear_force = loads.shear_force_N, bend_moment = loads.bend_moment_N_m;
  BondAction out;
  if (p.damping_ratio > 0.0) {
    const double c = 2.0 * p.damping_ratio;
    const double c_normal = c * std::sqrt(kn_area * effective_mass_kg), c_shear = c * std::sqrt(ks_area * effective_mass_kg);
    const double c_twist = c * std::sqrt(kt * effective_inertia_kg_m2), c_bend = c * std::sqrt(kb * effective_inertia_kg_m2);
    normal_force += c_normal * normal_speed;
    shear_force += shear_velocity * c_shear;
    twist += c_twist * twist_rate;
    bend_moment += bend_rate * c_bend;
    // Each damper opposes its own rate, and takes c rate^2 from the motion.
    out.loss_W = c_normal * normal_speed * normal_speed + c_shear * norm2(shear_velocity) +
                 c_twist * twist_rate * twist_rate + c_bend * norm2(bend_rate);
  }
  out.force_on_i_N = n * normal_force + shear_force;
  const Vec3 lever = cross(n, shear_force);
  out.torque_on_i_N_m = n * twist + bend_moment + lever * arm_i;
  out.torque_on_j_N_m = -(n * twist + bend_moment) + lever * arm_j;
  return out;
}

}  // namespace regodem
