#include "sim/snapshot_capture.hpp"

#include <algorithm>
#include <limits>

#include "sim/contact_walk.hpp"

namespace regodem {

std::vector<std::uint32_t> contacts_per_particle(const Simulation& sim) {
  const ParticleStore& p = sim.particles;
  std::vector<std::uint32_t> count(p.size(), 0);
  // The lists index particles as ordered at the last build; particles appended since
  // come after all of those and are in no list yet. Lists that point past the store
  // (none should: a removal or a gather rebuilds them) are not read.
  const NeighborList& lists = sim.neighbor_list();
  const auto past = [](const std::vector<std::uint32_t>& v, std::size_t n) {
    return std::any_of(v.begin(), v.end(), [n](std::uint32_t k) { return k >= n; });
  };
  if (past(lists.partner, p.size()) || past(lists.wall_primitive, sim.walls.primitives.size())) return count;
  const ContactWalk walk(p, lists, sim.walls);
  MeshTouchFinder finder;
  std::vector<MeshTouch> touches;
  const auto owners = static_cast<std::uint32_t>(std::min(walk.owners(), p.size()));
  for (std::uint32_t i = 0; i < owners; ++i) {
    walk.pairs(i, [&](std::uint32_t, const ContactWalk::ListedPair& pair) {
      ++count[i];
      ++count[pair.j];
    });
    walk.walls(i, finder, touches, [&](const WallTouch&) { ++count[i]; });
  }
  return count;
}

SimulationSnapshotWriter::SimulationSnapshotWriter(std::filesystem::path directory, VtpOptions options,
                                                   bool write_walls, std::vector<std::string> region_names)
    : series_(std::move(directory), options, write_walls), region_names_(std::move(region_names)) {}

ParticleSnapshot SimulationSnapshotWriter::particle_snapshot(const Simulation& sim) {
  const ParticleStore& p = sim.particles;
  contacts_ = contacts_per_particle(sim);
  ParticleSnapshot s;
  s.time_s = sim.time_s();
  s.step = sim.step_count();
  s.id = p.id;
  s.position_m = p.position_m;
  s.radius_m = p.radius_m;
  s.velocity_m_per_s = p.velocity_m_per_s;
  s.angular_velocity_rad_per_s = p.angular_velocity_rad_per_s;
  s.material = p.material;
  s.region = p.region;
  s.contacts = contacts_;
  if (sim.heat_enabled()) s.temperature_K = p.temperature_K;
  if (sim.heat_enabled() && sim.settings().heat.track_thermal_history) {
    s.peak_temperature_K = p.peak_temperature_K;
    s.time_above_threshold_s = p.time_above_threshold_s;
  }
  // Intact bonds per particle, from the bond store's per-particle index (current after
  // every bond pass); the field is written only for a run with bonds.
  if (sim.bonds_configured()) {
    const BondStore& bonds = sim.bonds();
    intact_bonds_.assign(p.size(), 0);
    if (bonds.bond_offset.size() == p.size() + 1)
      for (std::size_t i = 0; i < p.size(); ++i)
        intact_bonds_[i] = static_cast<std::uint16_t>(bonds.bond_offset[i + 1] - bonds.bond_offset[i]);
    s.intact_bonds = intact_bonds_;
  }
  for (std::size_t m = 0; m < sim.model().materials.size(); ++m)
    s.material_names.push_back(sim.model().materials[static_cast<MaterialIndex>(m)].name);
  s.region_names = region_names_;
  return s;
}

WallSnapshot SimulationSnapshotWriter::wall_snapshot(const Simulation& sim) {
  const Domain& domain = sim.settings().domain;
  surface_ = tessellate_walls(sim.walls, domain.min_m, domain.max_m);
  WallSnapshot s;
  s.time_s = sim.time_s();
  s.step = sim.step_count();
  s.surface = &surface_;
  for (const WallBody& body : sim.walls.bodies) {
    s.body_names.push_back(body.name);
    s.body_force_N.push_back(body.force_N);
  }
  if (sim.heat_enabled()) {
    for (std::size_t b = 0; b < sim.walls.bodies.size(); ++b) {
      const ThermalWall* w = b < sim.model().wall_thermal.size() ? &sim.model().wall_thermal[b] : nullptr;
      const bool adiabatic = w == nullptr || w->mode == WallThermalMode::adiabatic;
      s.body_temperature_K.push_back(adiabatic ? std::numeric_limits<double>::quiet_NaN()
                                               : sim.wall_thermal_state[b].temperature_K);
      s.body_thermal_mode.push_back(w == nullptr ? 0 : static_cast<std::uint8_t>(w->mode));
    }
  }
  return s;
}

void SimulationSnapshotWriter::write(const Simulation& sim) {
  const ParticleSnapshot particles = particle_snapshot(sim);
  if (sim.walls.bodies.empty()) {
    series_.write(particles, nullptr);
    return;
  }
  const WallSnapshot walls = wall_snapshot(sim);
  series_.write(particles, &walls);
}

}  // namespace regodem
