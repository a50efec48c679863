// The batched bond step (src/contact/parallel_bond_batch.hpp) against the one-bond law
// (update_bond), and against itself in other lanes. Both are one source (bond_kernel)
// compiled for two lane types; the compiler may fuse a multiply and an add in one and
// not the other, so they agree to round-off, not to the bit: 1e-12 of each vector's
// magnitude (a fused operation moves one rounding, 1e-16 of a term; a wrong formula
// moves the result by its own size). What the pass needs exactly is that a bond's
// result does not depend on its lane or on the bonds beside it: then no grouping of
// the bonds (threads, later ranks) changes a run. That is compared bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <vector>

#include "contact/parallel_bond_batch.hpp"
#include "core/rng.hpp"

namespace regodem {
namespace {

using bond_kernel::kLanes;

struct DrawnBond {
  BondParameters parameters;
  BondSection section;
  double rest_length_m = 0.0;
  BondKinematics kinematics;
  Vec3 normal;
  BondLoads loads;
};

Vec3 random_vector(Rng& rng, double magnitude) {
  return {rng.uniform(-magnitude, magnitude), rng.uniform(-magnitude, magnitude), rng.uniform(-magnitude, magnitude)};
}

// A bond of the drilling models' sizes, strained and moving as grains near a drill do;
// spin_rad_per_s sets how far the pair turns in the step (dt 1e-6 s: 1e4 rad/s is an
// angle of 0.01 rad, the series' limit).
DrawnBond draw_bond(Rng& rng, double spin_rad_per_s) {
  DrawnBond d;
  d.parameters = icy_regolith_bond_parameters();
  d.parameters.normal_stiffness_Pa_per_m *= rng.uniform(0.5, 2.0);
  const double ri = rng.uniform(0.5e-3, 3e-3), rj = rng.uniform(0.5e-3, 3e-3);
  d.section = BondSection::of_radius(std::min(ri, rj));
  const Vec3 axis = random_vector(rng, 1.0);
  const Vec3 n = axis * (1.0 / norm(axis));
  d.rest_length_m = (ri + rj) * rng.uniform(0.98, 1.02);
  BondKinematics& k = d.kinematics;
  k.radius_i_m = ri;
  k.radius_j_m = rj;
  k.position_i_m = random_vector(rng, 0.05);
  k.position_j_m = k.position_i_m + n * (d.rest_length_m * rng.uniform(0.999, 1.001)) + random_vector(rng, 1e-6);
  k.velocity_i_m_per_s = random_vector(rng, 5.0);
  k.velocity_j_m_per_s = random_vector(rng, 5.0);
  k.angular_velocity_i_rad_per_s = random_vector(rng, spin_rad_per_s);
  k.angular_velocity_j_rad_per_s = random_vector(rng, spin_rad_per_s);
  // The last step's normal: near the new one, as a step leaves it.
  const Vec3 old = n + random_vector(rng, 1e-3);
  d.normal = old * (1.0 / norm(old));
  const double area = d.section.area_m2;
  d.loads.normal_force_N = rng.uniform(-3e7, 3e7) * area;
  d.loads.shear_force_N = random_vector(rng, 3e7 * area);
  d.loads.twist_moment_N_m = rng.uniform(-1.0, 1.0) * 3e7 * d.section.polar_inertia_m4 / d.section.radius_m;
  d.loads.bend_moment_N_m = random_vector(rng, 3e7 * d.section.inertia_m4 / d.section.radius_m);
  return d;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool same_bits(const Vec3& a, const Vec3& b) { return same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z); }

constexpr double kRoundOff = 1e-12;  // of each vector's magnitude (the header comment)
void expect_round_off(const Vec3& a, const Vec3& b, const char* what, int draw) {
  const double tol = kRoundOff * norm(b);
  EXPECT_NEAR(a.x, b.x, tol) << what << " of draw " << draw;
  EXPECT_NEAR(a.y, b.y, tol) << what << " of draw " << draw;
  EXPECT_NEAR(a.z, b.z, tol) << what << " of draw " << draw;
}

// The bonds as the pass holds them: particle 2l and 2l + 1 are bond l's ends.
BondLaneStep step_lanes(const DrawnBond* bonds, int count, double dt) {
  std::vector<Vec3> position, velocity, spin;
  std::vector<double> radius;
  std::vector<BondParameters> kinds;
  BondStore store;
  for (int l = 0; l < count; ++l) {
    const BondKinematics& k = bonds[l].kinematics;
    position.insert(position.end(), {k.position_i_m, k.position_j_m});
    velocity.insert(velocity.end(), {k.velocity_i_m_per_s, k.velocity_j_m_per_s});
    spin.insert(spin.end(), {k.angular_velocity_i_rad_per_s, k.angular_velocity_j_rad_per_s});
    radius.insert(radius.end(), {k.radius_i_m, k.radius_j_m});
    kinds.push_back(bonds[l].parameters);
    store.local_i.push_back(static_cast<std::uint32_t>(2 * l));
    store.local_j.push_back(static_cast<std::uint32_t>(2 * l + 1));
    store.kind.push_back(static_cast<std::uint16_t>(l));
    store.rest_length_m.push_back(bonds[l].rest_length_m);
    store.section.push_back(bonds[l].section);
    store.normal.push_back(bonds[l].normal);
    store.loads.push_back(bonds[l].loads);
  }
  BondLaneSource source;
  source.position_m = position.data();
  source.velocity_m_per_s = velocity.data();
  source.angular_velocity_rad_per_s = spin.data();
  source.radius_m = radius.data();
  source.bonds = &store;
  source.kinds = kinds.data();
  BondLaneStep step;
  step_bond_lanes(source, 0, count, dt, step);
  return step;
}

// Runs `count` bonds through the lanes and each through update_bond; returns how many
// lanes were compared (not flagged alone).
int compare_group(DrawnBond* bonds, int count, double dt, int draw) {
  const BondLaneStep step = step_lanes(bonds, count, dt);
  int compared = 0;
  for (int l = 0; l < count; ++l) {
    DrawnBond alone = bonds[l];
    const BondAction a = update_bond(alone.parameters, alone.section, alone.rest_length_m, alone.kinematics, dt, 1.0,
                                     1.0, alone.normal, alone.loads);
    const Vec3 phi = (alone.kinematics.angular_velocity_i_rad_per_s + alone.kinematics.angular_velocity_j_rad_per_s) *
                     (0.5 * dt);
    EXPECT_EQ(step.alone[l], !(norm2(phi) < bond_kernel::kSeriesLimit)) << "draw " << draw << " lane " << l;
    if (step.alone[l]) continue;
    ++compared;
    expect_round_off(step.normal[l], alone.normal, "normal", draw);
    const double force_scale = std::abs(alone.loads.normal_force_N) + norm(alone.loads.shear_force_N);
    EXPECT_NEAR(step.loads[l].normal_force_N, alone.loads.normal_force_N, kRoundOff * force_scale) << "draw " << draw;
    EXPECT_NEAR(step.loads[l].twist_moment_N_m, alone.loads.twist_moment_N_m,
                kRoundOff * std::abs(alone.loads.twist_moment_N_m))
        << "draw " << draw;
    expect_round_off(step.loads[l].shear_force_N, alone.loads.shear_force_N, "shear force", draw);
    expect_round_off(step.loads[l].bend_moment_N_m, alone.loads.bend_moment_N_m, "bending moment", draw);
    expect_round_off(step.action[l].force_on_i_N, a.force_on_i_N, "force on i", draw);
    expect_round_off(step.action[l].torque_on_i_N_m, a.torque_on_i_N_m, "torque on i", draw);
    expect_round_off(step.action[l].torque_on_j_N_m, a.torque_on_j_N_m, "torque on j", draw);
    EXPECT_EQ(step.action[l].loss_W, 0.0);
  }
  return compared;
}

TEST(ParallelBondBatch, EveryLaneAgreesWithTheOneBondLaw) {
  Rng rng(42);
  const double dt = 1e-6;
  int compared = 0, alone = 0;
  for (int draw = 0; draw < 4000; ++draw) {
    DrawnBond bonds[kLanes];
    // Mostly small spins; one group in ten spins past the series (those lanes go alone).
    const double spin = draw % 10 == 0 ? 3e4 : 2e3;
    for (DrawnBond& b : bonds) b = draw_bond(rng, spin);
    const int count = 1 + draw % kLanes;  // full and short groups
    const int c = compare_group(bonds, count, dt, draw);
    compared += c;
    alone += count - c;
  }
  // Both paths occurred, the lanes' far more often.
  EXPECT_GT(compared, 4 * alone);
  EXPECT_GT(alone, 100);
}

TEST(ParallelBondBatch, AHalfTurnAndARestingPairAgreeWithTheOneBondLaw) {
  Rng rng(7);
  DrawnBond bonds[kLanes];
  for (DrawnBond& b : bonds) b = draw_bond(rng, 0.0);
  // Lane 0: the stored normal points the other way (the smallest rotation's half turn).
  const Vec3 d = bonds[0].kinematics.position_j_m - bonds[0].kinematics.position_i_m;
  bonds[0].normal = -(d * (1.0 / norm(d)));
  // Lane 1: at rest and unloaded; lane 2: a re-evaluation (dt = 0 is the pass's refresh).
  bonds[1].kinematics.velocity_i_m_per_s = bonds[1].kinematics.velocity_j_m_per_s = {};
  bonds[1].loads = {};
  EXPECT_EQ(compare_group(bonds, kLanes, 1e-6, 0), kLanes);
  EXPECT_EQ(compare_group(bonds, kLanes, 0.0, 1), kLanes);
}

TEST(ParallelBondBatch, ABondsResultDoesNotDependOnItsLaneOrTheBondsBesideIt) {
  Rng rng(99);
  const double dt = 1e-6;
  for (int draw = 0; draw < 500; ++draw) {
    const DrawnBond bond = draw_bond(rng, 2e3);
    DrawnBond first[kLanes];
    first[0] = bond;
    const BondLaneStep reference = step_lanes(first, 1, dt);  // alone in a short group
    ASSERT_FALSE(reference.alone[0]);
    for (int lane = 0; lane < kLanes; ++lane) {
      DrawnBond group[kLanes];
      for (DrawnBond& other : group) other = draw_bond(rng, 2e3);
      group[lane] = bond;
      const BondLaneStep step = step_lanes(group, kLanes, dt);
      EXPECT_TRUE(same_bits(step.normal[lane], reference.normal[0])) << "draw " << draw << " lane " << lane;
      EXPECT_TRUE(same_bits(step.loads[lane].normal_force_N, reference.loads[0].normal_force_N) &&
                  same_bits(step.loads[lane].twist_moment_N_m, reference.loads[0].twist_moment_N_m) &&
                  same_bits(step.loads[lane].shear_force_N, reference.loads[0].shear_force_N) &&
                  same_bits(step.loads[lane].bend_moment_N_m, reference.loads[0].bend_moment_N_m))
          << "draw " << draw << " lane " << lane;
      EXPECT_TRUE(same_bits(step.action[lane].force_on_i_N, reference.action[0].force_on_i_N) &&
                  same_bits(step.action[lane].torque_on_i_N_m, reference.action[0].torque_on_i_N_m) &&
                  same_bits(step.action[lane].torque_on_j_N_m, reference.action[0].torque_on_j_N_m))
          << "draw " << draw << " lane " << lane;
    }
  }
}

}  // namespace
}  // namespace regodem
