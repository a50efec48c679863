#include "io/snapshot_series.hpp"

#include <system_error>

#include <fmt/format.h>

namespace regodem {
namespace {

void add_time_fields(VtpDocument& document, double time_s, std::uint64_t step) {
  // "TimeValue" is the name ParaView reads as a data set's time when opened alone.
  const double time[1] = {time_s};
  const double steps[1] = {static_cast<double>(step)};
  document.add_field_data("TimeValue", time);
  document.add_field_data("step", steps);
}

void check_particle_lengths(const ParticleSnapshot& s) {
  const std::size_t n = s.position_m.size();
  const auto check = [n](std::size_t size, const char* name, bool optional) {
    if (size != n && !(optional && size == 0))
      throw std::invalid_argument(fmt::format("particle snapshot: '{}' has {} values for {} particles", name, size, n));
  };
  check(s.id.size(), "id", false);
  check(s.radius_m.size(), "radius", false);
  check(s.velocity_m_per_s.size(), "velocity", false);
  check(s.angular_velocity_rad_per_s.size(), "angular_velocity", false);
  check(s.material.size(), "material", false);
  check(s.region.size(), "region", false);
  check(s.contacts.size(), "contacts", false);
  check(s.temperature_K.size(), "temperature", true);
  check(s.peak_temperature_K.size(), "peak_temperature", true);
  check(s.time_above_threshold_s.size(), "time_above_threshold", true);
  check(s.intact_bonds.size(), "intact_bonds", true);
}

}  // namespace

VtpDocument particle_document(const ParticleSnapshot& s, const VtpOptions& options) {
  check_particle_lengths(s);
  VtpDocument document(options);
  add_time_fields(document, s.time_s, s.step);
  if (!s.material_names.empty()) document.add_field_strings("material_names", s.material_names);
  if (!s.region_names.empty()) document.add_field_strings("region_names", s.region_names);
  document.set_points(s.position_m);
  document.add_vertex_per_point();
  document.add_point_data("id", s.id);
  document.add_point_data("radius", s.radius_m);
  if (!s.temperature_K.empty()) document.add_point_data("temperature", s.temperature_K);
  if (!s.peak_temperature_K.empty()) document.add_point_data("peak_temperature", s.peak_temperature_K);
  if (!s.time_above_threshold_s.empty()) document.add_point_data("time_above_threshold", s.time_above_threshold_s);
  document.add_point_data("velocity", s.velocity_m_per_s);
  document.add_point_data("angular_velocity", s.angular_velocity_rad_per_s);
  document.add_point_data("material", s.material);
  document.add_point_data("region", s.region);
  document.add_point_data("contacts", s.contacts);
  if (!s.intact_bonds.empty()) document.add_point_data("intact_bonds", s.intact_bonds);
  return document;
}

VtpDocument wall_document(const WallSnapshot& s, const VtpOptions& options) {
  if (s.surface == nullptr) throw std::invalid_argument("wall snapshot without a surface");
  const WallSurface& surface = *s.surface;
  const std::size_t bodies = s.body_names.size();
  if (s.body_force_N.size() != bodies || (!s.body_temperature_K.empty() && s.body_temperature_K.size() != bodies) ||
      s.body_thermal_mode.size() != s.body_temperature_K.size())
    throw std::invalid_argument("wall snapshot: per-body arrays of different lengths");
  for (const std::uint32_t b : surface.body)
    if (b >= bodies) throw std::invalid_argument(fmt::format("wall snapshot: triangle of body {} of {}", b, bodies));

  VtpDocument document(options);
  add_time_fields(document, s.time_s, s.step);
  document.add_field_strings("wall_names", s.body_names);
  document.set_points(surface.points_m);
  document.set_triangles(surface.triangles);
  // Per-body values spread to the body's triangles: ParaView colours cells directly.
  const std::size_t n = surface.triangles.size();
  document.add_cell_data("wall", surface.body);
  std::vector<Vec3> force(n);
  for (std::size_t t = 0; t < n; ++t) force[t] = s.body_force_N[surface.body[t]];
  document.add_cell_data("force", force);
  if (!s.body_temperature_K.empty()) {
    std::vector<double> temperature(n);
    std::vector<std::uint8_t> mode(n);
    for (std::size_t t = 0; t < n; ++t) {
      temperature[t] = s.body_temperature_K[surface.body[t]];
      mode[t] = s.body_thermal_mode[surface.body[t]];
    }
    document.add_cell_data("temperature", temperature);
    document.add_cell_data("thermal_mode", mode);
  }
  return document;
}

SnapshotSeries::SnapshotSeries(std::filesystem::path directory, VtpOptions options, bool write_walls)
    : directory_(std::move(directory)),
      options_(options),
      write_walls_(write_walls),
      particles_(directory_ / particles_collection),
      walls_(directory_ / walls_collection) {
  std::error_code error;
  std::filesystem::create_directories(directory_ / data_folder, error);
  if (error)
    throw std::system_error(error, fmt::format("cannot create '{}'", (directory_ / data_folder).string()));
}

void SnapshotSeries::restore(std::size_t count, std::vector<PvdCollection::Entry> particle_entries,
                             std::vector<PvdCollection::Entry> wall_entries) {
  count_ = count;
  particles_.restore(std::move(particle_entries));
  if (write_walls_) walls_.restore(std::move(wall_entries));
}

void SnapshotSeries::write(const ParticleSnapshot& particles, const WallSnapshot* walls) {
  const std::string particle_file = fmt::format("{}/particles_{:06d}.vtp", data_folder, count_);
  write_vtp(directory_ / particle_file, particle_document(particles, options_));
  particles_.add(particles.time_s, particle_file);
  if (write_walls_ && walls != nullptr) {
    const std::string wall_file = fmt::format("{}/walls_{:06d}.vtp", data_folder, count_);
    write_vtp(directory_ / wall_file, wall_document(*walls, options_));
    walls_.add(walls->time_s, wall_file);
  }
  ++count_;
}

}  // namespace regodem
