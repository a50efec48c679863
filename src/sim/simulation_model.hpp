#pragma once
// The model of a run (issue 18; MuJoCo's mjModel is the pattern): what does not change
// while it steps. The settings, the materials and the per-pair tables derived from them
// (contact law, conduction), the per-material thermal caches, the bond kinds and the walls'
// thermal descriptions. The
// Simulation holds one and reads it in every pass; the state (particles, walls' poses and
// temperatures, lists, bonds, books, clock) is what a checkpoint saves.
#include <vector>

#include "contact/contact_parameters.hpp"
#include "contact/parallel_bond.hpp"
#include "core/material.hpp"
#include "core/vec3.hpp"
#include "thermal/conduction_parameters.hpp"
#include "thermal/heat_partition.hpp"
#include "thermal/thermal_wall.hpp"

namespace regodem {

struct Domain {
  Vec3 min_m, max_m;
  bool contains(const Vec3& x) const {
    return x.x >= min_m.x && x.y >= min_m.y && x.z >= min_m.z && x.x <= max_m.x && x.y <= max_m.y &&
           x.z <= max_m.z;
  }
};

/// Heat transfer settings (DESIGN.md section 2, "Conduction", "Thermal stepping").
struct HeatSettings {
  bool enabled = false;
  double time_scale_factor = 1.0;  // S: every conductance x S, for compressed mechanical time
  // Heat generated at contacts (docs/physics.md, "Friction heat and its partition"): the sliding
  // power only (friction_heating), or every loss of contacts and bonds (dissipation_heating).
  bool friction_heating = false;
  bool dissipation_heating = false;
  HeatPartitionModel partition = HeatPartitionModel::fixed;
  double friction_partition = 0.5;  // `fixed`: the particle's share at a wall (two particles: half each)
  bool generates_heat() const { return friction_heating || dissipation_heating; }
  /// The partition weighs each body by its properties (conductivity or effusivity).
  bool partition_weighs_bodies() const {
    return generates_heat() &&
           (partition == HeatPartitionModel::conductivity || partition == HeatPartitionModel::effusivity);
  }
  // Per-particle peak temperature and time above the threshold (measure/thermal_history.hpp),
  // recorded in the temperature update when on.
  bool track_thermal_history = false;
  double thermal_history_threshold_K = 203.15;  // -70 degC
};

/// What happens to a particle that leaves the domain: `stop` the run with a blow-up
/// error (a leak or an instability is a bug in the scenario), or `remove` it and go on
/// (fragments thrown off a failing sample, cuttings flung by a drill), counting it and
/// booking its thermal energy as lost.
enum class LostParticles { stop, remove };

struct SimulationSettings {
  Domain domain;
  LostParticles lost_particles = LostParticles::stop;
  Vec3 gravity_m_per_s2{0.0, 0.0, -9.81};
  double time_step_s = 0.0;
  double neighbor_skin_m = 0.0;
  double min_particle_radius_m = 0.0;  // sizes the neighbour grid
  double max_particle_radius_m = 0.0;  // the largest a run inserts: how far ghosts reach under MPI
  int threads = 1;
  // Below this many particles per thread the force pass is shorter than the threads'
  // synchronisation, so fewer threads run it.
  std::size_t min_particles_per_thread = 2500;
  // Keep the mechanical energy books (EnergyAudit: losses, the springs' energy, the
  // walls' work); dissipation heating keeps them whatever this says.
  bool energy_audit = false;
  HeatSettings heat;
};

/// The settings, the materials and everything derived from them, built once; a stage's
/// overrides of the pair properties give a new table (Simulation::set_materials).
struct SimulationModel {
  SimulationSettings settings;
  MaterialTable materials;
  ContactParameterTable contact;        // per material pair, from `materials`
  ConductionParameterTable conduction;  // per material pair, the time-scale factor S folded in
  std::vector<double> inv_specific_heat;  // per material: 1/c if c is constant, else 0
  std::vector<char> conductivity_varies;  // per material: k is a table of T
  // Parallel bonds: the kinds, and per material pair (a * materials + b, symmetric) the
  // kind that bonds them or -1 (Simulation::configure_bonds).
  std::vector<BondParameters> bond_kinds;
  std::vector<int> bond_kind_of_pair;
  // What each wall body is thermally, index for index with the bodies (its temperatures
  // are state: Simulation::wall_thermal_state).
  std::vector<ThermalWall> wall_thermal;

  /// Throws InputError for settings no run can take (a neighbour skin of 0).
  SimulationModel(MaterialTable materials, const SimulationSettings& settings);
  /// Derives the tables and caches from `materials` again (after they changed).
  void derive_tables();
};

}  // namespace regodem
