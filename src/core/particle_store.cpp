#include "core/particle_store.hpp"

#include <numbers>

namespace regodem {

std::size_t ParticleStore::add(const NewParticle& p) {
  const double volume = 4.0 / 3.0 * std::numbers::pi * p.radius_m * p.radius_m * p.radius_m;
  const double mass = p.density_kg_per_m3 * volume;
  const double inertia = 0.4 * mass * p.radius_m * p.radius_m;  // solid sphere
  id.push_back(next_id_++);
  radius_m.push_back(p.radius_m);
  mass_kg.push_back(mass);
  inv_mass_per_kg.push_back(1.0 / mass);
  inv_inertia.push_back(1.0 / inertia);
  position_m.push_back(p.position_m);
  velocity_m_per_s.push_back(p.velocity_m_per_s);
  angular_velocity_rad_per_s.push_back(p.angular_velocity_rad_per_s);
  force_N.push_back({});
  torque_N_m.push_back({});
  material.push_back(p.material);
  region.push_back(p.region);
  temperature_K.push_back(p.temperature_K);
  heat_flow_W.push_back(0.0);
  conductivity_W_per_mK.push_back(0.0);  // set by the simulation from the material
  peak_temperature_K.push_back(p.temperature_K);
  time_above_threshold_s.push_back(0.0);
  return id.size() - 1;
}

void ParticleStore::permute(const std::vector<std::uint32_t>& order, int threads) {
  const std::size_t n = order.size();
  for_each_field([&](auto& field) {
    std::remove_reference_t<decltype(field)> sorted(field.size());
#pragma omp parallel for schedule(static) num_threads(threads) if (n > 4096)
    for (std::size_t k = 0; k < n; ++k) sorted[k] = field[order[k]];
    field.swap(sorted);
  });
}

void ParticleStore::remove_if(const std::vector<char>& remove_flag) {
  for_each_field([&](auto& field) {
    std::size_t kept = 0;
    for (std::size_t k = 0; k < field.size(); ++k)
      if (!remove_flag[k]) field[kept++] = field[k];
    field.resize(kept);
  });
}

void ParticleStore::reserve(std::size_t n) {
  for_each_field([&](auto& field) { field.reserve(n); });
}

}  // namespace regodem
