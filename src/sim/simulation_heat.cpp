// The heat side of the Simulation (DESIGN.md section 2, "Conduction", "Thermal walls",
// "Energy"): temperature updates after the contact pass, the energy ledger, and the
// frozen conductance network that static-bed stages step on their own.
#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <omp.h>

#include <cmath>

#include "contact/hertz_normal.hpp"
#include "core/error.hpp"
#include "measure/thermal_history.hpp"
#include "sim/contact_walk.hpp"
#include "sim/simulation.hpp"
#include "thermal/lumped_wall_step.hpp"
#include "thermal/static_bed_solver.hpp"

namespace regodem {

double Simulation::particle_thermal_energy_J(std::size_t i) const {
  const TemperatureCurve& c = model_.materials[particles.material[i]].specific_heat_J_per_kgK;
  return particles.mass_kg[i] * c.integral_from_zero(particles.temperature_K[i]);
}

double Simulation::thermal_energy_J() const {
  ExactSum own;
  for (std::size_t i = 0; i < particles.size(); ++i)
    if (!is_ghost(i)) own += particle_thermal_energy_J(i);
  double sum = total_over_ranks(own);
  for (std::size_t b = 0; b < wall_thermal_state.size(); ++b)  // the same on every rank
    sum += wall_thermal_state[b].stored_heat_J(model_.wall_thermal[b]);
  return sum;
}

void Simulation::set_particle_temperature_K(std::size_t i, double temperature_K) {
  if (!heat_enabled())
    throw InputError(fmt::format("particle {}: the run has no heat (heat.enabled), so no temperature to set",
                                 particles.id[i]));
  if (!(temperature_K > 0.0) || !std::isfinite(temperature_K))
    throw InputError(fmt::format("particle {}: a temperature must be above 0 K, got {} K", particles.id[i],
                                 temperature_K));
  const double before_J = particle_thermal_energy_J(i);
  particles.temperature_K[i] = temperature_K;
  particles.conductivity_W_per_mK[i] = model_.materials[particles.material[i]].conductivity_W_per_mK.at(temperature_K);
  if (i < particles.peak_temperature_K.size())
    particles.peak_temperature_K[i] = std::max(particles.peak_temperature_K[i], temperature_K);
  ledger_.reference_energy_J += particle_thermal_energy_J(i) - before_J;
}

void Simulation::refresh_conductivities() {
  for (std::size_t i = 0; i < particles.size(); ++i)
    particles.conductivity_W_per_mK[i] =
        model_.materials[particles.material[i]].conductivity_W_per_mK.at(particles.temperature_K[i]);
}

void Simulation::fill_partition_weights() {
  const std::size_t n = particles.size();
  partition_weight_.resize(n);
  const HeatPartitionModel model = model_.settings.heat.partition;
#pragma omp parallel for schedule(static) num_threads(model_.settings.threads) if (n > 4096)
  for (std::size_t i = 0; i < n; ++i) {
    const Material& m = model_.materials[particles.material[i]];
    const double c = model == HeatPartitionModel::effusivity ? m.specific_heat_J_per_kgK.at(particles.temperature_K[i]) : 0.0;
    partition_weight_[i] = heat_partition_weight(model, particles.conductivity_W_per_mK[i], m.density_kg_per_m3, c);
  }
}

double Simulation::wall_partition_weight(const WallContactHeat& wall, MaterialIndex wall_material) const {
  const Material& m = model_.materials[wall_material];
  // The bulk's conductivity: the material's, else the wall's own contact conductivity.
  const double material_k = m.conductivity_W_per_mK.at(wall.temperature_K);
  const double k = material_k > 0.0 || wall.conductivity < 0.0 ? material_k : wall.conductivity;
  return heat_partition_weight(model_.settings.heat.partition, k, m.density_kg_per_m3,
                               m.specific_heat_J_per_kgK.at(wall.temperature_K));
}

void Simulation::update_temperatures(double dt_s) {
  const double* __restrict inv_specific_heat = model_.inv_specific_heat.data();
  const char* __restrict conductivity_varies = model_.conductivity_varies.data();
  const std::size_t n = particles.size();
  double* __restrict temperature = particles.temperature_K.data();
  double* __restrict conductivity = particles.conductivity_W_per_mK.data();
  const double* __restrict heat = particles.heat_flow_W.data();
  const double* __restrict mass = particles.mass_kg.data();
  const MaterialIndex* __restrict material = particles.material.data();
  // The thermal history rides on this pass (the temperatures are in cache here): two
  // more arrays streamed, and only when a scenario asks for it.
  const bool track = model_.settings.heat.track_thermal_history;
  const double threshold_K = model_.settings.heat.thermal_history_threshold_K;
  double* __restrict peak = particles.peak_temperature_K.data();
  double* __restrict time_above = particles.time_above_threshold_s.data();
#pragma omp parallel for schedule(static) num_threads(model_.settings.threads) if (n > 2048)
  for (std::size_t i = 0; i < n; ++i) {
    const MaterialIndex m = material[i];
    const double energy_per_mass = heat[i] * dt_s / mass[i];
    const double old_K = temperature[i];
    if (inv_specific_heat[m] > 0.0) {
      temperature[i] += energy_per_mass * inv_specific_heat[m];
    } else {
      const TemperatureCurve& c = model_.materials[m].specific_heat_J_per_kgK;
      temperature[i] = c.inverse_integral(c.integral_from_zero(temperature[i]) + energy_per_mass);
    }
    if (conductivity_varies[m]) conductivity[i] = model_.materials[m].conductivity_W_per_mK.at(temperature[i]);
    if (track) record_thermal_history(old_K, temperature[i], dt_s, threshold_K, peak[i], time_above[i]);
  }

  for (std::size_t b = 0; b < wall_thermal_state.size(); ++b) {
    const ThermalWall& wall = model_.wall_thermal[b];
    ThermalWallState& w = wall_thermal_state[b];
    const double generated_W = wall_generated_heat_W_[b];
    const double into_wall_W = -w.heat_flow_to_particles_W + generated_W;
    w.heat_to_particles_J += w.heat_flow_to_particles_W * dt_s;
    w.generated_heat_J += generated_W * dt_s;
    switch (wall.mode) {
      case WallThermalMode::adiabatic: break;
      case WallThermalMode::lumped: {
        // Its nodes take their contacts' heat, and the rod's own exchanges (lumped_wall_step.hpp).
        const std::span<const double> contact_heat_W(node_heat_in_W_.data() + wall_node_begin_[b],
                                                     wall_node_begin_[b + 1] - wall_node_begin_[b]);
        const WallBoundaryHeat out =
            step_lumped_wall(w.node_temperatures_K(), wall.node_heat_capacities_J_per_K(), wall.node_areas_m2(),
                             contact_heat_W, wall.rod, dt_s, model_.settings.heat.time_scale_factor);
        w.radiated_heat_J += out.radiated_J;
        w.held_end_heat_in_J += out.held_end_in_J;
        ledger_.boundary_heat_in_J += out.held_end_in_J - out.radiated_J;
        w.refresh_summary_temperature(wall);
        break;
      }
      case WallThermalMode::fixed:
        // Heat a fixed wall takes leaves the system (the wall is a reservoir).
        ledger_.boundary_heat_in_J -= into_wall_W * dt_s;
        w.temperature_K = wall.prescribed_temperature_K.at(time_s_);
        break;
    }
  }
  ledger_.generated_heat_J += generated_heat_W_ * dt_s;
}

ThermalNetwork Simulation::thermal_network(std::vector<int>& wall_node, std::vector<int>& wall_boundary) {
  ensure_forces();  // current neighbour lists
  ThermalNetwork net;
  const std::size_t n = particles.size();
  net.heat_capacity_J_per_K.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    net.heat_capacity_J_per_K[i] =
        particles.mass_kg[i] *
        model_.materials[particles.material[i]].specific_heat_J_per_kgK.at(particles.temperature_K[i]);
  const std::vector<ThermalWall>& wall_thermal = model_.wall_thermal;
  wall_node.assign(wall_thermal.size(), -1);
  wall_boundary.assign(wall_thermal.size(), -1);
  for (std::size_t b = 0; b < wall_thermal.size(); ++b) {
    if (wall_thermal[b].mode == WallThermalMode::lumped) {
      wall_node[b] = static_cast<int>(net.heat_capacity_J_per_K.size());
      net.heat_capacity_J_per_K.push_back(wall_thermal[b].heat_capacity_J_per_K);
    } else if (wall_thermal[b].mode == WallThermalMode::fixed) {
      wall_boundary[b] = static_cast<int>(net.boundary_count++);
    }
  }
  // The same contacts (ContactWalk) and conductances as the coupled contact pass: a = sqrt(R* delta_n).
  const ContactWalk walk(particles, neighbors_, walls);
  MeshTouchFinder finder;
  std::vector<MeshTouch> touches;
  for (std::uint32_t i = 0; i < n; ++i) {
    const double ri = particles.radius_m[i];
    const MaterialIndex mi = particles.material[i];
    const double ki = particles.conductivity_W_per_mK[i];
    walk.pairs(i, [&](std::uint32_t, const ContactWalk::ListedPair& pair) {
      const std::uint32_t j = pair.j;
      const double a = HertzNormal::contact_radius_m(ri * pair.radius_j_m / pair.radius_sum_m,
                                                     pair.radius_sum_m - std::sqrt(pair.distance2_m2));
      const ConductionPairParameters& pair_heat = model_.conduction(mi, particles.material[j]);
      const double g = contact_conductance_W_per_K(
          pair_heat, pair_heat.pair_conductivity(ki, particles.conductivity_W_per_mK[j]), a);
      if (g > 0.0) net.edges.push_back({i, j, g});
    });
    walk.walls(i, finder, touches, [&](const WallTouch& touch) {
      const WallContactHeat wh = WallContactHeat::of(wall_thermal[touch.body], wall_thermal_state[touch.body]);
      if (!wh.conducts) return;
      const double a = HertzNormal::contact_radius_m(ri, ri - touch.distance_m);
      const double g =
          contact_conductance_W_per_K(model_.conduction(mi, touch.material), wh.contact_conductivity(ki), a);
      if (!(g > 0.0)) return;  // nor a NaN one (a blown-up state)
      if (wall_node[touch.body] >= 0)
        net.edges.push_back({i, static_cast<std::uint32_t>(wall_node[touch.body]), g});
      else
        net.boundary_links.push_back({i, static_cast<std::uint32_t>(wall_boundary[touch.body]), g});
    });
  }
  return net;
}

double Simulation::thermal_stability_limit_s() {
  std::vector<int> wall_node, wall_boundary;
  ThermalNetwork network = thermal_network(wall_node, wall_boundary);
  if (!halo_) return StaticBedSolver(StaticBedMethod::explicit_euler, std::move(network)).stability_limit_s();
  // Split over ranks: min C / sum G over the nodes (StaticBedSolver::stability_limit_s).
  // An own particle's every contact is listed here, so its sum is whole; a ghost's is a
  // share (its own rank has the whole, and ghosts carry no heat capacity); a lumped
  // wall's is this rank's share of its contacts, summed over the ranks.
  std::vector<double> g(network.heat_capacity_J_per_K.size(), 0.0);
  for (const ThermalNetwork::Edge& e : network.edges) {
    g[e.a] += e.conductance_W_per_K;
    g[e.b] += e.conductance_W_per_K;
  }
  for (const ThermalNetwork::BoundaryLink& link : network.boundary_links) g[link.node] += link.conductance_W_per_K;
  double limit_s = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < particles.size(); ++i)
    if (!is_ghost(i) && g[i] > 0.0) limit_s = std::min(limit_s, network.heat_capacity_J_per_K[i] / g[i]);
  std::vector<double> wall_g;
  for (const int node : wall_node)
    if (node >= 0) wall_g.push_back(g[static_cast<std::size_t>(node)]);
  halo_->sum_in_rank_order(wall_g);
  for (std::size_t b = 0, k = 0; b < wall_node.size(); ++b) {
    if (wall_node[b] < 0) continue;
    const double wall_sum = wall_g[k++];
    if (wall_sum > 0.0)
      limit_s = std::min(limit_s, network.heat_capacity_J_per_K[static_cast<std::size_t>(wall_node[b])] / wall_sum);
  }
  return -largest_over_ranks(-limit_s);
}

void Simulation::advance_frozen(double dt_s, const std::vector<double>& boundary_heat_in_by_body_J) {
  time_s_ += dt_s;
  for (std::size_t b = 0; b < wall_thermal_state.size(); ++b) {
    const ThermalWall& wall = model_.wall_thermal[b];
    if (wall.mode != WallThermalMode::fixed) continue;
    ThermalWallState& w = wall_thermal_state[b];
    const double heat_J = b < boundary_heat_in_by_body_J.size() ? boundary_heat_in_by_body_J[b] : 0.0;
    ledger_.boundary_heat_in_J += heat_J;
    w.heat_to_particles_J += heat_J;
    w.heat_flow_to_particles_W = heat_J / dt_s;
    w.temperature_K = wall.prescribed_temperature_K.at(time_s_);
  }
}

}  // namespace regodem
