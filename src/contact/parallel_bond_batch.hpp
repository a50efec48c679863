#pragma once
// The undamped bond step of several bonds at once, one per lane of a vector register
// (bond_kernel::BondLanes): the bond pass's fast path (sim/simulation_bonds.cpp). Each
// lane agrees with update_bond to round-off, and gives the same bits in any lane beside
// any other bonds (ParallelBondBatch.* tests).
#include <cstddef>

#include "contact/bond_store.hpp"
#include "contact/parallel_bond.hpp"

namespace regodem {

/// What the lanes read: the particles' arrays (by local index) and the bonds.
struct BondLaneSource {
  const Vec3* position_m = nullptr;
  const Vec3* velocity_m_per_s = nullptr;  // over the step (velocity Verlet's half-step)
  const Vec3* angular_velocity_rad_per_s = nullptr;
  const double* radius_m = nullptr;
  const BondStore* bonds = nullptr;
  const BondParameters* kinds = nullptr;  // indexed by BondStore::kind
};

/// What step_bond_lanes returns for each lane.
struct BondLaneStep {
  Vec3 normal[bond_kernel::kLanes];
  BondLoads loads[bond_kernel::kLanes];
  BondAction action[bond_kernel::kLanes];
  // The lane's spin angle is not small (bond_kernel::kSeriesLimit): nothing above is
  // meant for it, and its bond takes update_bond alone.
  bool alone[bond_kernel::kLanes] = {};
};

/// The step over dt_s of the undamped bonds first_bond .. first_bond + count - 1 (count
/// 1 .. kLanes): for each lane, the normal, loads and action update_bond would give.
/// Nothing is written to the bonds.
void step_bond_lanes(const BondLaneSource& source, std::size_t first_bond, int count, double dt_s,
                     BondLaneStep& out);

}  // namespace regodem
