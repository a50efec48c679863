#pragma once
// The undamped bond step of a batch of bonds, kLanes at a time, one bond per lane of a
// vector register (bond_kernel::BondLanes): the bond pass's fast path
// (sim/simulation_bonds.cpp). Each lane agrees with update_bond to round-off, and gives
// the same bits in any lane and batch position beside any other bonds
// (ParallelBondBatch.* tests).
//
// Why a batch: filling a vector lane by lane straight before using it makes the CPU
// wait for each small store to reach the wide load (a store-forwarding stall), which
// cost more than the bond law's arithmetic. So the batch first copies what its bonds need
// of their particles (the pairs' separations, relative velocities, spins and radii) and the
// bonds' constants into rows (one row per scalar, structure of arrays), then
// steps them a vector at a time with whole-vector loads and stores; the bonds' own state
// is already in rows (BondStore::state).
#include <cstddef>

#include "contact/bond_store.hpp"
#include "contact/parallel_bond.hpp"

namespace regodem {

/// What the lanes read: the particles' arrays (by local index) and the bond kinds.
struct BondLaneSource {
  const Vec3* position_m = nullptr;
  const Vec3* velocity_m_per_s = nullptr;  // over the step (velocity Verlet's half-step)
  const Vec3* angular_velocity_rad_per_s = nullptr;
  const double* radius_m = nullptr;
  const BondParameters* kinds = nullptr;  // indexed by BondStore::kind
};

/// Scratch and results of one batch (step_bond_batch); a thread keeps one and reuses it.
class BondBatch {
 public:
  static constexpr int kBonds = 8 * bond_kernel::kLanes;  // a multiple of the lanes

  // Rows of the inputs and results, kBonds values each.
  enum Input : int {
    separation, centre_velocity = separation + 3, spin_i = centre_velocity + 3, spin_j = spin_i + 3,
    radius_i = spin_j + 3, radius_j, rest_length,
    normal_stiffness, shear_stiffness, twist_stiffness, bend_stiffness, input_rows
  };
  enum Output : int {
    force_on_i, torque_on_i = force_on_i + 3, torque_on_j = torque_on_i + 3, spin_angle2 = torque_on_j + 3,
    output_rows
  };

  /// Bond k of the batch (0 .. count - 1) after step_bond_batch: whether its spin angle
  /// is not small (bond_kernel::kSeriesLimit): then its state in the store is left as it
  /// was, nothing here is meant for it, and it takes update_bond alone.
  bool alone(int k) const { return !(out_[spin_angle2][k] < bond_kernel::kSeriesLimit); }
  /// Its action (no loss), and its loads before the step.
  BondAction action(int k) const { return {out3(force_on_i, k), out3(torque_on_i, k), out3(torque_on_j, k), 0.0}; }
  BondLoads loads_before(int k) const {
    const auto row = [&](int r) { return old_[r][k]; };
    return {row(BondStore::normal_force), {row(BondStore::shear_x), row(BondStore::shear_y), row(BondStore::shear_z)},
            row(BondStore::twist_moment), {row(BondStore::bend_x), row(BondStore::bend_y), row(BondStore::bend_z)}};
  }

 private:
  friend void step_bond_batch(const BondLaneSource&, BondStore&, std::size_t, int, double, BondBatch&);
  Vec3 out3(int row, int k) const { return {out_[row][k], out_[row + 1][k], out_[row + 2][k]}; }

  alignas(64) double in_[input_rows][kBonds];
  alignas(64) double out_[output_rows][kBonds];
  alignas(64) double old_[BondStore::state_rows][kBonds];  // the bonds' state before the step
};

/// The step over dt_s of the undamped bonds first_bond .. first_bond + count - 1 (count
/// 1 .. BondBatch::kBonds): each bond's new normal and loads, as update_bond would give
/// them, into its state in `bonds` (not for a bond flagged alone), and its action into
/// `batch`.
void step_bond_batch(const BondLaneSource& source, BondStore& bonds, std::size_t first_bond, int count, double dt_s,
                     BondBatch& batch);

}  // namespace regodem
