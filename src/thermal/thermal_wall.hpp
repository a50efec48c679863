#pragma once
// The thermal side of a wall body (DESIGN.md section 2, "Thermal walls"): adiabatic
// (passes no heat), fixed (a prescribed temperature, constant or over time) or lumped
// (one uniform temperature T_w with m_w C_w dT_w/dt = -sum_i Q_iw). A segmented sieve is
// one wall body per segment, each lumped. Kept beside WallSet::bodies, index for index.
#include <cstdint>
#include <optional>

#include "thermal/conduction_parameters.hpp"
#include "thermal/time_table.hpp"

namespace regodem {

enum class WallThermalMode : std::uint8_t { adiabatic, fixed, lumped };

/// Which conductivity k_c a particle-wall contact uses.
enum class WallConductivityMix : std::uint8_t {
  wall,           // the wall's own (the sieve's lambda_w); the particle's when the wall gives none
  harmonic_mean,  // 2 k_w k_i / (k_w + k_i)
};

struct ThermalWall {
  WallThermalMode mode = WallThermalMode::adiabatic;
  double temperature_K = 0.0;                   // current; fixed: follows the table; lumped: its state
  TimeTable prescribed_temperature_K;           // fixed mode
  double heat_capacity_J_per_K = 0.0;           // lumped: m_w C_w
  std::optional<double> conductivity_W_per_mK;  // none: the particle's own (the paper's k_s)
  WallConductivityMix mix = WallConductivityMix::wall;

  // Filled by the simulation.
  double heat_flow_to_particles_W = 0.0;  // last step: sum over contacts of Q from the wall
  double heat_to_particles_J = 0.0;       // cumulative heat conducted into the particles
  double generated_heat_J = 0.0;           // cumulative generated heat the wall received
};

/// What a contact with a wall body needs, taken once per pass: its temperature and
/// how it chooses the contact conductivity k_c.
struct WallContactHeat {
  bool conducts = false;     // fixed or lumped; adiabatic walls pass no heat
  double temperature_K = 0.0;
  double conductivity = -1.0;  // < 0: the particle's own
  bool harmonic = false;

  static WallContactHeat of(const ThermalWall& w) {
    return {w.mode != WallThermalMode::adiabatic, w.temperature_K,
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
