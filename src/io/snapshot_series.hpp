#pragma once
// Snapshots of a run for ParaView: per snapshot one particles .vtp and one walls .vtp
// in OUTDIR/vtk/, listed with their simulated times in OUTDIR/particles.pvd and
// OUTDIR/walls.pvd. Each .vtp is written whole, then its .pvd rewritten whole, so a run
// stopped at any point leaves two valid collections. The data come in as plain arrays
// (this layer knows no Simulation); sim/snapshot_capture.hpp fills them.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/particle_store.hpp"
#include "core/vec3.hpp"
#include "geometry/wall_tessellation.hpp"
#include "io/pvd_writer.hpp"
#include "io/vtp_writer.hpp"

namespace regodem {

/// One snapshot of the particles: views of per-particle arrays (all of one length).
struct ParticleSnapshot {
  double time_s = 0.0;
  std::uint64_t step = 0;
  std::span<const ParticleId> id;
  std::span<const Vec3> position_m;
  std::span<const double> radius_m;
  std::span<const Vec3> velocity_m_per_s;
  std::span<const Vec3> angular_velocity_rad_per_s;
  std::span<const MaterialIndex> material;
  std::span<const RegionTag> region;
  std::span<const std::uint32_t> contacts;      // touching particles and walls
  // Optional fields, written only when given (non-empty): no field of placeholders.
  std::span<const double> temperature_K;        // heat on
  std::span<const double> peak_temperature_K;   // the run tracks the thermal history
  std::span<const double> time_above_threshold_s;  // the same
  std::span<const std::uint16_t> intact_bonds;  // the simulation has bonds
  std::vector<std::string> material_names;      // index = material
  std::vector<std::string> region_names;        // index = region tag
};

/// The walls at one snapshot: triangles plus per-body values.
struct WallSnapshot {
  double time_s = 0.0;
  std::uint64_t step = 0;
  const WallSurface* surface = nullptr;
  std::vector<std::string> body_names;
  std::vector<double> body_temperature_K;    // NaN: adiabatic (no temperature); empty: heat off
  std::vector<std::uint8_t> body_thermal_mode;  // 0 adiabatic, 1 fixed, 2 lumped; empty: heat off
  std::vector<Vec3> body_force_N;            // reaction of the particles on each body
};

/// The particles as a VtpDocument (points with vertex cells and point data).
VtpDocument particle_document(const ParticleSnapshot& snapshot, const VtpOptions& options);
/// The walls as a VtpDocument (triangles with cell data per body).
VtpDocument wall_document(const WallSnapshot& snapshot, const VtpOptions& options);

class SnapshotSeries {
 public:
  /// Output file names relative to the run's directory, for --overwrite.
  static constexpr const char* particles_collection = "particles.pvd";
  static constexpr const char* walls_collection = "walls.pvd";
  static constexpr const char* data_folder = "vtk";

  /// Creates `directory`/vtk/ (throws std::system_error naming it if it cannot).
  SnapshotSeries(std::filesystem::path directory, VtpOptions options, bool write_walls);

  /// Writes snapshot number count() (particles, and walls when `walls` is given and
  /// the series writes walls) and rewrites the collections.
  void write(const ParticleSnapshot& particles, const WallSnapshot* walls);

  std::size_t count() const { return count_; }
  /// A resumed run: the series as its checkpoint knew it. The next snapshot is number
  /// `count` (files of later numbers are overwritten) and the collections are
  /// rewritten with the entries given.
  void restore(std::size_t count, std::vector<PvdCollection::Entry> particle_entries,
               std::vector<PvdCollection::Entry> wall_entries);
  const PvdCollection& particles() const { return particles_; }
  const PvdCollection& walls() const { return walls_; }

 private:
  std::filesystem::path directory_;
  VtpOptions options_;
  bool write_walls_;
  PvdCollection particles_, walls_;
  std::size_t count_ = 0;
};

}  // namespace regodem
