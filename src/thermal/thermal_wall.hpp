#pragma once
// The thermal side of a wall body (DESIGN.md section 2, "Thermal walls"): adiabatic
// (passes no heat), fixed (a prescribed temperature, constant or over time) or lumped
// (one uniform temperature T_w with m_w C_w dT_w/dt = -sum_i Q_iw). A segmented sieve is
// one wall body per segment, each lumped. A lumped mesh wall (the drill) may instead be
// one body of axial segments that conduct to each other along the rod (WallRod). Kept
// beside WallSet::bodies, index for index.
#include <algorithm>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "thermal/conduction_parameters.hpp"
#include "thermal/time_table.hpp"

namespace regodem {

enum class WallThermalMode : std::uint8_t { adiabatic, fixed, lumped };

/// Which conductivity k_c a particle-wall contact uses.
enum class WallConductivityMix : std::uint8_t {
  wall,           // the wall's own (the sieve's lambda_w); the particle's when the wall gives none
  harmonic_mean,  // 2 k_w k_i / (k_w + k_i)
};

/// A lumped wall's heat paths beyond its contacts (docs/drilling-heat.md, "The drill as a
/// thermal body"): axial segments that conduct to their neighbours, radiation to
/// surroundings, and a held far end. The model side: nothing here changes in a run.
struct WallRod {
  // Axial segments, the first at the tip: each one's m C and surface. Empty: the wall is
  // one node (ThermalWall::heat_capacity_J_per_K, area_m2).
  std::vector<double> segment_heat_capacity_J_per_K;
  std::vector<double> segment_area_m2;
  double area_m2 = 0.0;                    // the one-node wall's surface (radiation)
  double link_conductance_W_per_K = 0.0;   // between neighbouring segments: k A / dz
  double emissivity = 0.0;                 // 0: no radiation
  double surroundings_K = 0.0;             // what the surface radiates to
  std::optional<double> held_end_K;        // the far end (the last node's side), held
  double held_end_conductance_W_per_K = 0.0;  // last node to the held end: k A / (dz / 2)

  bool segmented() const { return !segment_heat_capacity_J_per_K.empty(); }
  bool exchanges() const { return segmented() || emissivity > 0.0 || held_end_K.has_value(); }
};

/// A wall's thermal description: the model side, fixed by the scenario while a run steps
/// (its temperatures and heat books are ThermalWallState).
struct ThermalWall {
  WallThermalMode mode = WallThermalMode::adiabatic;
  double initial_temperature_K = 0.0;           // lumped: every node's at the start
  TimeTable prescribed_temperature_K;           // fixed mode
  double heat_capacity_J_per_K = 0.0;           // lumped: m_w C_w
  std::optional<double> conductivity_W_per_mK;  // none: the particle's own (the paper's k_s)
  WallConductivityMix mix = WallConductivityMix::wall;
  WallRod rod;                                  // lumped only

  /// The nodes a contact can touch: a segmented wall's segments, else the one wall.
  std::size_t node_count() const { return std::max<std::size_t>(1, rod.segment_heat_capacity_J_per_K.size()); }
  std::span<const double> node_heat_capacities_J_per_K() const {
    return rod.segmented() ? std::span<const double>(rod.segment_heat_capacity_J_per_K)
                           : std::span<const double>(&heat_capacity_J_per_K, 1);
  }
  std::span<const double> node_areas_m2() const {
    return rod.segmented() ? std::span<const double>(rod.segment_area_m2) : std::span<const double>(&rod.area_m2, 1);
  }
};

/// A wall's thermal state: its temperatures and heat books, what a checkpoint saves.
struct ThermalWallState {
  double temperature_K = 0.0;  // fixed: follows the table; lumped: its state (segmented: the m C weighted mean)
  std::vector<double> segment_temperature_K;  // a segmented wall's, segment by segment
  // Filled by the simulation.
  double heat_flow_to_particles_W = 0.0;  // last step: sum over contacts of Q from the wall
  double heat_to_particles_J = 0.0;       // cumulative heat conducted into the particles
  double generated_heat_J = 0.0;          // cumulative generated heat the wall received
  double radiated_heat_J = 0.0;           // cumulative heat radiated to the surroundings
  double held_end_heat_in_J = 0.0;        // cumulative heat in through the held end
  double peak_temperature_K = 0.0;        // lumped: the hottest node so far

  /// Where a wall starts: a fixed wall at its table's value at t = 0, a lumped one (every
  /// segment) at its initial temperature.
  static ThermalWallState start(const ThermalWall& wall) {
    ThermalWallState s;
    s.temperature_K = wall.initial_temperature_K;
    if (wall.mode == WallThermalMode::fixed) s.temperature_K = wall.prescribed_temperature_K.at(0.0);
    if (wall.mode == WallThermalMode::lumped) {
      if (wall.rod.segmented())
        s.segment_temperature_K.assign(wall.rod.segment_heat_capacity_J_per_K.size(), wall.initial_temperature_K);
      s.peak_temperature_K = s.temperature_K;
      s.refresh_summary_temperature(wall);
    }
    return s;
  }
  double node_temperature_K(std::size_t node) const {
    return segment_temperature_K.empty() ? temperature_K : segment_temperature_K[node];
  }
  std::span<double> node_temperatures_K() {
    return segment_temperature_K.empty() ? std::span<double>(&temperature_K, 1) : std::span<double>(segment_temperature_K);
  }
  /// Sum of m C T over the nodes (lumped; 0 otherwise): the wall's share of the ledger.
  double stored_heat_J(const ThermalWall& wall) const {
    if (wall.mode != WallThermalMode::lumped) return 0.0;
    if (segment_temperature_K.empty()) return wall.heat_capacity_J_per_K * temperature_K;
    double sum = 0.0;
    for (std::size_t s = 0; s < segment_temperature_K.size(); ++s)
      sum += wall.rod.segment_heat_capacity_J_per_K[s] * segment_temperature_K[s];
    return sum;
  }
  /// temperature_K from the segments (m C weighted), and the peak so far.
  void refresh_summary_temperature(const ThermalWall& wall) {
    if (!segment_temperature_K.empty()) temperature_K = stored_heat_J(wall) / wall.heat_capacity_J_per_K;
    for (double t : node_temperatures_K()) peak_temperature_K = std::max(peak_temperature_K, t);
  }
};

/// What a contact with a wall body needs, taken once per pass: its temperature and
/// how it chooses the contact conductivity k_c.
struct WallContactHeat {
  bool conducts = false;     // fixed or lumped; adiabatic walls pass no heat
  double temperature_K = 0.0;
  double conductivity = -1.0;  // < 0: the particle's own
  bool harmonic = false;

  static WallContactHeat of(const ThermalWall& w, const ThermalWallState& state, std::size_t node = 0) {
    return {w.mode != WallThermalMode::adiabatic, state.node_temperature_K(node),
            w.conductivity_W_per_mK ? *w.conductivity_W_per_mK : -1.0, w.mix == WallConductivityMix::harmonic_mean};
  }
  /// k_c for a particle of conductivity k_particle: the wall's own (the sieve's
  /// lambda_w), the particle's when the wall gives none (the paper's k_s), or the mean.
  double contact_conductivity(double k_particle) const {
    if (conductivity < 0.0) return k_particle;
    return harmonic ? harmonic_mean(conductivity, k_particle) : conductivity;
  }
};

}  // namespace regodem
