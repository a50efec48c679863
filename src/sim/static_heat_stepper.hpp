#pragma once
// Heat on a frozen bed (DESIGN.md section 2, "Thermal stepping"): while a stage freezes
// the mechanics, the contact network and its conductances are taken once and the
// temperatures advance with their own, much larger step — explicit at a fraction of
// the stability limit, or implicit (backward Euler, Crank-Nicolson). The paper's
// matching cell (~1e5 particles heated ~1e3 s, ~5e9 mechanical steps) takes minutes.
// Where c varies, the solve's energy increments go into the enthalpy h(T), as in the
// coupled update, so the energy ledger closes however c varies.
#include <vector>

#include "sim/stage_plan.hpp"
#include "thermal/static_bed_solver.hpp"

namespace regodem {

class Simulation;

class StaticHeatStepper {
 public:
  /// Takes the network of the current contacts. Throws InputError for an explicit
  /// stage whose thermal_time_step exceeds the stability limit.
  StaticHeatStepper(Simulation& sim, const Stage& stage);

  double time_step_s() const { return time_step_s_; }
  double stability_limit_s() const { return stability_limit_s_; }
  /// Advances temperatures and the clock by dt_s (at most time_step_s()).
  void advance(double dt_s);

 private:
  void refresh_values();
  void add_energy_to_enthalpy();

  Simulation& sim_;
  std::vector<int> wall_node_, wall_boundary_;
  StaticBedSolver solver_;
  double time_step_s_ = 0.0;
  double stability_limit_s_ = 0.0;
  bool properties_vary_ = false;       // a table over temperature: refresh C and G each step
  bool specific_heat_varies_ = false;  // c(T): new temperatures through the enthalpy
  std::vector<double> node_temperature_K_, boundary_start_K_, boundary_end_K_, boundary_heat_by_body_J_;
};

}  // namespace regodem
