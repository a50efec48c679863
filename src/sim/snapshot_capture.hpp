#pragma once
// Takes the ParaView snapshots of a Simulation: gathers what io/snapshot_series.hpp
// writes (views of the particle arrays, a contact count per particle, the walls'
// triangles with each body's temperature and force) and hands it over.
#include <filesystem>
#include <string>
#include <vector>

#include "geometry/wall_tessellation.hpp"
#include "io/snapshot_series.hpp"
#include "sim/simulation.hpp"

namespace regodem {

/// Contacts of each particle (touching particles and walls) from the neighbour lists of
/// the last build, by the force pass's own walk (ContactWalk): done only when a snapshot is
/// taken, so the force pass stays as it is. Particles added since the last build have 0.
std::vector<std::uint32_t> contacts_per_particle(const Simulation& sim);

class SimulationSnapshotWriter {
 public:
  /// `region_names`: the insertion region tags in tag order (StagePlan::region_names).
  SimulationSnapshotWriter(std::filesystem::path directory, VtpOptions options, bool write_walls,
                           std::vector<std::string> region_names);

  void write(const Simulation& sim);

  const SnapshotSeries& series() const { return series_; }
  SnapshotSeries& series() { return series_; }

  /// The snapshots' data without writing them (tests compare files against these).
  ParticleSnapshot particle_snapshot(const Simulation& sim);
  WallSnapshot wall_snapshot(const Simulation& sim);

 private:
  SnapshotSeries series_;
  std::vector<std::string> region_names_;
  std::vector<std::uint32_t> contacts_;  // the buffer the particle snapshot views
  std::vector<std::uint16_t> intact_bonds_;
  WallSurface surface_;                  // the buffer the wall snapshot points to
};

}  // namespace regodem
