#pragma once
// A 32-bit FNV-1a hash of every particle's id, position, velocity, spin and temperature, in
// store order: two runs that end bit for bit alike (thread or rank counts) hash the same.
#include <cstddef>
#include <cstdint>

#include "core/particle_store.hpp"

namespace regodem::bench {

inline std::uint32_t state_hash(const ParticleStore& particles) {
  std::uint32_t hash = 2166136261u;
  const auto mix = [&](const auto& value) {
    const auto* bytes = reinterpret_cast<const unsigned char*>(&value);
    for (std::size_t k = 0; k < sizeof value; ++k) hash = (hash ^ bytes[k]) * 16777619u;
  };
  for (std::size_t p = 0; p < particles.size(); ++p) {
    mix(particles.id[p]);
    mix(particles.position_m[p]);
    mix(particles.velocity_m_per_s[p]);
    mix(particles.angular_velocity_rad_per_s[p]);
    mix(particles.temperature_K[p]);
  }
  return hash;
}

}  // namespace regodem::bench
