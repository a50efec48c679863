#pragma once
// The run as a list of stages, each with an end condition and temporary changes of the
// contact properties, plus the insertions that fill the domain during them.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "core/particle_store.hpp"
#include "sim/insertion.hpp"
#include "sim/measurement_plan.hpp"
#include "sim/snapshot_schedule.hpp"

namespace regodem {

/// The most steps one stage may plan: 500x the ~2e9 of the paper's full drilling case
/// (277,300 particles, 200 s), and far below 2^53, where a step count stops being exact
/// in a double and long before a 64-bit counter overflows. The scenario's plan is
/// checked against it when built; a static-bed stage's default step, known only once
/// its bed is, when the stage starts.
inline constexpr double max_steps_per_stage = 1e12;

/// Changes the properties of one material pair (or every pair) while a stage runs.
struct PairOverride {
  int material_a = -1, material_b = -1;  // -1, -1: every pair
  std::optional<double> restitution, sliding_friction, rolling_friction;
};

/// How a stage moves heat (see ThermalStepping in the scenario spec).
enum class HeatStepping { coupled, static_explicit, static_backward_euler, static_crank_nicolson };

/// Bonds formed at a stage's start (Simulation::form_bonds): flags by material index
/// and region tag, empty for all.
struct BondFormation {
  double gap_fraction = 0.0;
  std::vector<char> materials;
  std::vector<char> regions;
};

struct Stage {
  std::string name;
  bool until_settled = false;
  double duration_s = 0.0;                // !until_settled
  double settled_kinetic_energy_J = 0.0;  // until_settled: mean per particle
  double min_duration_s = 0.0;
  double max_duration_s = std::numeric_limits<double>::infinity();
  // Ends when wall body depth_body reaches depth_m (WallBody::depth_m), if >= 0.
  int depth_body = -1;
  double depth_m = 0.0;
  bool ends_at_depth() const { return depth_body >= 0; }
  // Ends when a measurement reaches a value, at most max_duration_s after its start
  // (else the run fails); checked every step of a static-bed stage, every 64 of a coupled one.
  std::optional<MeasurementTarget> until_measured;
  bool ends_on_measurement() const { return until_measured.has_value(); }
  std::vector<PairOverride> overrides;
  // Static-bed stages (anything but coupled) freeze the mechanics: particles and walls
  // stay put and only temperatures advance, with their own step. They end by time or
  // on a measurement.
  HeatStepping heat_stepping = HeatStepping::coupled;
  double thermal_time_step_s = 0.0;  // 0: stability_fraction x the explicit limit
  double stability_fraction = 0.5;
  std::optional<BondFormation> form_bonds;
  bool freezes_mechanics() const { return heat_stepping != HeatStepping::coupled; }
  /// The default heat step of a static-bed stage, in explicit stability limits: the
  /// fraction for explicit stepping; implicit methods are stable at any step and by
  /// default take 10 times that, still resolving the bed's slow, diffusive modes.
  double default_step_in_stability_limits() const {
    return stability_fraction * (heat_stepping == HeatStepping::static_explicit ? 1.0 : 10.0);
  }
};

struct StagePlan {
  std::vector<Stage> stages;
  std::vector<Insertion> insertions;
  double sample_interval_s = 0.0;   // 0: 100 samples per time-limited stage
  SnapshotSchedule snapshots;       // ParaView snapshots; none by default
  MeasurementPlan measurements;     // regions, bands, profiles; none by default
  std::vector<std::string> region_names;  // insertion region tags, index = RegionTag
  std::uint64_t seed = 1;
};

}  // namespace regodem
