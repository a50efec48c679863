#pragma once
// The parallel bond (Potyondy & Cundall 2004; DESIGN.md section 2, "Parallel bonds"):
// a cemented disk of radius R_b = lambda_b min(R_i, R_j) between two spheres, acting
// in parallel with the Hertz-Mindlin contact. This header holds the per-bond law only
// (parameters, state, one update, the stresses); the bond list is bond_store.hpp and
// the pass over all bonds lives in sim/simulation_bonds.cpp.
//
// Particles carry no orientation, so the bond keeps its loads as vectors in the world
// frame and turns them with the pair each step (see update_bond):
//   * F_n: tension (> 0) or compression (< 0) along the bond normal n (from i to j),
//     total form F_n = k_n A (L - L0), L the centre distance, L0 at formation: the
//     same as summing dF_n = k_n A du_n, without drift;
//   * F_s: shear force on i, in the plane normal to n, dF_s = k_s A du_s;
//   * M_t: twisting moment on i about n (a scalar), dM_t = k_s J dtheta_n;
//   * M_b: bending moment on i, in the plane normal to n, dM_b = k_n I dtheta_s.
// du and dtheta are the relative motion of j with respect to i at the bond over the
// step (j's contact point velocity minus i's, times dt; omega_j - omega_i times dt).
// So a stretched bond pulls i towards j (force on i = F_n n + F_s), a sheared one drags
// i along with j, and j feels the opposite force; torque on i = M_t n + M_b +
// arm_i n x F_s, on j = -M_t n - M_b + arm_j n x F_s.
#include <cmath>
#include <cstdint>

#include "core/vec3.hpp"

namespace regodem {

/// Constants of one kind of bond (per material pair).
struct BondParameters {
  double normal_stiffness_Pa_per_m = 0.0;  // k_n, stiffness per unit area (N/m^3)
  double shear_stiffness_Pa_per_m = 0.0;   // k_s
  double tensile_strength_Pa = 0.0;        // sigma_c
  double shear_strength_Pa = 0.0;          // tau_c
  double radius_multiplier = 1.0;          // lambda_b: R_b = lambda_b min(R_i, R_j)
  // Viscous damping of the relative motion at the bond as a fraction of critical
  // (2 zeta sqrt(k m*) per component); 0, as in EDEM and the paper, by default. It
  // damps the force only and never enters the stresses that break the bond.
  double damping_ratio = 0.0;
  // Conduction through the bond: the bond radius acts as a contact radius,
  // G = 2 k_c R_b (DESIGN.md Eq. 1 with a = R_b), off by default as in the paper.
  bool conducts_heat = false;
};

/// The paper's Table 2 (Zhao et al. 2023): k_n = 3e10 N/m^3, k_s = 1.5e9 N/m^3,
/// sigma_c = 1.2e11 Pa, tau_c = 6e10 Pa, lambda_b = 1. Practically unbreakable: a
/// 0.6 mm bond holds ~34 kN and stretches ~4 m first (DESIGN.md section 2).
BondParameters zhao2023_bond_parameters();
/// The default set, icy regolith at cryogenic temperature (docs/physics.md, "Parallel
/// bonds", explains the choice and its sources): k_n = 1e12 N/m^3, k_s = 4e11 N/m^3,
/// sigma_c = tau_c = 30 MPa, lambda_b = 1.
BondParameters icy_regolith_bond_parameters();

/// Geometric constants of a bond of radius R_b: A = pi R_b^2, I = pi R_b^4/4, J = 2I.
struct BondSection {
  double radius_m = 0.0;
  double area_m2 = 0.0;
  double inertia_m4 = 0.0;        // I, bending
  double polar_inertia_m4 = 0.0;  // J, twisting
  // 1/A, R_b/I and R_b/J: the stress check runs every step, without divisions.
  double inv_area_per_m2 = 0.0;
  double radius_over_inertia_per_m3 = 0.0;
  double radius_over_polar_inertia_per_m3 = 0.0;
  static BondSection of_radius(double radius_m);
};

/// The loads a bond carries (world frame, see the header comment).
struct BondLoads {
  double normal_force_N = 0.0;  // F_n, tension positive
  Vec3 shear_force_N;           // F_s on i
  double twist_moment_N_m = 0.0;  // M_t on i about n
  Vec3 bend_moment_N_m;         // M_b on i
};

/// Positions and motions of the two particles at the end of a step: what one bond
/// update needs. Velocities are those over the step (the half-step velocities of
/// velocity Verlet, which moved the positions).
struct BondKinematics {
  Vec3 position_i_m, position_j_m;
  Vec3 velocity_i_m_per_s, velocity_j_m_per_s;
  Vec3 angular_velocity_i_rad_per_s, angular_velocity_j_rad_per_s;
  double radius_i_m = 0.0, radius_j_m = 0.0;
};

enum class BondBreak : std::uint8_t { none, tension, shear };

/// sigma = F_n/A + |M_b| R_b/I and tau = |F_s|/A + |M_t| R_b/J (DESIGN.md section 2).
struct BondStresses {
  double tensile_Pa = 0.0;
  double shear_Pa = 0.0;
};
/// What one update returns: forces and torques on both particles (j's force is the
/// opposite of i's), including damping.
struct BondAction {
  Vec3 force_on_i_N;
  Vec3 torque_on_i_N_m;
  Vec3 torque_on_j_N_m;
  // What the bond's damping takes from the pair's motion (c v^2 per component; 0 without
  // damping), or, in the step it breaks, the mean of its stored energy before and after
  // the step's update, over the step.
  double loss_W = 0.0;
};

/// The elastic energy a bond's loads store: F_n^2/(2 k_n A) + |F_s|^2/(2 k_s A) +
/// M_t^2/(2 k_s J) + |M_b|^2/(2 k_n I), what it releases on breaking.
double bond_elastic_energy_J(const BondParameters& p, const BondSection& section, const BondLoads& loads);

// The per-step functions are defined here, inline: the bond pass calls them once per bond
// per step, and across translation units the compiler could not inline them.

/// sigma and tau of the loads (the formulas above BondStresses).
inline BondStresses bond_stresses(const BondLoads& loads, const BondSection& section) {
  // Potyondy & Cundall (2004) Eq. 12: the bond is a beam of circular section.
  BondStresses s;
  s.tensile_Pa = loads.normal_force_N * section.inv_area_per_m2 +
                 norm(loads.bend_moment_N_m) * section.radius_over_inertia_per_m3;
  s.shear_Pa = norm(loads.shear_force_N) * section.inv_area_per_m2 +
               std::abs(loads.twist_moment_N_m) * section.radius_over_polar_inertia_per_m3;
  return s;
}

/// Tension when sigma > sigma_c, shear when tau > tau_c; where both fail, the criterion
/// exceeded by the larger ratio to its strength names the mode.
inline BondBreak bond_failure(const BondStresses& stresses, const BondParameters& p) {
  if (stresses.tensile_Pa <= p.tensile_strength_Pa && stresses.shear_Pa <= p.shear_strength_Pa) return BondBreak::none;
  const double tension = stresses.tensile_Pa / p.tensile_strength_Pa;
  const double shear = stresses.shear_Pa / p.shear_strength_Pa;
  if (!(tension > 1.0) && !(shear > 1.0)) return BondBreak::none;
  return tension >= shear ? BondBreak::tension : BondBreak::shear;
}

/// True when the bond holds: bond_failure(bond_stresses(loads, section), p) is none. The
/// pass asks it of every bond every step, so it compares the stresses' parts squared and
/// takes no square root (sigma <= sigma_c is |M_b| R_b/I <= sigma_c - F_n/A); only a
/// bond that fails needs its stresses. NaN loads do not hold here, so the caller falls
/// back to bond_failure, which decides them as before.
inline bool bond_holds(const BondLoads& loads, const BondSection& section, const BondParameters& p) {
  const double tension_left = p.tensile_strength_Pa - loads.normal_force_N * section.inv_area_per_m2;
  const double shear_left =
      p.shear_strength_Pa - std::abs(loads.twist_moment_N_m) * section.radius_over_polar_inertia_per_m3;
  const double bend = section.radius_over_inertia_per_m3, area = section.inv_area_per_m2;
  return tension_left >= 0.0 && norm2(loads.bend_moment_N_m) * (bend * bend) <= tension_left * tension_left &&
         shear_left >= 0.0 && norm2(loads.shear_force_N) * (area * area) <= shear_left * shear_left;
}

namespace bond_detail {

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

}  // namespace bond_detail

/// Rotates v by the rotation vector phi (axis phi/|phi|, angle |phi|; Rodrigues).
inline Vec3 rotate_by(const Vec3& v, const Vec3& phi) { return bond_detail::Rotation(phi)(v); }

namespace bond_detail {

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

}  // namespace bond_detail

/// The smallest rotation that takes unit vector a to unit vector b, applied to v.
inline Vec3 rotate_between(const Vec3& v, const Vec3& a, const Vec3& b) {
  return bond_detail::MinimalRotation(a, b)(v);
}

/// One step of a bond: turns the stored loads with the pair (the mean spin of the two
/// particles, then the remaining change of the normal), adds the increments of the
/// step (dt), sets F_n from the stretch, and returns the forces. `normal` is the bond
/// normal of the previous step, updated here; rest_length_m is L0. effective_mass_kg
/// and effective_inertia (of the pair) scale the optional damping only.
inline BondAction update_bond(const BondParameters& p, const BondSection& section, double rest_length_m,
                       const BondKinematics& k, double dt_s, double effective_mass_kg,
                       double effective_inertia_kg_m2, Vec3& normal, BondLoads& loads) {
  const Vec3 d = k.position_j_m - k.position_i_m;
  const double length = norm(d), inv_length = 1.0 / length;
  const Vec3 n = d * inv_length;

  // 1. Turn the stored loads with the pair: first with the mean spin of the two
  // particles over the step (exact for a rigid rotation of the pair, whatever its axis),
  // then by the smallest rotation that takes the spun old normal onto the new one (the
  // part of the normal's change that relative translation made).
  const bond_detail::Rotation spin((k.angular_velocity_i_rad_per_s + k.angular_velocity_j_rad_per_s) * (0.5 * dt_s));
  const bond_detail::MinimalRotation align(spin(normal), n);
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
