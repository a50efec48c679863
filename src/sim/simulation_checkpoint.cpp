// Checkpoints of a Simulation (docs/checkpoint-format.md): everything a step reads, in
// sections. The neighbour lists are saved as they are, not rebuilt: a rebuild re-sorts
// the particles and changes the order in which forces are summed, so a run that is
// checkpointed, or resumed, would no longer be the run that was not.
#include <fmt/format.h>

#include <limits>
#include <utility>

#include "io/checkpoint_file.hpp"
#include "sim/simulation.hpp"

namespace regodem {
namespace {

// Section tags and the versions of their layouts.
constexpr const char* kParticles = "PART";
constexpr const char* kMaterials = "MATN";
constexpr const char* kClock = "SIMU";
constexpr const char* kNeighbors = "NBRS";
constexpr const char* kWalls = "WALL";
constexpr const char* kWallHeat = "WTHM";
constexpr const char* kBonds = "BOND";
constexpr const char* kEnergyAudit = "AUDT";

void put(ByteWriter& w, const Vec3& v) {
  w.put(v.x);
  w.put(v.y);
  w.put(v.z);
}
Vec3 get_vec3(ByteReader& r) {
  Vec3 v;
  r.get(v.x);
  r.get(v.y);
  r.get(v.z);
  return v;
}

void save_particles(ByteWriter& w, ParticleStore& particles) {
  std::uint32_t fields = 0;
  particles.for_each_field([&](auto&) { ++fields; });
  w.put(fields);
  particles.for_each_field([&](auto& field) {
    w.put(static_cast<std::uint32_t>(sizeof(typename std::decay_t<decltype(field)>::value_type)));
    w.put_vector(field);
  });
  w.put(particles.next_id());
}

/// Every field of for_each_field, so a field added there is saved and restored too; a
/// checkpoint with another list of fields is refused. Read into a store of its own and
/// moved in whole: a refused one leaves `particles_out` as it was, not with fields of
/// different lengths that any later pass would read out of bounds.
void load_particles(ByteReader& r, ParticleStore& particles_out) {
  ParticleStore particles;
  std::uint32_t fields = 0;
  particles.for_each_field([&](auto&) { ++fields; });
  const auto saved_fields = r.get<std::uint32_t>();
  if (saved_fields != fields)
    r.fail(fmt::format("holds {} particle fields, this regodem has {}: it was written by another version", saved_fields,
                       fields));
  std::size_t count = 0, index = 0;
  particles.for_each_field([&](auto& field) {
    const auto element_bytes = r.get<std::uint32_t>();
    if (element_bytes != sizeof(typename std::decay_t<decltype(field)>::value_type))
      r.fail(fmt::format("particle field {} has {}-byte elements, this regodem's {}", index, element_bytes,
                         sizeof(typename std::decay_t<decltype(field)>::value_type)));
    r.get_vector(field);
    if (index == 0) count = field.size();
    if (field.size() != count) r.fail(fmt::format("particle field {} has {} values for {} particles", index, field.size(), count));
    ++index;
  });
  particles.set_next_id(r.get<ParticleId>());
  particles_out = std::move(particles);
}

void save_bonds(ByteWriter& w, const BondStore& b, const BondCounts& counts, const std::vector<BondBreakEvent>& pending) {
  w.put(counts.formed);
  w.put(counts.broken_in_tension);
  w.put(counts.broken_in_shear);
  w.put_vector(b.id_i);
  w.put_vector(b.id_j);
  w.put_vector(b.kind);
  w.put_vector(b.rest_length_m);
  w.put(static_cast<std::uint64_t>(b.size()));
  for (std::size_t k = 0; k < b.size(); ++k) {
    const BondSection& s = b.section[k];
    for (double v : {s.radius_m, s.area_m2, s.inertia_m4, s.polar_inertia_m4, s.inv_area_per_m2,
                     s.radius_over_inertia_per_m3, s.radius_over_polar_inertia_per_m3})
      w.put(v);
    put(w, b.normal_of(k));
    const BondLoads l = b.loads_of(k);
    w.put(l.normal_force_N);
    put(w, l.shear_force_N);
    w.put(l.twist_moment_N_m);
    put(w, l.bend_moment_N_m);
    const BondAction& a = b.action[k];
    put(w, a.force_on_i_N);
    put(w, a.torque_on_i_N_m);
    put(w, a.torque_on_j_N_m);
  }
  w.put_vector(b.heat_to_i_W);
  w.put_vector(b.broken);
  w.put(static_cast<std::uint64_t>(pending.size()));
  for (const BondBreakEvent& e : pending) {
    w.put(e.time_s);
    put(w, e.position_m);
    w.put(static_cast<std::uint8_t>(e.mode));
    w.put(e.particle_i);
    w.put(e.particle_j);
    w.put(e.tensile_stress_Pa);
    w.put(e.shear_stress_Pa);
  }
}

void load_bonds(ByteReader& r, BondStore& b, BondCounts& counts, std::vector<BondBreakEvent>& pending) {
  r.get(counts.formed);
  r.get(counts.broken_in_tension);
  r.get(counts.broken_in_shear);
  r.get_vector(b.id_i);
  r.get_vector(b.id_j);
  r.get_vector(b.kind);
  r.get_vector(b.rest_length_m);
  const auto n = r.get<std::uint64_t>();
  if (n != b.id_i.size() || n != b.id_j.size() || n != b.kind.size() || n != b.rest_length_m.size())
    r.fail("the bond arrays differ in length");
  b.section.assign(n, {});
  b.number_in_order();
  b.resize_state(n);
  b.action.assign(n, {});
  for (std::size_t k = 0; k < n; ++k) {
    BondSection& s = b.section[k];
    for (double* v : {&s.radius_m, &s.area_m2, &s.inertia_m4, &s.polar_inertia_m4, &s.inv_area_per_m2,
                      &s.radius_over_inertia_per_m3, &s.radius_over_polar_inertia_per_m3})
      r.get(*v);
    const Vec3 normal = get_vec3(r);
    BondLoads l;
    r.get(l.normal_force_N);
    l.shear_force_N = get_vec3(r);
    r.get(l.twist_moment_N_m);
    l.bend_moment_N_m = get_vec3(r);
    b.set_state(k, normal, l);
    BondAction& a = b.action[k];
    a.force_on_i_N = get_vec3(r);
    a.torque_on_i_N_m = get_vec3(r);
    a.torque_on_j_N_m = get_vec3(r);
  }
  r.get_vector(b.heat_to_i_W);
  r.get_vector(b.broken);
  if (b.heat_to_i_W.size() != n || b.broken.size() != n) r.fail("the bond arrays differ in length");
  b.local_i.assign(n, 0);
  b.local_j.assign(n, 0);
  pending.resize(r.get<std::uint64_t>());
  for (BondBreakEvent& e : pending) {
    r.get(e.time_s);
    e.position_m = get_vec3(r);
    e.mode = static_cast<BondBreak>(r.get<std::uint8_t>());
    r.get(e.particle_i);
    r.get(e.particle_j);
    r.get(e.tensile_stress_Pa);
    r.get(e.shear_stress_Pa);
  }
}

/// Pair lists with their histories, and the wall and mesh lists.
void save_neighbors(ByteWriter& w, const NeighborList& nl) {
  w.put_vector(nl.offset);
  w.put_vector(nl.partner);
  w.put_vector(nl.tangential_history_m);
  w.put_vector(nl.wall_offset);
  w.put_vector(nl.wall_primitive);
  w.put_vector(nl.wall_tangential_history_m);
  w.put_vector(nl.mesh_offset);
  w.put_vector(nl.mesh_wall);
  w.put_vector(nl.mesh_triangle);
  w.put_vector(nl.mesh_tangential_history_m);
  w.put_vector(std::vector<std::uint32_t>{});  // where the threads' owner ranges were (issue 18: unused)
  const NeighborList::BuildState build = nl.build_state();
  w.put_vector(build.positions_m);
  w.put_vector(build.half_skin_m);
  w.put_vector(build.body_half_skin_m);
  w.put(build.slow_half_skin_m);
  w.put(build.rebuilds);
}

/// The layout version of a section (1 when absent: the reader reports it).
std::uint32_t section_version(const Checkpoint& checkpoint, std::string_view tag) {
  for (const CheckpointSection& s : checkpoint.sections())
    if (s.tag == tag) return s.version;
  return 1;
}

/// NBRS version 2 adds each particle's and wall body's half of the skin; a version 1
/// section (before issue 18) restores without them, and the lists are built again at
/// the next step.
constexpr std::uint32_t kNeighborsVersion = 2;

/// WTHM version 2 adds each wall's radiated and held-end heat, its peak temperature and
/// segment temperatures, and every wall node's contact heat (issue 21); a version 1
/// section restores walls of one node each.
constexpr std::uint32_t kWallHeatVersion = 2;
constexpr std::uint32_t kEnergyAuditVersion = 2;  // 2: the fastest impact

/// skin_m, bodies: a version 1 list was built with every half at skin/2.
void load_neighbors(ByteReader& r, std::uint32_t version, double skin_m, std::size_t bodies, NeighborList& nl,
                    std::size_t particles,
                    std::size_t primitives, std::size_t meshes) {
  r.get_vector(nl.offset);
  r.get_vector(nl.partner);
  r.get_vector(nl.tangential_history_m);
  r.get_vector(nl.wall_offset);
  r.get_vector(nl.wall_primitive);
  r.get_vector(nl.wall_tangential_history_m);
  r.get_vector(nl.mesh_offset);
  r.get_vector(nl.mesh_wall);
  r.get_vector(nl.mesh_triangle);
  r.get_vector(nl.mesh_tangential_history_m);
  std::vector<std::uint32_t> unused_owner_ranges;  // the threads' owner ranges of checkpoints before issue 18
  r.get_vector(unused_owner_ranges);
  NeighborList::BuildState build;
  r.get_vector(build.positions_m);
  if (version >= 2) {
    r.get_vector(build.half_skin_m);
    r.get_vector(build.body_half_skin_m);
    r.get(build.slow_half_skin_m);
  } else {
    // Built by the uniform rule, which is the present one with every half at skin/2.
    build.half_skin_m.assign(build.positions_m.size(), 0.5 * skin_m);
    build.body_half_skin_m.assign(bodies, 0.5 * skin_m);
    build.slow_half_skin_m = 0.5 * skin_m;
  }
  r.get(build.rebuilds);
  if (build.half_skin_m.size() != build.positions_m.size()) r.fail("holds neighbour skins of another particle count");
  for (const double h : build.half_skin_m)
    if (!(h > 0.0)) r.fail("holds a neighbour skin that is not positive");
  nl.restore_build_state(std::move(build));
  // A list of another particle count, or pointing past the arrays, would be read out
  // of bounds by the force pass.
  const auto csr_fits = [&](const std::vector<std::uint32_t>& offset, std::size_t entries) {
    return offset.empty() || (offset.size() == particles + 1 && offset.back() == entries);
  };
  bool fits = csr_fits(nl.offset, nl.partner.size()) && csr_fits(nl.wall_offset, nl.wall_primitive.size()) &&
              csr_fits(nl.mesh_offset, nl.mesh_triangle.size()) &&
              nl.tangential_history_m.size() == nl.partner.size() &&
              nl.wall_tangential_history_m.size() == nl.wall_primitive.size() &&
              nl.mesh_tangential_history_m.size() == nl.mesh_triangle.size() &&
              nl.mesh_wall.size() == nl.mesh_triangle.size();
  for (std::uint32_t j : nl.partner) fits = fits && j < particles;
  for (std::uint32_t p : nl.wall_primitive) fits = fits && p < primitives;
  for (std::uint32_t m : nl.mesh_wall) fits = fits && m < meshes;
  if (!fits) r.fail("the neighbour lists do not fit the particles and walls");
}

}  // namespace

CheckpointParticles read_checkpoint_particles(const Checkpoint& checkpoint) {
  CheckpointParticles saved;
  ByteReader particles = checkpoint.reader(kParticles);
  load_particles(particles, saved.particles);
  ByteReader names = checkpoint.reader(kMaterials);
  saved.material_names.resize(names.get<std::uint64_t>());
  for (std::string& name : saved.material_names) name = names.get_string();
  for (const MaterialIndex m : saved.particles.material)
    if (m >= saved.material_names.size()) names.fail(fmt::format("a particle has material {} of {}", m, saved.material_names.size()));
  checkpoint.reader(kClock).get(saved.time_s);
  return saved;
}

void Simulation::save_state(Checkpoint& checkpoint) const {
  {
    ByteWriter w;
    // for_each_field hands out mutable references; nothing is changed here.
    save_particles(w, const_cast<ParticleStore&>(particles));
    checkpoint.add(kParticles, 1, std::move(w));
  }
  {
    ByteWriter w;
    w.put(static_cast<std::uint64_t>(model_.materials.size()));
    for (std::size_t m = 0; m < model_.materials.size(); ++m) w.put_string(model_.materials[static_cast<MaterialIndex>(m)].name);
    checkpoint.add(kMaterials, 1, std::move(w));
  }
  {
    ByteWriter w;
    w.put(time_s_);
    w.put(step_);
    w.put(model_.settings.time_step_s);
    w.put(static_cast<std::int32_t>(model_.settings.threads));
    w.put(static_cast<std::uint8_t>(forces_current_));
    w.put(static_cast<std::int32_t>(active_threads_));
    w.put(stats_.particle_contacts);
    w.put(stats_.wall_contacts);
    w.put(ledger_.reference_energy_J);
    w.put(ledger_.boundary_heat_in_J);
    w.put(ledger_.generated_heat_J);
    w.put(generated_heat_W_);
    w.put_vector(wall_generated_heat_W_);
    put(w, grid_.origin_m);
    w.put(grid_.cell_size_m);
    w.put(static_cast<std::int32_t>(grid_.nx));
    w.put(static_cast<std::int32_t>(grid_.ny));
    w.put(static_cast<std::int32_t>(grid_.nz));
    w.put(lost_particle_count_);
    checkpoint.add(kClock, 1, std::move(w));
  }
  {
    ByteWriter w;
    save_neighbors(w, neighbors_);
    checkpoint.add(kNeighbors, kNeighborsVersion, std::move(w));
  }
  {
    ByteWriter w;
    w.put(static_cast<std::uint64_t>(walls.bodies.size()));
    for (const WallBody& b : walls.bodies) {
      w.put_string(b.name);
      const WallMotion& m = b.motion;
      put(w, m.velocity_m_per_s);
      put(w, m.angular_velocity_rad_per_s);
      put(w, m.axis_point_m);
      w.put(m.start_s);
      w.put(m.stop_s);
      w.put(m.max_travel_m);
      put(w, b.force_N);
      put(w, b.torque_N_m);
      put(w, b.displacement_m);
      for (const auto& row : b.pose.rotation)
        for (double v : row) w.put(v);
      put(w, b.pose.translation_m);
      w.put(b.travel_m);
      w.put(b.depth_at_start_m);
      put(w, b.feed_direction);
      put(w, b.spin_axis);
      w.put(b.displacement_since_build_m);
    }
    w.put(static_cast<std::uint64_t>(walls.primitives.size()));
    for (const WallPrimitive& p : walls.primitives) {
      put(w, p.point_m);
      put(w, p.axis);
    }
    w.put(static_cast<std::uint64_t>(walls.meshes.size()));
    checkpoint.add(kWalls, 1, std::move(w));
  }
  {
    ByteWriter w;
    w.put(static_cast<std::uint64_t>(wall_thermal_state.size()));
    for (std::size_t b = 0; b < wall_thermal_state.size(); ++b) {
      const ThermalWallState& t = wall_thermal_state[b];
      w.put(static_cast<std::uint8_t>(model_.wall_thermal[b].mode));
      w.put(t.temperature_K);
      w.put(t.heat_flow_to_particles_W);
      w.put(t.heat_to_particles_J);
      w.put(t.generated_heat_J);
      w.put(t.radiated_heat_J);
      w.put(t.held_end_heat_in_J);
      w.put(t.peak_temperature_K);
      w.put_vector(t.segment_temperature_K);
    }
    w.put_vector(node_heat_in_W_);
    checkpoint.add(kWallHeat, kWallHeatVersion, std::move(w));
  }
  {
    ByteWriter w;
    save_bonds(w, bonds_, bond_counts_, bond_breaks_);
    checkpoint.add(kBonds, 1, std::move(w));
  }
  {
    ByteWriter w;
    w.put(audit_.wall_work_J);
    w.put(audit_.dissipated_J);
    w.put(audit_.exchanged_J);
    w.put(audit_.spring_source_J);
    w.put_vector(audit_.wall_work_by_body_J);
    w.put(dissipated_power_W_);
    w.put(spring_source_W_);
    w.put(contact_elastic_energy_J_);
    w.put_vector(wall_power_W_);
    w.put(static_cast<std::uint8_t>(audit_awaits_contact_elastic_));
    w.put(static_cast<std::uint8_t>(keeps_energy_audit()));
    w.put(fastest_impact_.key);  // version 2
    w.put(fastest_impact_.approach_speed_m_per_s);
    w.put(fastest_impact_.wall_body);
    w.put(fastest_impact_.time_s);
    checkpoint.add(kEnergyAudit, kEnergyAuditVersion, std::move(w));
  }
}

void Simulation::restore_state(const Checkpoint& checkpoint) {
  {
    ByteReader r = checkpoint.reader(kParticles);
    load_particles(r, particles);
  }
  const std::size_t n = particles.size();
  {
    ByteReader r = checkpoint.reader(kMaterials);
    const auto count = r.get<std::uint64_t>();
    if (count != model_.materials.size()) r.fail(fmt::format("has {} materials, the scenario {}", count, model_.materials.size()));
    for (std::size_t m = 0; m < count; ++m) {
      const std::string name = r.get_string();
      if (name != model_.materials[static_cast<MaterialIndex>(m)].name)
        r.fail(fmt::format("material {} is '{}', in the scenario '{}'", m, name,
                           model_.materials[static_cast<MaterialIndex>(m)].name));
    }
  }
  int saved_threads = 0;
  {
    ByteReader r = checkpoint.reader(kClock);
    r.get(time_s_);
    r.get(step_);
    const auto dt = r.get<double>();
    if (dt != model_.settings.time_step_s)
      r.fail(fmt::format("was written with a time step of {:.17g} s, the scenario gives {:.17g} s", dt,
                         model_.settings.time_step_s));
    saved_threads = r.get<std::int32_t>();
    forces_current_ = r.get<std::uint8_t>() != 0;
    active_threads_ = r.get<std::int32_t>();
    r.get(stats_.particle_contacts);
    r.get(stats_.wall_contacts);
    r.get(ledger_.reference_energy_J);
    r.get(ledger_.boundary_heat_in_J);
    r.get(ledger_.generated_heat_J);
    r.get(generated_heat_W_);
    r.get_vector(wall_generated_heat_W_);
    if (wall_generated_heat_W_.size() != walls.bodies.size()) r.fail("holds another number of walls");
    grid_.origin_m = get_vec3(r);
    r.get(grid_.cell_size_m);
    grid_.nx = r.get<std::int32_t>();
    grid_.ny = r.get<std::int32_t>();
    grid_.nz = r.get<std::int32_t>();
    r.get(lost_particle_count_);
    if (active_threads_ < 1 || active_threads_ > saved_threads) r.fail("holds an impossible thread count");
  }
  {
    ByteReader r = checkpoint.reader(kWalls);
    const auto bodies = r.get<std::uint64_t>();
    if (bodies != walls.bodies.size())
      r.fail(fmt::format("has {} wall bodies, the scenario {}", bodies, walls.bodies.size()));
    for (WallBody& b : walls.bodies) {
      const std::string name = r.get_string();
      if (name != b.name) r.fail(fmt::format("has wall '{}' where the scenario has '{}'", name, b.name));
      WallMotion& m = b.motion;
      m.velocity_m_per_s = get_vec3(r);
      m.angular_velocity_rad_per_s = get_vec3(r);
      m.axis_point_m = get_vec3(r);
      r.get(m.start_s);
      r.get(m.stop_s);
      r.get(m.max_travel_m);
      b.force_N = get_vec3(r);
      b.torque_N_m = get_vec3(r);
      b.displacement_m = get_vec3(r);
      for (auto& row : b.pose.rotation)
        for (double& v : row) r.get(v);
      b.pose.translation_m = get_vec3(r);
      r.get(b.travel_m);
      r.get(b.depth_at_start_m);
      b.feed_direction = get_vec3(r);
      b.spin_axis = get_vec3(r);
      r.get(b.displacement_since_build_m);
      b.spin_reach_cached = false;  // a cache: found again from the same pose
    }
    const auto primitives = r.get<std::uint64_t>();
    if (primitives != walls.primitives.size())
      r.fail(fmt::format("has {} wall primitives, the scenario {}", primitives, walls.primitives.size()));
    for (WallPrimitive& p : walls.primitives) {
      p.point_m = get_vec3(r);
      p.axis = get_vec3(r);
    }
    if (r.get<std::uint64_t>() != walls.meshes.size()) r.fail("has another number of mesh walls than the scenario");
  }
  {
    ByteReader r = checkpoint.reader(kWallHeat, kWallHeatVersion);
    const std::uint32_t version = section_version(checkpoint, kWallHeat);
    if (r.get<std::uint64_t>() != wall_thermal_state.size())
      r.fail("has another number of thermal walls than the scenario");
    for (std::size_t b = 0; b < wall_thermal_state.size(); ++b) {
      const ThermalWall& wall = model_.wall_thermal[b];
      ThermalWallState& t = wall_thermal_state[b];
      if (r.get<std::uint8_t>() != static_cast<std::uint8_t>(wall.mode)) r.fail("has a wall of another thermal mode");
      r.get(t.temperature_K);
      r.get(t.heat_flow_to_particles_W);
      r.get(t.heat_to_particles_J);
      r.get(t.generated_heat_J);
      if (version >= 2) {
        r.get(t.radiated_heat_J);
        r.get(t.held_end_heat_in_J);
        r.get(t.peak_temperature_K);
        const std::size_t segments = t.segment_temperature_K.size();
        r.get_vector(t.segment_temperature_K);
        if (t.segment_temperature_K.size() != segments) r.fail("has a wall of another number of thermal segments");
      } else {
        if (wall.rod.segmented()) r.fail("is from before segmented walls (WTHM version 1): start the run again");
        t.peak_temperature_K = t.temperature_K;
      }
    }
    if (version >= 2) {
      r.get_vector(node_heat_in_W_);
      if (node_heat_in_W_.size() != wall_node_begin_.back()) r.fail("has another number of wall thermal nodes");
    } else {
      // One node per wall: what its contacts put in, from the wall's sums.
      for (std::size_t b = 0; b < wall_thermal_state.size(); ++b)
        node_heat_in_W_[wall_node_begin_[b]] =
            -wall_thermal_state[b].heat_flow_to_particles_W + wall_generated_heat_W_[b];
    }
  }
  {
    ByteReader r = checkpoint.reader(kNeighbors, kNeighborsVersion);
    load_neighbors(r, section_version(checkpoint, kNeighbors), model_.settings.neighbor_skin_m, walls.bodies.size(),
                   neighbors_, n, walls.primitives.size(),
                   walls.meshes.size());
  }
  {
    ByteReader r = checkpoint.reader(kBonds);
    load_bonds(r, bonds_, bond_counts_, bond_breaks_);
    for (std::uint16_t k : bonds_.kind)
      if (k >= model_.bond_kinds.size()) r.fail(fmt::format("has a bond of kind {}, the scenario {} kinds", k, model_.bond_kinds.size()));
    if (bonds_.refresh_indices(particles) < bonds_.size()) r.fail("has a bond to a particle that does not exist");
  }
  bool books_kept = false;
  if (checkpoint.has(kEnergyAudit)) {
    ByteReader r = checkpoint.reader(kEnergyAudit, kEnergyAuditVersion);
    r.get(audit_.wall_work_J);
    r.get(audit_.dissipated_J);
    r.get(audit_.exchanged_J);
    r.get(audit_.spring_source_J);
    r.get_vector(audit_.wall_work_by_body_J);
    r.get(dissipated_power_W_);
    r.get(spring_source_W_);
    r.get(contact_elastic_energy_J_);
    r.get_vector(wall_power_W_);
    audit_awaits_contact_elastic_ = r.get<std::uint8_t>() != 0;
    books_kept = r.at_end() || r.get<std::uint8_t>() != 0;  // d5f098e wrote no flag: its books were kept
    if (section_version(checkpoint, kEnergyAudit) >= 2) {  // version 1 (before 2026-12-02) saw no impacts
      r.get(fastest_impact_.key);
      r.get(fastest_impact_.approach_speed_m_per_s);
      r.get(fastest_impact_.wall_body);
      r.get(fastest_impact_.time_s);
      if (fastest_impact_.wall_body >= static_cast<std::int32_t>(walls.bodies.size()))
        r.fail("holds an impact on a wall that does not exist");
    }
    if (audit_.wall_work_by_body_J.size() != walls.bodies.size() || wall_power_W_.size() != walls.bodies.size())
      r.fail("holds another number of walls");
  }
  if (!books_kept && keeps_energy_audit()) {
    // Written before the audit existed, or by a run that did not keep it: the books open
    // here, with the energy the particles have now (the springs' share joins at the next
    // contact pass).
    audit_ = EnergyAudit{};
    audit_.wall_work_by_body_J.assign(walls.bodies.size(), 0.0);
    for (std::size_t i = 0; i < n; ++i) audit_.exchanged_J += particle_mechanical_energy_J(i);
    audit_.exchanged_J += bond_elastic_energy_J();
    contact_elastic_energy_J_ = 0.0;
    audit_awaits_contact_elastic_ = true;
  }
  // The lists do not depend on the thread count, nor do the sums over them: another
  // thread count only shares the owners' blocks out otherwise, and the run goes on bit for bit.
  neighbors_.index_partners(n);
  active_threads_ = force_pass_threads();
}

void Simulation::adopt_particles(const Checkpoint& checkpoint, const std::vector<MaterialIndex>& material_of_saved,
                                 std::optional<double> temperature_K) {
  if (!particles.empty())
    throw CheckpointError(fmt::format("particles from checkpoint '{}' must come before any other", checkpoint.source));
  {
    ByteReader r = checkpoint.reader(kParticles);
    load_particles(r, particles);
  }
  const std::size_t n = particles.size();
  for (std::size_t i = 0; i < n; ++i) {
    MaterialIndex& m = particles.material[i];
    if (m >= material_of_saved.size())
      throw CheckpointError(fmt::format("checkpoint '{}': particle {} has material {} of {}", checkpoint.source,
                                        particles.id[i], m, material_of_saved.size()));
    m = material_of_saved[m];
    if (temperature_K) {
      particles.temperature_K[i] = *temperature_K;
      if (i < particles.peak_temperature_K.size()) particles.peak_temperature_K[i] = *temperature_K;
      if (i < particles.time_above_threshold_s.size()) particles.time_above_threshold_s[i] = 0.0;
    }
    particles.conductivity_W_per_mK[i] = model_.materials[m].conductivity_W_per_mK.at(particles.temperature_K[i]);
    if (heat_enabled()) ledger_.reference_energy_J += particle_thermal_energy_J(i);
    audit_.exchanged_J += particle_mechanical_energy_J(i);
  }
  {
    // The particle pairs and their springs; wall entries belong to the other run's walls.
    ByteReader r = checkpoint.reader(kNeighbors, kNeighborsVersion);
    NeighborList saved;
    load_neighbors(r, section_version(checkpoint, kNeighbors), model_.settings.neighbor_skin_m, walls.bodies.size(), saved,
                   n, std::numeric_limits<std::size_t>::max(),
                   std::numeric_limits<std::size_t>::max());
    neighbors_ = NeighborList();
    neighbors_.offset = std::move(saved.offset);
    neighbors_.partner = std::move(saved.partner);
    neighbors_.tangential_history_m = std::move(saved.tangential_history_m);
    if (neighbors_.offset.empty()) neighbors_.offset.assign(n + 1, 0);
    neighbors_.wall_offset.assign(n + 1, 0);
    neighbors_.mesh_offset.assign(n + 1, 0);
  }
  {
    ByteReader r = checkpoint.reader(kBonds);
    BondCounts counts;
    std::vector<BondBreakEvent> pending;
    load_bonds(r, bonds_, counts, pending);
    for (std::uint16_t k : bonds_.kind)
      if (k >= model_.bond_kinds.size())
        r.fail(fmt::format("has bonds of kind {}, but this scenario defines {} bond kinds (bond kinds are matched by "
                           "their order in `bonds`)",
                           k, model_.bond_kinds.size()));
    bond_counts_ = {};
    bond_counts_.formed = bonds_.size();
    for (std::size_t b = 0; b < bonds_.size(); ++b) bonds_.broken[b] = 0;
    // The saved order, which the rebuild then sorts.
    if (bonds_.refresh_indices(particles) < bonds_.size()) r.fail("has a bond to a particle that does not exist");
  }
  audit_.exchanged_J += bond_elastic_energy_J();  // the adopted bonds' loads
  // Sorts the particles and carries the springs over; renumbers the bonds.
  rebuild_neighbors();
  forces_current_ = false;
}

}  // namespace regodem
