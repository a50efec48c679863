#include "io/summary_json_writer.hpp"

#include <cmath>

#include "io/atomic_file.hpp"
#include "sim/time_scale.hpp"

namespace regodem {
namespace {

/// JSON has no NaN or infinity; nlohmann would write null for them anyway, but saying
/// so here keeps that decision visible.
nlohmann::ordered_json number_or_null(std::optional<double> value) {
  if (!value || !std::isfinite(*value)) return nullptr;
  return *value;
}

/// A simulated time in real seconds (x S); empty stays empty.
std::optional<double> real_time_s(const TimeScale& scale, std::optional<double> simulated_s) {
  return simulated_s ? std::optional<double>(scale.real_time_s(*simulated_s)) : std::nullopt;
}

nlohmann::ordered_json stage_to_json(const StageSummary& stage, const TimeScale& scale) {
  nlohmann::ordered_json json;
  json["name"] = stage.name;
  json["result"] = stage.result ? std::string(to_string(*stage.result)) : std::string("not started");
  json["start_time_s"] = number_or_null(stage.start_time_s);
  json["end_time_s"] = number_or_null(stage.end_time_s);
  // How long it ran in simulated time: a stage that ended on a measurement gives the
  // time another run must heat for (the matching cell's W0 time).
  const std::optional<double> duration_s =
      stage.end_time_s && stage.start_time_s ? std::optional<double>(*stage.end_time_s - *stage.start_time_s)
                                             : std::nullopt;
  json["duration_s"] = number_or_null(duration_s);
  json["start_time_real_s"] = number_or_null(real_time_s(scale, stage.start_time_s));
  json["end_time_real_s"] = number_or_null(real_time_s(scale, stage.end_time_s));
  json["duration_real_s"] = number_or_null(real_time_s(scale, duration_s));
  json["wall_time_s"] = number_or_null(stage.wall_time_s);
  json["message"] = stage.message;
  return json;
}

/// "temperature_mean" in K -> "temperature_mean_K"; a count ("-") keeps its name.
std::string key_with_unit(const SeriesColumn& column) {
  return column.unit.empty() || column.unit == "-" ? column.name : column.name + "_" + column.unit;
}

/// Counts as whole numbers, the rest as numbers (null for NaN: an empty region).
nlohmann::ordered_json value_to_json(const SeriesColumn& column, double value) {
  if (column.name.starts_with("count") && std::isfinite(value)) return static_cast<std::int64_t>(value);
  return number_or_null(value);
}

/// A region or band: its last row by column. A profile: time (and depth) once, each
/// other column as an array over the bins.
nlohmann::ordered_json measurement_to_json(const MeasurementFinal& m) {
  nlohmann::ordered_json json;
  json["file"] = m.file;
  json["samples"] = m.samples;
  nlohmann::ordered_json last = nullptr;
  if (!m.last_rows.empty()) {
    last = nlohmann::ordered_json::object();
    const bool profile = m.table.kind == "profile";
    for (std::size_t c = 0; c < m.table.columns.size(); ++c) {
      const SeriesColumn& column = m.table.columns[c];
      if (!profile || column.name == "time" || column.name == "real_time" || column.name == "depth") {
        last[key_with_unit(column)] = value_to_json(column, m.last_rows.front()[c]);
        continue;
      }
      nlohmann::ordered_json values = nlohmann::ordered_json::array();
      for (const std::vector<double>& row : m.last_rows) values.push_back(value_to_json(column, row[c]));
      last[key_with_unit(column)] = std::move(values);
    }
  }
  json["final"] = std::move(last);
  return json;
}

nlohmann::ordered_json measurements_to_json(const RunSummary& summary) {
  nlohmann::ordered_json json = nlohmann::ordered_json::object();
  const TimeScale scale{summary.heat.time_scale_factor};
  if (const auto& h = summary.thermal_history)
    json["thermal_history"] = {{"threshold_K", number_or_null(h->threshold_K)},
                               {"particles", h->particles},
                               {"crossed", h->crossed},
                               {"crossed_fraction", number_or_null(h->crossed_fraction)},
                               {"peak_temperature_max_K", number_or_null(h->peak_temperature_max_K)},
                               {"time_above_threshold_mean_s", number_or_null(h->time_above_threshold_mean_s)},
                               {"time_above_threshold_max_s", number_or_null(h->time_above_threshold_max_s)},
                               {"time_above_threshold_mean_real_s",
                                number_or_null(scale.real_time_s(h->time_above_threshold_mean_s))},
                               {"time_above_threshold_max_real_s",
                                number_or_null(scale.real_time_s(h->time_above_threshold_max_s))}};
  for (const char* kind : {"region", "band", "profile"}) {
    nlohmann::ordered_json group = nlohmann::ordered_json::object();
    for (const MeasurementFinal& m : summary.measurements)
      if (m.table.kind == kind) group[m.table.name] = measurement_to_json(m);
    if (!group.empty()) json[std::string(kind) + "s"] = std::move(group);
  }
  return json;
}

}  // namespace

std::string_view to_string(RunStatus status) {
  switch (status) {
    case RunStatus::completed: return "completed";
    case RunStatus::failed: return "failed";
    case RunStatus::interrupted: return "interrupted";
  }
  return "failed";
}

std::string_view to_string(StageResult result) {
  switch (result) {
    case StageResult::finished: return "finished";
    case StageResult::failed: return "failed";
    case StageResult::interrupted: return "interrupted";
  }
  return "failed";
}

nlohmann::ordered_json summary_to_json(const RunSummary& summary) {
  const TimeScale scale{summary.heat.time_scale_factor};
  nlohmann::ordered_json json;
  json["outcome"] = std::string(to_string(summary.status));
  json["message"] = summary.message;
  json["particles"] = summary.particles;
  json["steps"] = summary.steps;
  json["simulated_time_s"] = number_or_null(summary.simulated_time_s);
  json["real_time_s"] = number_or_null(scale.real_time_s(summary.simulated_time_s));  // x S
  json["wall_time_s"] = number_or_null(summary.wall_time_s);
  json["particle_steps_per_s"] = number_or_null(summary.particle_steps_per_s);
  json["time_step_s"] = number_or_null(summary.time_step_s);
  json["threads"] = summary.threads;
  json["mpi_ranks"] = summary.mpi_ranks;
  json["version"] = summary.version;
  json["build_type"] = summary.build_type;
  json["compiler"] = summary.compiler;
  json["started_at_utc"] = summary.started_at_utc;
  json["scenario"] = {{"name", summary.scenario_name},
                      {"file", summary.scenario_file},
                      {"hash", summary.scenario_hash},
                      {"copy", summary.scenario_copy},
                      {"overrides", summary.overrides}};
  json["heat"] = {{"enabled", summary.heat.enabled},
                  {"time_scale_factor", number_or_null(summary.heat.time_scale_factor)},
                  {"friction_heating", summary.heat.friction_heating},
                  {"dissipation_heating", summary.heat.dissipation_heating},
                  {"heat_partition", summary.heat.heat_partition},
                  {"friction_partition", number_or_null(summary.heat.friction_partition)}};
  if (!summary.lumped_walls.empty()) {
    nlohmann::ordered_json walls = nlohmann::ordered_json::object();
    for (const LumpedWallSummary& w : summary.lumped_walls) {
      nlohmann::ordered_json segments = nlohmann::ordered_json::array();
      for (double t : w.segment_temperature_K) segments.push_back(number_or_null(t));
      walls[w.name] = {{"temperature_K", number_or_null(w.temperature_K)},
                       {"peak_temperature_K", number_or_null(w.peak_temperature_K)},
                       {"segment_temperature_K", segments},
                       {"generated_heat_J", number_or_null(w.generated_heat_J)},
                       {"heat_to_particles_J", number_or_null(w.heat_to_particles_J)},
                       {"radiated_heat_J", number_or_null(w.radiated_heat_J)},
                       {"held_end_heat_in_J", number_or_null(w.held_end_heat_in_J)}};
    }
    json["lumped_walls"] = walls;
  }
  if (summary.energy_audit) {
    const EnergyAuditSummary& a = *summary.energy_audit;
    nlohmann::ordered_json by_wall = nlohmann::ordered_json::object();
    for (const auto& [name, work_J] : a.wall_work_by_wall_J) by_wall[name] = number_or_null(work_J);
    json["energy_audit"] = {{"wall_work_J", number_or_null(a.wall_work_J)},
                            {"dissipated_J", number_or_null(a.dissipated_J)},
                            {"spring_source_J", number_or_null(a.spring_source_J)},
                            {"exchanged_J", number_or_null(a.exchanged_J)},
                            {"mechanical_energy_J", number_or_null(a.mechanical_energy_J)},
                            {"imbalance_J", number_or_null(a.imbalance_J)},
                            {"relative_imbalance", number_or_null(a.relative_imbalance)},
                            {"wall_work_by_wall_J", by_wall}};
  }
  if (summary.fastest_impact) {
    const ImpactSummary& i = *summary.fastest_impact;
    json["fastest_impact"] = {{"approach_speed_m_per_s", number_or_null(i.approach_speed_m_per_s)},
                              {"contact_time_s", number_or_null(i.contact_time_s)},
                              {"contact_steps", number_or_null(i.contact_steps)},
                              {"wall", i.wall.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(i.wall)},
                              {"time_s", number_or_null(i.time_s)}};
  }
  if (summary.bonds)
    json["bonds"] = {{"formed", summary.bonds->formed},
                     {"intact", summary.bonds->intact},
                     {"broken", summary.bonds->broken_in_tension + summary.bonds->broken_in_shear},
                     {"broken_in_tension", summary.bonds->broken_in_tension},
                     {"broken_in_shear", summary.bonds->broken_in_shear}};
  if (summary.thermal_history || !summary.measurements.empty()) json["measurements"] = measurements_to_json(summary);
  json["stages"] = nlohmann::ordered_json::array();
  for (const StageSummary& stage : summary.stages) json["stages"].push_back(stage_to_json(stage, scale));
  json["notices"] = summary.notices;
  return json;
}

void write_summary_json(const std::filesystem::path& path, const RunSummary& summary) {
  write_file_atomically(path, summary_to_json(summary).dump(2) + "\n");
}

}  // namespace regodem
