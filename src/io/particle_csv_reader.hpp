#pragma once
// Reads a packing made elsewhere: a CSV file whose header names the columns x, y, z,
// radius (metres), optionally vx, vy, vz (m/s) and temperature (K), in any order.
#include <string>
#include <vector>

#include "core/vec3.hpp"

namespace regodem {

struct ParticleRecord {
  Vec3 position_m;
  double radius_m = 0.0;
  Vec3 velocity_m_per_s;
  double temperature_K = 0.0;
  bool has_temperature = false;
  int line = 0;  // in the file, for messages
};

/// Throws InputError naming the file and line of a malformed row, or of a header that
/// names a column twice or an unknown one.
std::vector<ParticleRecord> read_particle_csv(const std::string& path);

}  // namespace regodem
