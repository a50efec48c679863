// The batched bond step (src/contact/parallel_bond_batch.hpp) against the one-bond law
// (update_bond), and against itself in other lanes and batch positions. Both are one source (bond_kernel)
// compiled for two lane types; the compiler may fuse a multiply and an add in one and
// not the other, so they agree to round-off, not to the bit: 1e-12 of each vector's
// magnitude (a fused operation moves one rounding, 1e-16 of a term; a wrong formula
// moves the result by its own size). What the pass needs exactly is that a bond's
// result does not depend on its lane or on the bonds beside it: then no grouping of
// the bonds (threads, later ranks) changes a run. That is compared bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>
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

// What the batch gives one bond.
struct BatchResult {
  Vec3 normal;
  BondLoads loads;
  BondAction action;
  bool alone = false;
};

// The bonds as the pass holds them: particle 2k and 2k + 1 are bond k's ends.
std::vector<BatchResult> step_batch(const DrawnBond* bonds, int count, double dt) {
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
  }
  store.resize_state(static_cast<std::size_t>(count));
  for (int l = 0; l < count; ++l) store.set_state(static_cast<std::size_t>(l), bonds[l].normal, bonds[l].loads);
  BondLaneSource source;
  source.position_m = position.data();
  source.velocity_m_per_s = velocity.data();
  source.angular_velocity_rad_per_s = spin.data();
  source.radius_m = radius.data();
  source.kinds = kinds.data();
  auto batch = std::make_unique<BondBatch>();
  step_bond_batch(source, store, 0, count, dt, *batch);
  std::vector<BatchResult> results(static_cast<std::size_t>(count));
  for (int k = 0; k < count; ++k) {
    results[k] = {store.normal_of(k), store.loads_of(k), batch->action(k), batch->alone(k)};
    EXPECT_TRUE(same_bits(batch->loads_before(k).twist_moment_N_m, bonds[k].loads.twist_moment_N_m) &&
                same_bits(batch->loads_before(k).bend_moment_N_m, bonds[k].loads.bend_moment_N_m));
    // A bond flagged alone is left as it was.
    if (results[k].alone) {
      EXPECT_TRUE(same_bits(results[k].normal, bonds[k].normal) &&
                  same_bits(results[k].loads.shear_force_N, bonds[k].loads.shear_force_N));
    }
  }
  return results;
}

// Runs `count` bonds through a batch and each through update_bond; returns how many
// were compared (not flagged alone).
int compare_group(DrawnBond* bonds, int count, double dt, int draw) {
  const std::vector<BatchResult> step = step_batch(bonds, count, dt);
  int compared = 0;
  for (int l = 0; l < count; ++l) {
    DrawnBond alone = bonds[l];
    const BondAction a = update_bond(alone.parameters, alone.section, alone.rest_length_m, alone.kinematics, dt, 1.0,
                                     1.0, alone.normal, alone.loads);
    const Vec3 phi = (alone.kinematics.angular_velocity_i_rad_per_s + alone.kinematics.angular_velocity_j_rad_per_s) *
                     (0.5 * dt);
    EXPECT_EQ(step[l].alone, !(norm2(phi) < bond_kernel::kSeriesLimit)) << "draw " << draw << " lane " << l;
    if (step[l].alone) continue;
    ++compared;
    expect_round_off(step[l].normal, alone.normal, "normal", draw);
    const double force_scale = std::abs(alone.loads.normal_force_N) + norm(alone.loads.shear_force_N);
    EXPECT_NEAR(step[l].loads.normal_force_N, alone.loads.normal_force_N, kRoundOff * force_scale) << "draw " << draw;
    EXPECT_NEAR(step[l].loads.twist_moment_N_m, alone.loads.twist_moment_N_m,
                kRoundOff * std::abs(alone.loads.twist_moment_N_m))
        << "draw " << draw;
    expect_round_off(step[l].loads.shear_force_N, alone.loads.shear_force_N, "shear force", draw);
    expect_round_off(step[l].loads.bend_moment_N_m, alone.loads.bend_moment_N_m, "bending moment", draw);
    expect_round_off(step[l].action.force_on_i_N, a.force_on_i_N, "force on i", draw);
    expect_round_off(step[l].action.torque_on_i_N_m, a.torque_on_i_N_m, "torque on i", draw);
    expect_round_off(step[l].action.torque_on_j_N_m, a.torque_on_j_N_m, "torque on j", draw);
    EXPECT_EQ(step[l].action.loss_W, 0.0);
  }
  return compared;
}

TEST(ParallelBondBatch, EveryLaneAgreesWithTheOneBondLaw) {
  Rng rng(42);
  const double dt = 1e-6;
  int compared = 0, alone = 0;
  for (int draw = 0; draw < 500; ++draw) {
    DrawnBond bonds[BondBatch::kBonds];
    // Mostly small spins; one bond in ten spins past the series (it goes alone).
    for (int k = 0; k < BondBatch::kBonds; ++k) bonds[k] = draw_bond(rng, (draw + k) % 10 == 0 ? 3e4 : 2e3);
    const int count = 1 + (draw * 7) % BondBatch::kBonds;  // full and short batches and groups
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
  // Every lane, in the first and the last vector of a batch, full and short batches.
  std::vector<int> places;
  for (int l = 0; l < kLanes; ++l) places.insert(places.end(), {l, BondBatch::kBonds - kLanes + l});
  for (int draw = 0; draw < 200; ++draw) {
    const DrawnBond bond = draw_bond(rng, 2e3);
    const BatchResult reference = step_batch(&bond, 1, dt)[0];  // alone in a short batch
    ASSERT_FALSE(reference.alone);
    for (int place : places) {
      DrawnBond batch[BondBatch::kBonds];
      for (DrawnBond& other : batch) other = draw_bond(rng, 2e3);
      batch[place] = bond;
      const int count = draw % 2 == 0 ? BondBatch::kBonds : place + 1;
      const BatchResult step = step_batch(batch, count, dt)[static_cast<std::size_t>(place)];
      EXPECT_TRUE(same_bits(step.normal, reference.normal)) << "draw " << draw << " place " << place;
      EXPECT_TRUE(same_bits(step.loads.normal_force_N, reference.loads.normal_force_N) &&
                  same_bits(step.loads.twist_moment_N_m, reference.loads.twist_moment_N_m) &&
                  same_bits(step.loads.shear_force_N, reference.loads.shear_force_N) &&
                  same_bits(step.loads.bend_moment_N_m, reference.loads.bend_moment_N_m))
          << "draw " << draw << " place " << place;
      EXPECT_TRUE(same_bits(step.action.force_on_i_N, reference.action.force_on_i_N) &&
                  same_bits(step.action.torque_on_i_N_m, reference.action.torque_on_i_N_m) &&
                  same_bits(step.action.torque_on_j_N_m, reference.action.torque_on_j_N_m))
          << "draw " << draw << " place " << place;
    }
  }
}

}  // namespace
}  // namespace regodem
