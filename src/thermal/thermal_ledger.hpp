#pragma once
// The running energy balance of the heat model (DESIGN.md section 2, "Energy"): the
// thermal energy of particles and lumped walls may change only by heat through fixed
// walls and by the heat generated at contacts (friction or every loss); what insertion brings in is counted in the reference.
namespace regodem {

struct ThermalLedger {
  double reference_energy_J = 0.0;  // energy at the start, plus that of inserted particles
  double boundary_heat_in_J = 0.0;  // through fixed-temperature walls, into the system
  double generated_heat_J = 0.0;     // generated at contacts and bonds (heat.friction_heating / dissipation_heating)

  double expected_energy_J() const { return reference_energy_J + boundary_heat_in_J + generated_heat_J; }
};

}  // namespace regodem
