#include "sim/static_heat_stepper.hpp"

#include <fmt/format.h>

#include "core/error.hpp"
#include "measure/thermal_history.hpp"
#include "sim/simulation.hpp"

namespace regodem {
namespace {

StaticBedMethod method_of(HeatStepping stepping) {
  switch (stepping) {
    case HeatStepping::static_backward_euler: return StaticBedMethod::backward_euler;
    case HeatStepping::static_crank_nicolson: return StaticBedMethod::crank_nicolson;
    default: return StaticBedMethod::explicit_euler;
  }
}

ThermalNetwork network_of(Simulation& sim, std::vector<int>& wall_node, std::vector<int>& wall_boundary) {
  return sim.thermal_network(wall_node, wall_boundary);
}

}  // namespace

StaticHeatStepper::StaticHeatStepper(Simulation& sim, const Stage& stage)
    : sim_(sim), solver_(method_of(stage.heat_stepping), network_of(sim, wall_node_, wall_boundary_)) {
  stability_limit_s_ = solver_.stability_limit_s();
  const bool is_explicit = stage.heat_stepping == HeatStepping::static_explicit;
  if (stage.thermal_time_step_s > 0.0) {
    time_step_s_ = stage.thermal_time_step_s;
    if (is_explicit && time_step_s_ > stability_limit_s_)
      throw InputError(fmt::format(
          "stage '{}': thermal_time_step {:.4g} s is above the explicit stability limit {:.4g} s "
          "(min m c / sum G over the bed); use at most that, or an implicit heat_stepping",
          stage.name, time_step_s_, stability_limit_s_));
  } else {
    time_step_s_ = stage.default_step_in_stability_limits() * stability_limit_s_;
  }
  if (!std::isfinite(time_step_s_)) time_step_s_ = stage.duration_s > 0.0 ? stage.duration_s : 1.0;  // nothing conducts
  for (std::size_t m = 0; m < sim.model().materials.size(); ++m) {
    const Material& mat = sim.model().materials[static_cast<MaterialIndex>(m)];
    specific_heat_varies_ = specific_heat_varies_ || !mat.specific_heat_J_per_kgK.is_constant();
    properties_vary_ = properties_vary_ || specific_heat_varies_ || !mat.conductivity_W_per_mK.is_constant();
  }
}

void StaticHeatStepper::refresh_values() {
  std::vector<int> wall_node, wall_boundary;
  const ThermalNetwork net = sim_.thermal_network(wall_node, wall_boundary);
  std::vector<double> edge_g(net.edges.size()), link_g(net.boundary_links.size());
  for (std::size_t e = 0; e < net.edges.size(); ++e) edge_g[e] = net.edges[e].conductance_W_per_K;
  for (std::size_t l = 0; l < net.boundary_links.size(); ++l) link_g[l] = net.boundary_links[l].conductance_W_per_K;
  solver_.update_values(net.heat_capacity_J_per_K, edge_g, link_g);
}

void StaticHeatStepper::add_energy_to_enthalpy() {
  // The solve's C_i (T_i^{n+1} - T_i^n) is the energy node i took in the step, and these
  // sum to the heat through the fixed walls. With C_i = m_i c(T_i^n) frozen over the step,
  // reading T^{n+1} off the linear solve would let sum m h(T) drift by ~ m c' dT^2 / 2 a
  // step; adding the energy to the enthalpy, T = h^-1(h(T^n) + C_i dT_i / m_i), keeps it
  // exactly, as the coupled update does. Lumped walls have a constant C_w: nothing to do.
  const ParticleStore& p = sim_.particles;
  const std::vector<double>& capacity_J_per_K = solver_.network().heat_capacity_J_per_K;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const TemperatureCurve& c = sim_.model().materials[p.material[i]].specific_heat_J_per_kgK;
    if (c.is_constant()) continue;  // C is exact: the solve's temperature already conserves energy
    const double energy_per_mass = capacity_J_per_K[i] * (node_temperature_K_[i] - p.temperature_K[i]) / p.mass_kg[i];
    node_temperature_K_[i] = c.inverse_integral(c.integral_from_zero(p.temperature_K[i]) + energy_per_mass);
  }
}

void StaticHeatStepper::advance(double dt_s) {
  const std::size_t n = sim_.particles.size();
  const std::vector<ThermalWall>& walls = sim_.model().wall_thermal;
  const std::size_t n_bodies = walls.size();
  node_temperature_K_.assign(sim_.particles.temperature_K.begin(), sim_.particles.temperature_K.end());
  node_temperature_K_.resize(solver_.network().node_count());
  boundary_start_K_.assign(solver_.network().boundary_count, 0.0);
  boundary_end_K_.assign(solver_.network().boundary_count, 0.0);
  for (std::size_t b = 0; b < n_bodies; ++b) {
    const ThermalWall& w = walls[b];
    if (wall_node_[b] >= 0)
      node_temperature_K_[static_cast<std::size_t>(wall_node_[b])] = sim_.wall_thermal_state[b].temperature_K;
    if (wall_boundary_[b] >= 0) {
      boundary_start_K_[static_cast<std::size_t>(wall_boundary_[b])] = w.prescribed_temperature_K.at(sim_.time_s());
      boundary_end_K_[static_cast<std::size_t>(wall_boundary_[b])] =
          w.prescribed_temperature_K.at(sim_.time_s() + dt_s);
    }
  }
  const StaticStepReport report = solver_.step(dt_s, node_temperature_K_, boundary_start_K_, boundary_end_K_);
  if (specific_heat_varies_) add_energy_to_enthalpy();

  if (const HeatSettings& heat = sim_.settings().heat; heat.track_thermal_history) {
    ParticleStore& p = sim_.particles;
    for (std::size_t i = 0; i < n; ++i)
      record_thermal_history(p.temperature_K[i], node_temperature_K_[i], dt_s, heat.thermal_history_threshold_K,
                             p.peak_temperature_K[i], p.time_above_threshold_s[i]);
  }
  std::copy(node_temperature_K_.begin(), node_temperature_K_.begin() + static_cast<std::ptrdiff_t>(n),
            sim_.particles.temperature_K.begin());
  boundary_heat_by_body_J_.assign(n_bodies, 0.0);
  for (std::size_t b = 0; b < n_bodies; ++b) {
    ThermalWallState& w = sim_.wall_thermal_state[b];
    if (wall_node_[b] >= 0) {
      const double new_temperature = node_temperature_K_[static_cast<std::size_t>(wall_node_[b])];
      w.heat_flow_to_particles_W = -walls[b].heat_capacity_J_per_K * (new_temperature - w.temperature_K) / dt_s;
      w.heat_to_particles_J += w.heat_flow_to_particles_W * dt_s;
      w.temperature_K = new_temperature;
    }
    if (wall_boundary_[b] >= 0)
      boundary_heat_by_body_J_[b] = report.heat_from_boundary_J[static_cast<std::size_t>(wall_boundary_[b])];
  }
  sim_.advance_frozen(dt_s, boundary_heat_by_body_J_);
  if (properties_vary_) {
    sim_.refresh_conductivities();
    refresh_values();
  }
}

}  // namespace regodem
