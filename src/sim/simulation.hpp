#pragma once
// The simulation state and its time step: particles, materials, walls, neighbour
// lists, and the velocity-Verlet integrator around one contact pass per step.
#include <cstdint>
#include <string>
#include <vector>

#include "contact/contact_parameters.hpp"
#include "contact/neighbor_list.hpp"
#include "core/material.hpp"
#include "core/particle_store.hpp"
#include "geometry/wall_set.hpp"

namespace regodem {

struct Domain {
  Vec3 min_m, max_m;
  bool contains(const Vec3& x) const {
    return x.x >= min_m.x && x.y >= min_m.y && x.z >= min_m.z && x.x <= max_m.x && x.y <= max_m.y &&
           x.z <= max_m.z;
  }
};

struct SimulationSettings {
  Domain domain;
  Vec3 gravity_m_per_s2{0.0, 0.0, -9.81};
  double time_step_s = 0.0;
  double neighbor_skin_m = 0.0;
  double min_particle_radius_m = 0.0;  // sizes the neighbour grid
  int threads = 1;
  // Below this many particles per thread the force pass is shorter than the threads'
  // synchronisation, so fewer threads run it.
  std::size_t min_particles_per_thread = 2500;
};

/// Contact counts and extremes seen in the last force pass.
struct ContactStatistics {
  std::uint64_t particle_contacts = 0;
  std::uint64_t wall_contacts = 0;
};

class Simulation {
 public:
  Simulation(MaterialTable materials, WallSet walls, const SimulationSettings& settings);

  /// Advances one time step. Throws SimulationError on a blow-up (non-finite state,
  /// a particle moving more than half its radius in one step) or an escape.
  void step();
  void advance(std::uint64_t steps);

  /// Adds particles; forces and neighbour lists are refreshed before the next step.
  void add_particle(const NewParticle& p);
  /// Call after changing the material pair properties (stage overrides).
  void refresh_contact_parameters();

  double time_s() const { return time_s_; }
  std::uint64_t step_count() const { return step_; }
  double time_step_s() const { return settings_.time_step_s; }
  int threads() const { return settings_.threads; }
  const SimulationSettings& settings() const { return settings_; }
  const ContactStatistics& contact_statistics() const { return stats_; }
  const NeighborList& neighbor_list() const { return neighbors_; }

  // Measurements over all particles (each a pass over the arrays).
  double translational_kinetic_energy_J() const;
  double rotational_kinetic_energy_J() const;
  double gravitational_potential_energy_J() const;  // -sum m g.x
  double max_speed_m_per_s() const;
  /// Largest particle-particle overlap divided by the smaller diameter of the pair.
  double max_overlap_fraction() const;

  ParticleStore particles;
  MaterialTable materials;
  WallSet walls;

 private:
  void ensure_forces();
  void rebuild_neighbors();
  /// slip_time_s: dt after a step, 0 when re-evaluating an unchanged state.
  void compute_forces(double slip_time_s);
  /// Returns the largest displacement since the last neighbour build.
  double first_half_kick_and_drift();
  void second_half_kick();
  [[noreturn]] void report_blow_up(const std::string& what, double at_time_s, std::uint64_t at_step) const;

  SimulationSettings settings_;
  ContactParameterTable contact_parameters_;
  NeighborList neighbors_;
  CellGrid grid_;
  double time_s_ = 0.0;
  std::uint64_t step_ = 0;
  bool forces_current_ = false;
  int active_threads_ = 1;  // threads of the force pass, set at each neighbour build
  ContactStatistics stats_;

  struct Spill {  // a contribution to a particle outside the thread's owner range
    std::uint32_t particle;
    Vec3 force_N, torque_N_m;
  };
  std::vector<std::vector<Spill>> spills_;
  std::vector<std::vector<Vec3>> wall_force_by_thread_, wall_torque_by_thread_;
};

}  // namespace regodem
