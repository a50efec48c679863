#include "contact/parallel_bond_batch.hpp"

#include <cstring>

namespace regodem {
namespace {

using bond_kernel::BondLanes;
using bond_kernel::kLanes;
using bond_kernel::V3;

BondLanes load(const double* row) {
  BondLanes v;
  std::memcpy(&v, row, sizeof v);
  return v;
}
V3<BondLanes> load3(const double* row, std::size_t stride) {
  return {load(row), load(row + stride), load(row + 2 * stride)};
}
void store(double* row, BondLanes v) { std::memcpy(row, &v, sizeof v); }
void store3(double* row, std::size_t stride, const V3<BondLanes>& v) {
  store(row, v.x);
  store(row + stride, v.y);
  store(row + 2 * stride, v.z);
}

}  // namespace

void step_bond_batch(const BondLaneSource& source, BondStore& bonds, std::size_t first_bond, int count, double dt_s,
                     BondBatch& batch) {
  using B = BondBatch;
  using S = BondStore;
  constexpr std::size_t stride = B::kBonds;
  auto& in = batch.in_;
  auto& out = batch.out_;
  auto& old = batch.old_;

  // 1. What the bonds need of their particles (x_j - x_i, v_j - v_i, the spins and radii)
  // and the bonds' constants, copied into the rows bond by bond.
  const auto put3 = [&](int row, int k, const Vec3& v) {
    in[row][k] = v.x;
    in[row + 1][k] = v.y;
    in[row + 2][k] = v.z;
  };
  // The particles of the bonds a few ahead are asked for early: a bond's ends lie
  // anywhere in the particle arrays, and the copy would otherwise wait for each.
  constexpr int kAhead = 8;
  const std::size_t bond_count = bonds.size();
  const auto prefetch_ends = [&](std::size_t b) {
    for (std::uint32_t p : {bonds.local_i[b], bonds.local_j[b]}) {
      __builtin_prefetch(&source.position_m[p]);
      __builtin_prefetch(&source.velocity_m_per_s[p]);
      __builtin_prefetch(&source.angular_velocity_rad_per_s[p]);
    }
  };
  for (int k = 0; k < kAhead && first_bond + k < bond_count; ++k) prefetch_ends(first_bond + k);
  for (int k = 0; k < count; ++k) {
    const std::size_t b = first_bond + static_cast<std::size_t>(k);
    if (b + kAhead < bond_count) prefetch_ends(b + kAhead);
    const std::uint32_t i = bonds.local_i[b], j = bonds.local_j[b];
    put3(B::separation, k, source.position_m[j] - source.position_m[i]);
    put3(B::centre_velocity, k, source.velocity_m_per_s[j] - source.velocity_m_per_s[i]);
    put3(B::spin_i, k, source.angular_velocity_rad_per_s[i]);
    put3(B::spin_j, k, source.angular_velocity_rad_per_s[j]);
    in[B::radius_i][k] = source.radius_m[i];
    in[B::radius_j][k] = source.radius_m[j];
    in[B::rest_length][k] = bonds.rest_length_m[b];
    const BondParameters& kind = source.kinds[bonds.kind[b]];
    const BondSection& section = bonds.section[b];
    in[B::normal_stiffness][k] = kind.normal_stiffness_Pa_per_m * section.area_m2;
    in[B::shear_stiffness][k] = kind.shear_stiffness_Pa_per_m * section.area_m2;
    in[B::twist_stiffness][k] = kind.shear_stiffness_Pa_per_m * section.polar_inertia_m4;
    in[B::bend_stiffness][k] = kind.normal_stiffness_Pa_per_m * section.inertia_m4;
  }
  // A short last vector repeats the batch's first bond's inputs in its spare lanes,
  // with the state of the store's padding; they are written back unchanged.
  const int padded = (count + kLanes - 1) / kLanes * kLanes;
  for (int row = 0; row < B::input_rows; ++row)
    for (int k = count; k < padded; ++k) in[row][k] = in[row][0];
  BondLanes lane_index;
  for (int l = 0; l < kLanes; ++l) lane_index[l] = l;

  // 2. The step, a vector of bonds at a time.
  for (int first = 0; first < padded; first += kLanes) {
    const auto row = [&](int r) { return &in[r][first]; };
    double* state[S::state_rows];
    for (int r = 0; r < S::state_rows; ++r) state[r] = bonds.state[r].data() + first_bond + first;
    BondLanes before[S::state_rows];
    for (int r = 0; r < S::state_rows; ++r) {
      before[r] = load(state[r]);
      store(&old[r][first], before[r]);
    }
    bond_kernel::BondStepInput<BondLanes> v;
    v.separation = load3(row(B::separation), stride);
    v.centre_velocity = load3(row(B::centre_velocity), stride);
    v.spin_i = load3(row(B::spin_i), stride);
    v.spin_j = load3(row(B::spin_j), stride);
    v.radius_i = load(row(B::radius_i));
    v.radius_j = load(row(B::radius_j));
    v.rest_length = load(row(B::rest_length));
    v.normal = {before[S::normal_x], before[S::normal_y], before[S::normal_z]};
    v.normal_force = before[S::normal_force];
    v.twist_moment = before[S::twist_moment];
    v.shear_force = {before[S::shear_x], before[S::shear_y], before[S::shear_z]};
    v.bend_moment = {before[S::bend_x], before[S::bend_y], before[S::bend_z]};
    v.normal_stiffness = load(row(B::normal_stiffness));
    v.shear_stiffness = load(row(B::shear_stiffness));
    v.twist_stiffness = load(row(B::twist_stiffness));
    v.bend_stiffness = load(row(B::bend_stiffness));

    // The pair's mean spin over the step, in its series form (bond_spin_rotation); a
    // lane past the series' range is flagged by its angle^2.
    const V3<BondLanes> phi = (v.spin_i + v.spin_j) * (BondLanes{} + 0.5 * dt_s);
    const BondLanes angle2 = bond_kernel::dot(phi, phi);
    const bond_kernel::BondStepOutput<BondLanes> s =
        bond_kernel::bond_step(v, bond_kernel::series_rotation(phi), dt_s);
    const bond_kernel::BondForces<BondLanes> f = bond_kernel::bond_forces(
        s.normal, s.normal_force, s.shear_force, s.twist_moment, s.bend_moment, s.arm_i, s.arm_j);

    // The new state where the lane is a bond of the batch and in the series' range.
    const bond_kernel::LaneMask update = (angle2 < bond_kernel::kSeriesLimit) & (lane_index + first < count);
    const BondLanes after[S::state_rows] = {s.normal.x,      s.normal.y,      s.normal.z,      s.normal_force,
                                            s.twist_moment,  s.shear_force.x, s.shear_force.y, s.shear_force.z,
                                            s.bend_moment.x, s.bend_moment.y, s.bend_moment.z};
    for (int r = 0; r < S::state_rows; ++r) store(state[r], bond_kernel::lane_select(update, after[r], before[r]));

    const auto result = [&](int r) { return &out[r][first]; };
    store(result(B::spin_angle2), angle2);
    store3(result(B::force_on_i), stride, f.force_on_i);
    store3(result(B::torque_on_i), stride, f.torque_on_i);
    store3(result(B::torque_on_j), stride, f.torque_on_j);
  }
}

}  // namespace regodem
