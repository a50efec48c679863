#pragma once
// summary.json: what a run did, how fast, with what build and scenario, so that runs
// can be compared and reproduced. Written whole (atomic_file) at the end of a run.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "sim/run_observer.hpp"

namespace regodem {

enum class RunStatus { completed, failed, interrupted };

/// "completed", "failed", "interrupted".
std::string_view to_string(RunStatus status);
/// "finished", "failed", "interrupted".
std::string_view to_string(StageResult result);

struct StageSummary {
  std::string name;
  std::optional<StageResult> result;  // empty: the stage never started ("not started")
  std::optional<double> start_time_s;
  std::optional<double> end_time_s;
  std::optional<double> wall_time_s;
  std::string message;  // why it failed or was interrupted
};

/// Heat transfer settings of the run (DESIGN.md section 2): S must be known to read
/// the run's times as physical heating times.
struct HeatSummary {
  bool enabled = false;
  double time_scale_factor = 1.0;
  bool friction_heating = false;
  bool dissipation_heating = false;
  std::string heat_partition = "fixed";
  double friction_partition = 0.5;
};


/// The mechanical energy books at the end (sim/energy_audit.hpp; docs/physics.md, "Energy audit").
struct EnergyAuditSummary {
  double wall_work_J = 0.0, dissipated_J = 0.0, spring_source_J = 0.0, exchanged_J = 0.0;
  double mechanical_energy_J = 0.0;  // kinetic + potential + elastic, now
  double imbalance_J = 0.0;          // mechanical energy less what the books expect
  double relative_imbalance = 0.0;   // over |wall work| + dissipated (0 when both are 0)
  std::vector<std::pair<std::string, double>> wall_work_by_wall_J;  // moving walls
};

/// The run's fastest impact against its step (sim/impact_record.hpp).
struct ImpactSummary {
  double approach_speed_m_per_s = 0.0;
  double contact_time_s = 0.0;  // its Hertz contact at that speed
  double contact_steps = 0.0;   // the same over the step
  std::string wall;             // the wall it struck; empty: two particles
  double time_s = 0.0;
};

/// A lumped wall at the end (a drill as a thermal body, docs/drilling-heat.md): its
/// temperatures and where its heat went, cumulative.
struct LumpedWallSummary {
  std::string name;
  double temperature_K = 0.0, peak_temperature_K = 0.0;
  std::vector<double> segment_temperature_K;  // 1 at the tip; empty: one node
  double generated_heat_J = 0.0, heat_to_particles_J = 0.0, radiated_heat_J = 0.0, held_end_heat_in_J = 0.0;
};

/// Parallel bonds of the run (present when the scenario has a `bonds` section).
struct BondSummary {
  std::uint64_t formed = 0, intact = 0, broken_in_tension = 0, broken_in_shear = 0;
};

/// The per-particle thermal history at the end of the run (measurements.thermal_history).
struct ThermalHistoryFinal {
  double threshold_K = 0.0;
  std::size_t particles = 0, crossed = 0;
  double crossed_fraction = 0.0;
  double peak_temperature_max_K = 0.0;
  double time_above_threshold_mean_s = 0.0, time_above_threshold_max_s = 0.0;
};

/// A measurement's table and its last sample (one row; one per bin for a profile).
struct MeasurementFinal {
  MeasurementTable table;
  std::string file;  // relative to the output directory
  std::size_t samples = 0;
  std::vector<std::vector<double>> last_rows;
};

struct RunSummary {
  RunStatus status = RunStatus::failed;
  std::string message;
  std::size_t particles = 0;
  std::uint64_t steps = 0;
  double simulated_time_s = 0.0;
  double wall_time_s = 0.0;
  double particle_steps_per_s = 0.0;
  double time_step_s = 0.0;
  int threads = 1;    // OpenMP threads of each process
  int mpi_ranks = 1;  // the processes a run over MPI is split over
  std::string version;
  std::string build_type;
  std::string compiler;
  std::string started_at_utc;  // ISO 8601
  std::optional<EnergyAuditSummary> energy_audit;  // when the run kept the books
  std::optional<ImpactSummary> fastest_impact;     // when any contact closed
  std::string scenario_name;
  std::string scenario_file;        // as given on the command line
  std::string scenario_hash;
  std::string scenario_copy;        // file name of the copy in the output directory
  std::vector<std::string> overrides;  // --set key.path=value, in the order applied
  HeatSummary heat;
  std::vector<LumpedWallSummary> lumped_walls;
  std::optional<BondSummary> bonds;
  std::optional<ThermalHistoryFinal> thermal_history;
  std::vector<MeasurementFinal> measurements;
  std::vector<StageSummary> stages;
  std::vector<std::string> notices;  // what the run told the user (a full insertion region...)
};

/// The summary as JSON, keys in a fixed, readable order. Times absent (a stage never
/// reached) and non-finite numbers become null.
nlohmann::ordered_json summary_to_json(const RunSummary& summary);

/// Writes summary_to_json, indented, to `path` atomically.
void write_summary_json(const std::filesystem::path& path, const RunSummary& summary);

}  // namespace regodem
