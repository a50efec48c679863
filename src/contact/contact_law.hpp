#pragma once
// A contact law composed of small models, one per slot (normal, damping, tangential,
// rolling), resolved at compile time so the pair loop inlines it. The loop is a
// template over the law; parameters come per material pair from ContactParameterTable.
#include <algorithm>

#include "contact/contact_parameters.hpp"
#include "contact/contact_state.hpp"
#include "contact/hertz_normal.hpp"
#include "contact/mindlin_tangential.hpp"
#include "contact/restitution_damping.hpp"
#include "contact/rolling_constant_torque.hpp"
#include "contact/rolling_own_spin.hpp"

namespace regodem {

template <class Normal, class Damping, class Tangential, class RelativeRolling, class OwnSpinRolling>
struct ContactLaw {
  /// Forces of one contact in overlap; updates the tangential history. Audit: also the
  /// losses, the springs' energy and the spring source (a few more flops per contact,
  /// only for runs that keep the energy books).
  template <bool Audit = false>
  [[gnu::always_inline]] static ContactForces evaluate(const ContactPairParameters& p, const ContactGeometry& c,
                                Vec3& tangential_history_m) {
    const auto normal = Normal::evaluate(p.effective_youngs_modulus_Pa, c.effective_radius_m, c.overlap_m);
    const double approach_speed = dot(c.relative_velocity_m_per_s, c.normal);  // > 0 while closing
    const double normal_damping =
        Damping::coefficient(p.damping_factor, normal.normal_stiffness_N_per_m, c.effective_mass_kg);
    // Repulsive total normal force; not clamped at zero by default (EDEM), so the
    // rebound matches the restitution coefficient exactly.
    double normal_force = normal.elastic_force_N + normal_damping * approach_speed;
    if (p.clamp_attractive_normal_force) normal_force = std::max(normal_force, 0.0);

    const Vec3 tangential_velocity = c.relative_velocity_m_per_s - approach_speed * c.normal;
    const double tangential_stiffness =
        Tangential::stiffness(p.effective_shear_modulus_Pa, normal.contact_radius_m);
    const double tangential_damping =
        Damping::coefficient(p.damping_factor, tangential_stiffness, c.effective_mass_kg);
    bool sliding = false;
    const double spring_before_m2 = Audit ? norm2(tangential_history_m) : 0.0;  // its turn into the plane keeps it
    const Vec3 tangential = Tangential::evaluate(
        tangential_history_m, c.normal, tangential_velocity, tangential_stiffness, tangential_damping,
        p.sliding_friction * std::max(normal_force, 0.0), c.slip_time_s, sliding);

    ContactForces out;
    out.elastic_normal_force_N = normal.elastic_force_N;
    out.contact_radius_m = normal.contact_radius_m;
    out.approach_speed_m_per_s = approach_speed;
    out.sliding_power_W = sliding ? std::abs(dot(tangential, tangential_velocity)) : 0.0;
    // Losses (docs/physics.md, "Energy audit"). The normal damper's c v_n^2. Tangentially,
    // the work the force takes from the relative motion, -F_t . v_t: while sliding all of it
    // is friction's; while stuck, what the spring does not keep (damping, and the implicit
    // spring update's own k v^2 dt / 2). What the spring's energy k |xi|^2 / 2 does besides
    // is the model's own source, booked apart: its stiffness follows the contact radius
    // (Mindlin k_t = 8 G* a; the overlap a step ago is delta less the approach over it), and
    // the reset while sliding, xi = -(F_t + gamma_t v_t)/k_t, can leave it holding energy no
    // force put in (where gamma_t |v_t| > mu F_n it points against the slip).
    if constexpr (Audit) {
      const double spring_after_m2 = norm2(tangential_history_m);
      const double earlier_stiffness = Tangential::stiffness(
          p.effective_shear_modulus_Pa,
          Normal::contact_radius_m(c.effective_radius_m, std::max(c.overlap_m - approach_speed * c.slip_time_s, 0.0)));
      const double tangential_work_W = -dot(tangential, tangential_velocity);
      const double spring_change_W = 0.5 * tangential_stiffness * (spring_after_m2 - spring_before_m2) / c.time_step_s;
      const double tangential_loss_W = std::max(sliding ? tangential_work_W : tangential_work_W - spring_change_W, 0.0);
      out.spring_source_W = 0.5 * (tangential_stiffness - earlier_stiffness) * spring_before_m2 / c.time_step_s +
                            spring_change_W + tangential_loss_W - tangential_work_W;
      out.dissipated_power_W = (normal_force - normal.elastic_force_N) * approach_speed + tangential_loss_W;
      out.elastic_energy_J =
          Normal::stored_energy_J(normal.elastic_force_N, c.overlap_m) + 0.5 * tangential_stiffness * spring_after_m2;
    }
    out.tangential_force_on_i_N = tangential;
    out.force_on_i_N = tangential - normal_force * c.normal;
    // Rolling: chosen per material pair (EDEM's own-spin model, or the relative spin).
    if (p.rolling_model == RollingModel::own_spin) {
      out.own_spin_resistance_i_N_m =
          OwnSpinRolling::resistance_N_m(p.rolling_friction, normal.elastic_force_N, c.contact_arm_i_m);
      out.own_spin_resistance_j_N_m =
          OwnSpinRolling::resistance_N_m(p.rolling_friction, normal.elastic_force_N, c.contact_arm_j_m);
    } else {
      out.rolling_torque_on_i_N_m = RelativeRolling::evaluate(
          c.angular_velocity_i_rad_per_s - c.angular_velocity_j_rad_per_s, c.normal, p.rolling_friction,
          normal.elastic_force_N, c.effective_radius_m, c.inv_inertia_i + c.inv_inertia_j, c.time_step_s);
    }
    return out;
  }
};

/// The paper's law: Hertz-Mindlin no-slip with restitution damping and constant-torque
/// rolling (on the relative spin, or EDEM's on each body's own).
using HertzMindlinLaw =
    ContactLaw<HertzNormal, RestitutionDamping, MindlinTangential, RollingConstantTorque, RollingOwnSpin>;

}  // namespace regodem
