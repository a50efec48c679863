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

#include "contact/parallel_bond_kernel.hpp"
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
// The three checks below run for every bond every step and are small: inline here, so
// that the pass (another translation unit) does not call them.
/// sigma and tau of the loads (the formulas above).
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


/// Rotates v by the rotation vector phi (axis phi/|phi|, angle |phi|; Rodrigues).
Vec3 rotate_by(const Vec3& v, const Vec3& phi);
/// That rotation as the bond step takes it: v' = v c + (phi x v) s1 + phi (phi.v) c1 with
/// c = cos a, s1 = sin(a)/a, c1 = (1 - cos a)/a^2, a = |phi|. The bond pass turns three
/// vectors by one spin per bond per step, where a is tiny: below a^2 = 1e-4 the series
/// (error a^8/9! < 1e-21) replaces sin, cos and the square root.
bond_kernel::SeriesRotation<double> bond_spin_rotation(const bond_kernel::V3<double>& phi);
/// The smallest rotation that takes unit vector a to unit vector b, applied to v.
Vec3 rotate_between(const Vec3& v, const Vec3& a, const Vec3& b);

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

/// update_bond's inputs as bond_kernel::bond_step takes them (the stiffnesses k_n A,
/// k_s A, k_s J, k_n I of the kind and section).
bond_kernel::BondStepInput<double> bond_step_input(const BondParameters& p, const BondSection& section,
                                                   double rest_length_m, const BondKinematics& k,
                                                   const Vec3& normal, const BondLoads& loads);

/// One step of a bond: turns the stored loads with the pair (the mean spin of the two
/// particles, then the remaining change of the normal), adds the increments of the
/// step (dt), sets F_n from the stretch, and returns the forces. `normal` is the bond
/// normal of the previous step, updated here; rest_length_m is L0. effective_mass_kg
/// and effective_inertia (of the pair) scale the optional damping only.
BondAction update_bond(const BondParameters& p, const BondSection& section, double rest_length_m,
                       const BondKinematics& k, double dt_s, double effective_mass_kg,
                       double effective_inertia_kg_m2, Vec3& normal, BondLoads& loads);

}  // namespace regodem
