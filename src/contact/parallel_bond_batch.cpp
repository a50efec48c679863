#include "contact/parallel_bond_batch.hpp"

namespace regodem {
namespace {

using bond_kernel::BondLanes;
using bond_kernel::kLanes;
using bond_kernel::V3;

Vec3 lane(const V3<BondLanes>& v, int l) { return {v.x[l], v.y[l], v.z[l]}; }

}  // namespace

void step_bond_lanes(const BondLaneSource& source, std::size_t first_bond, int count, double dt_s,
                     BondLaneStep& out) {
  const BondStore& bonds = *source.bonds;
  // A short group repeats its first bond in the spare lanes (their results are dropped).
  std::size_t bond[kLanes];
  std::uint32_t end_i[kLanes], end_j[kLanes];
  for (int l = 0; l < kLanes; ++l) {
    bond[l] = first_bond + static_cast<std::size_t>(l < count ? l : 0);
    end_i[l] = bonds.local_i[bond[l]];
    end_j[l] = bonds.local_j[bond[l]];
  }
  const auto pack = [&](auto value_of_lane) {
    BondLanes r;
    for (int l = 0; l < kLanes; ++l) r[l] = value_of_lane(l);
    return r;
  };
  const auto pack3 = [&](const Vec3* array, const std::uint32_t* index) {
    return V3<BondLanes>{pack([&](int l) { return array[index[l]].x; }), pack([&](int l) { return array[index[l]].y; }),
                         pack([&](int l) { return array[index[l]].z; })};
  };
  const auto pack_bond3 = [&](auto vector_of_bond) {
    return V3<BondLanes>{pack([&](int l) { return vector_of_bond(bond[l]).x; }),
                         pack([&](int l) { return vector_of_bond(bond[l]).y; }),
                         pack([&](int l) { return vector_of_bond(bond[l]).z; })};
  };

  // The inputs bond_step_input gives one bond, lane by lane.
  bond_kernel::BondStepInput<BondLanes> in;
  in.position_i = pack3(source.position_m, end_i);
  in.position_j = pack3(source.position_m, end_j);
  in.velocity_i = pack3(source.velocity_m_per_s, end_i);
  in.velocity_j = pack3(source.velocity_m_per_s, end_j);
  in.spin_i = pack3(source.angular_velocity_rad_per_s, end_i);
  in.spin_j = pack3(source.angular_velocity_rad_per_s, end_j);
  in.radius_i = pack([&](int l) { return source.radius_m[end_i[l]]; });
  in.radius_j = pack([&](int l) { return source.radius_m[end_j[l]]; });
  in.rest_length = pack([&](int l) { return bonds.rest_length_m[bond[l]]; });
  in.normal = pack_bond3([&](std::size_t b) -> const Vec3& { return bonds.normal[b]; });
  in.normal_force = pack([&](int l) { return bonds.loads[bond[l]].normal_force_N; });
  in.twist_moment = pack([&](int l) { return bonds.loads[bond[l]].twist_moment_N_m; });
  in.shear_force = pack_bond3([&](std::size_t b) -> const Vec3& { return bonds.loads[b].shear_force_N; });
  in.bend_moment = pack_bond3([&](std::size_t b) -> const Vec3& { return bonds.loads[b].bend_moment_N_m; });
  const auto kind = [&](int l) -> const BondParameters& { return source.kinds[bonds.kind[bond[l]]]; };
  const auto section = [&](int l) -> const BondSection& { return bonds.section[bond[l]]; };
  in.normal_stiffness = pack([&](int l) { return kind(l).normal_stiffness_Pa_per_m * section(l).area_m2; });
  in.shear_stiffness = pack([&](int l) { return kind(l).shear_stiffness_Pa_per_m * section(l).area_m2; });
  in.twist_stiffness = pack([&](int l) { return kind(l).shear_stiffness_Pa_per_m * section(l).polar_inertia_m4; });
  in.bend_stiffness = pack([&](int l) { return kind(l).normal_stiffness_Pa_per_m * section(l).inertia_m4; });

  // The pair's mean spin over the step, in its series form (bond_spin_rotation); a lane
  // past the series' range is flagged.
  const V3<BondLanes> phi = (in.spin_i + in.spin_j) * (BondLanes{} + 0.5 * dt_s);
  const BondLanes angle2 = bond_kernel::dot(phi, phi);
  const bond_kernel::BondStepOutput<BondLanes> s = bond_kernel::bond_step(in, bond_kernel::series_rotation(phi), dt_s);
  const bond_kernel::BondForces<BondLanes> f = bond_kernel::bond_forces(
      s.normal, s.normal_force, s.shear_force, s.twist_moment, s.bend_moment, s.arm_i, s.arm_j);

  for (int l = 0; l < count; ++l) {
    out.alone[l] = !(angle2[l] < bond_kernel::kSeriesLimit);
    out.normal[l] = lane(s.normal, l);
    out.loads[l].normal_force_N = s.normal_force[l];
    out.loads[l].shear_force_N = lane(s.shear_force, l);
    out.loads[l].twist_moment_N_m = s.twist_moment[l];
    out.loads[l].bend_moment_N_m = lane(s.bend_moment, l);
    out.action[l].force_on_i_N = lane(f.force_on_i, l);
    out.action[l].torque_on_i_N_m = lane(f.torque_on_i, l);
    out.action[l].torque_on_j_N_m = lane(f.torque_on_j, l);
    out.action[l].loss_W = 0.0;
  }
}

}  // namespace regodem
