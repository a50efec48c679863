// The per-bond law (src/contact/parallel_bond.hpp) against hand-worked values: the
// section constants, each increment, the stresses and failure modes, the balance of
// momentum and angular momentum, and frame handling under a rigid rotation.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "contact/parallel_bond.hpp"
#include "core/rng.hpp"

namespace regodem {
namespace {

constexpr double kPi = std::numbers::pi;

BondParameters params() {
  BondParameters p;
  p.normal_stiffness_Pa_per_m = 3e10;
  p.shear_stiffness_Pa_per_m = 1.5e9;
  p.tensile_strength_Pa = 1e6;
  p.shear_strength_Pa = 2e6;
  return p;
}

BondKinematics at_rest(double radius, double length) {
  BondKinematics k;
  k.position_j_m = {length, 0, 0};
  k.radius_i_m = k.radius_j_m = radius;
  return k;
}

// Round-off only (all tolerances below are relative 1e-12 unless stated).
void expect_vec_near(const Vec3& a, const Vec3& b, double tol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

TEST(ParallelBond, SectionConstants) {
  const BondSection s = BondSection::of_radius(2.0);
  EXPECT_DOUBLE_EQ(s.area_m2, 4.0 * kPi);
  EXPECT_DOUBLE_EQ(s.inertia_m4, 4.0 * kPi);        // pi r^4 / 4
  EXPECT_DOUBLE_EQ(s.polar_inertia_m4, 8.0 * kPi);  // pi r^4 / 2
}

TEST(ParallelBond, StretchGivesTensionThatPullsTheEndsTogether) {
  const BondParameters p = params();
  const double r = 1e-3;
  const BondSection s = BondSection::of_radius(r);
  BondLoads loads;
  Vec3 n{1, 0, 0};
  const double stretch = 1e-7;
  const BondAction a = update_bond(p, s, 2 * r, at_rest(r, 2 * r + stretch), 1e-6, 1.0, 1.0, n, loads);
  const double expected = p.normal_stiffness_Pa_per_m * s.area_m2 * stretch;
  // 1e-9: the stretch is the difference of two lengths 2e4 times larger (round-off 2e-12).
  EXPECT_NEAR(loads.normal_force_N, expected, 1e-9 * expected);
  EXPECT_NEAR(a.force_on_i_N.x, expected, 1e-9 * expected);  // i is pulled towards j (+x)
  EXPECT_NEAR(bond_stresses(loads, s).tensile_Pa, p.normal_stiffness_Pa_per_m * stretch, 1e-6);
  // Compression lowers sigma (DESIGN.md: tension positive).
  update_bond(p, s, 2 * r, at_rest(r, 2 * r - stretch), 1e-6, 1.0, 1.0, n, loads);
  EXPECT_LT(bond_stresses(loads, s).tensile_Pa, 0.0);
}

TEST(ParallelBond, ShearTwistAndBendIncrements) {
  const BondParameters p = params();
  const double r = 1e-3, dt = 1e-6;
  const BondSection s = BondSection::of_radius(r);
  {  // j slides along +y at v: F_s on i along +y, k_s A v dt; torque on each end
    BondKinematics k = at_rest(r, 2 * r);
    k.velocity_j_m_per_s = {0, 0.01, 0};
    BondLoads loads;
    Vec3 n{1, 0, 0};
    const BondAction a = update_bond(p, s, 2 * r, k, dt, 1.0, 1.0, n, loads);
    const double fs = p.shear_stiffness_Pa_per_m * s.area_m2 * 0.01 * dt;
    // 1e-9: the bond turns by v dt / L = 5e-6 rad in the step, which tilts the
    // increment by that angle (a relative change of its square, 2.5e-11).
    expect_vec_near(loads.shear_force_N, {0, fs, 0}, 1e-9 * fs);
    // arm r: torque on i = r x F = (r,0,0) x (0,fs,0) = (0,0,r fs); on j: (-r,0,0) x (0,-fs,0), the same
    expect_vec_near(a.torque_on_i_N_m, {0, 0, r * fs}, 1e-9 * r * fs);
    expect_vec_near(a.torque_on_j_N_m, {0, 0, r * fs}, 1e-9 * r * fs);
  }
  {  // the ends spin oppositely about n: pure twist, M_t = k_s J (w_j - w_i).n dt
    BondKinematics k = at_rest(r, 2 * r);
    k.angular_velocity_i_rad_per_s = {-0.5, 0, 0};
    k.angular_velocity_j_rad_per_s = {0.5, 0, 0};
    BondLoads loads;
    Vec3 n{1, 0, 0};
    const BondAction a = update_bond(p, s, 2 * r, k, dt, 1.0, 1.0, n, loads);
    const double mt = p.shear_stiffness_Pa_per_m * s.polar_inertia_m4 * 1.0 * dt;
    EXPECT_NEAR(loads.twist_moment_N_m, mt, 1e-12 * mt);
    expect_vec_near(a.torque_on_i_N_m, {mt, 0, 0}, 1e-12 * mt);
    expect_vec_near(a.torque_on_j_N_m, {-mt, 0, 0}, 1e-12 * mt);
    EXPECT_EQ(norm(loads.shear_force_N), 0.0);
  }
  {  // the ends turn oppositely about z: pure bending (the contact points move together)
    BondKinematics k = at_rest(r, 2 * r);
    k.angular_velocity_i_rad_per_s = {0, 0, -0.5};
    k.angular_velocity_j_rad_per_s = {0, 0, 0.5};
    BondLoads loads;
    Vec3 n{1, 0, 0};
    update_bond(p, s, 2 * r, k, dt, 1.0, 1.0, n, loads);
    const double mb = p.normal_stiffness_Pa_per_m * s.inertia_m4 * 1.0 * dt;
    expect_vec_near(loads.bend_moment_N_m, {0, 0, mb}, 1e-12 * mb);
    EXPECT_NEAR(norm(loads.shear_force_N), 0.0, 1e-30);
  }
}

// The pass's square-root-free check decides as the stresses do: loads drawn so that each
// part of sigma and tau runs from -1 to 1.5 strengths (both criteria near their limits
// and past them, compression, tension), every draw must agree exactly; the two outcomes
// must both occur, or the test has not tested anything.
TEST(ParallelBond, HoldsAgreesWithTheStresses) {
  const BondParameters p = params();
  const BondSection s = BondSection::of_radius(0.75e-3);
  Rng rng(2026);
  auto in_plane = [&](double magnitude) {
    const double a = rng.uniform(0.0, 2.0 * kPi);
    return Vec3{0.0, magnitude * std::cos(a), magnitude * std::sin(a)};
  };
  int held = 0, failed = 0;
  for (int draw = 0; draw < 20000; ++draw) {
    BondLoads loads;
    loads.normal_force_N = rng.uniform(-1.0, 1.5) * p.tensile_strength_Pa * s.area_m2;
    loads.bend_moment_N_m = in_plane(rng.uniform(0.0, 1.5) * p.tensile_strength_Pa * s.inertia_m4 / s.radius_m);
    loads.shear_force_N = in_plane(rng.uniform(0.0, 1.5) * p.shear_strength_Pa * s.area_m2);
    loads.twist_moment_N_m = rng.uniform(-1.5, 1.5) * p.shear_strength_Pa * s.polar_inertia_m4 / s.radius_m;
    const bool holds = bond_failure(bond_stresses(loads, s), p) == BondBreak::none;
    ASSERT_EQ(bond_holds(loads, s, p), holds) << "draw " << draw;
    (holds ? held : failed)++;
  }
  EXPECT_GT(held, 1000);
  EXPECT_GT(failed, 1000);
  // NaN loads: not "holds", so the pass asks bond_failure, which keeps them (as before).
  BondLoads nan_loads;
  nan_loads.normal_force_N = std::nan("");
  EXPECT_FALSE(bond_holds(nan_loads, s, p));
}

TEST(ParallelBond, StressesAndFailureModes) {
  const BondParameters p = params();
  const BondSection s = BondSection::of_radius(1e-3);
  BondLoads loads;
  loads.normal_force_N = 0.5 * p.tensile_strength_Pa * s.area_m2;
  loads.bend_moment_N_m = {0, 0.4 * p.tensile_strength_Pa * s.inertia_m4 / s.radius_m, 0};
  BondStresses st = bond_stresses(loads, s);
  EXPECT_NEAR(st.tensile_Pa, 0.9 * p.tensile_strength_Pa, 1e-9 * p.tensile_strength_Pa);
  EXPECT_EQ(bond_failure(st, p), BondBreak::none);
  loads.bend_moment_N_m = {0, 0.6 * p.tensile_strength_Pa * s.inertia_m4 / s.radius_m, 0};
  EXPECT_EQ(bond_failure(bond_stresses(loads, s), p), BondBreak::tension);
  loads = {};
  loads.shear_force_N = {0, 0.7 * p.shear_strength_Pa * s.area_m2, 0};
  loads.twist_moment_N_m = -0.4 * p.shear_strength_Pa * s.polar_inertia_m4 / s.radius_m;
  st = bond_stresses(loads, s);
  EXPECT_NEAR(st.shear_Pa, 1.1 * p.shear_strength_Pa, 1e-9 * p.shear_strength_Pa);
  EXPECT_EQ(bond_failure(st, p), BondBreak::shear);
  // A compressed bond (sigma < 0) does not fail in tension however hard it is pressed.
  loads = {};
  loads.normal_force_N = -100.0 * p.tensile_strength_Pa * s.area_m2;
  EXPECT_EQ(bond_failure(bond_stresses(loads, s), p), BondBreak::none);
}

TEST(ParallelBond, ForcesAndTorquesConserveMomentumAndAngularMomentum) {
  BondParameters p = params();
  p.damping_ratio = 0.3;
  const BondSection s = BondSection::of_radius(0.7e-3);
  BondKinematics k;
  k.position_i_m = {0.1e-3, -0.2e-3, 0.05e-3};
  k.position_j_m = {1.9e-3, 0.3e-3, -0.4e-3};
  k.radius_i_m = 1.0e-3;
  k.radius_j_m = 0.8e-3;
  k.velocity_i_m_per_s = {0.01, -0.02, 0.005};
  k.velocity_j_m_per_s = {-0.01, 0.03, 0.02};
  k.angular_velocity_i_rad_per_s = {3, -1, 2};
  k.angular_velocity_j_rad_per_s = {-2, 4, 1};
  BondLoads loads;
  loads.shear_force_N = {0, 1e-3, 2e-3};
  loads.bend_moment_N_m = {1e-7, 0, -2e-7};
  loads.twist_moment_N_m = 3e-7;
  Vec3 n = normalized(k.position_j_m - k.position_i_m);
  const BondAction a = update_bond(p, s, 1.85e-3, k, 1e-6, 1e-6, 1e-12, n, loads);
  // Total torque about the origin: x_i x F + x_j x (-F) + T_i + T_j = 0.
  const Vec3 total = cross(k.position_i_m, a.force_on_i_N) - cross(k.position_j_m, a.force_on_i_N) +
                     a.torque_on_i_N_m + a.torque_on_j_N_m;
  EXPECT_LT(norm(total), 1e-12 * (norm(a.torque_on_i_N_m) + norm(a.force_on_i_N) * 1e-3));
  // The in-plane loads stay in the bond plane.
  EXPECT_LT(std::abs(dot(loads.shear_force_N, n)), 1e-15);
  EXPECT_LT(std::abs(dot(loads.bend_moment_N_m, n)), 1e-18);
}

// A loaded bond carried through a rigid rotation of the pair (1.6 rad about an oblique
// axis, in 4,000 steps of theta = |omega| dt = 4e-4 rad): in the pair's own frame
// nothing changes. The turning of the stored loads is exact for rigid motion; the
// increments see the chord velocities of the centres, whose mid-step lever arms leave
// a slip of theta^3/12 of the 2 mm arm per step: 4,000 x 4.7e3 N/m x 1e-14 m ~ 2e-7 N
// against 2.2e-3 N of shear, so 1e-4 relative for the shear force, round-off (1e-9)
// for the moments and the normal force.
TEST(ParallelBond, RigidRotationOfThePairLeavesTheBondUnchanged) {
  const BondParameters p = params();
  const double r = 1e-3, length = 2.0e-3;
  const BondSection s = BondSection::of_radius(r);
  const Vec3 omega = Vec3{0.3, -0.5, 0.8} * 400.0;  // rad/s
  const double dt = 1e-6;
  const int steps = 4000;  // 1.6 rad in all
  const Vec3 x_i0{-0.5 * length, 0, 0}, x_j0{0.5 * length + 2e-8, 0, 0};  // slightly stretched
  BondLoads loads;
  loads.shear_force_N = {0, 2e-3, -1e-3};
  loads.bend_moment_N_m = {0, -3e-7, 1e-7};
  loads.twist_moment_N_m = 5e-8;
  Vec3 n{1, 0, 0};
  const double rest = length;
  BondLoads first;
  for (int step = 1; step <= steps; ++step) {
    const Vec3 turn = omega * (dt * step);
    BondKinematics k;
    k.position_i_m = rotate_by(x_i0, turn);
    k.position_j_m = rotate_by(x_j0, turn);
    // Rigid kinematics over the step: the chord velocity of each centre.
    const Vec3 previous = omega * (dt * (step - 1));
    k.velocity_i_m_per_s = (k.position_i_m - rotate_by(x_i0, previous)) * (1.0 / dt);
    k.velocity_j_m_per_s = (k.position_j_m - rotate_by(x_j0, previous)) * (1.0 / dt);
    k.angular_velocity_i_rad_per_s = k.angular_velocity_j_rad_per_s = omega;
    k.radius_i_m = k.radius_j_m = r;
    update_bond(p, s, rest, k, dt, 1.0, 1.0, n, loads);
    if (step == 1) first = loads;
  }
  // Back into the starting frame: rotate by minus the total turn.
  const Vec3 total_turn = omega * (dt * steps);
  const Vec3 shear_body = rotate_by(loads.shear_force_N, -total_turn);
  const Vec3 bend_body = rotate_by(loads.bend_moment_N_m, -total_turn);
  const Vec3 shear_first = rotate_by(first.shear_force_N, -omega * dt);
  const Vec3 bend_first = rotate_by(first.bend_moment_N_m, -omega * dt);
  EXPECT_GT(norm(total_turn), 1.5);  // a large rotation, not a small one
  expect_vec_near(shear_body, shear_first, 1e-4 * norm(shear_first));
  expect_vec_near(bend_body, bend_first, 1e-9 * norm(bend_first));
  EXPECT_NEAR(loads.twist_moment_N_m, first.twist_moment_N_m, 1e-9 * std::abs(first.twist_moment_N_m));
  EXPECT_NEAR(loads.normal_force_N, first.normal_force_N, 1e-9 * first.normal_force_N);
}

}  // namespace
}  // namespace regodem
