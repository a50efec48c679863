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

namespace regodem {

/// Changes the properties of one material pair (or every pair) while a stage runs.
struct PairOverride {
  int material_a = -1, material_b = -1;  // -1, -1: every pair
  std::optional<double> restitution, sliding_friction, rolling_friction;
};

struct Stage {
  std::string name;
  bool until_settled = false;
  double duration_s = 0.0;                // !until_settled
  double settled_kinetic_energy_J = 0.0;  // until_settled: mean per particle
  double min_duration_s = 0.0;
  double max_duration_s = std::numeric_limits<double>::infinity();
  std::vector<PairOverride> overrides;
};

struct StagePlan {
  std::vector<Stage> stages;
  std::vector<Insertion> insertions;
  double sample_interval_s = 0.0;   // 0: 100 samples per time-limited stage
  std::uint64_t seed = 1;
};

}  // namespace regodem
