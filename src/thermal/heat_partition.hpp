#pragma once
// How the heat generated at a contact is shared between its two bodies
// (docs/physics.md, "Friction heat and its partition"). Each body has a weight and takes
// w_a / (w_a + w_b) of the heat:
//   equal:        w = 1, half each;
//   fixed:        a particle at a wall takes a set fraction, two particles half each;
//   conductivity: w = k, the better conductor takes more;
//   effusivity:   w = sqrt(k rho c), the classical partition of sliding-contact heat
//                 (Blok 1937; Charron 1943): each body takes its share in proportion to
//                 how much heat its surface absorbs for a given temperature rise.
// An adiabatic wall takes none (the particle gets it all), whatever the model.
#include <cmath>
#include <cstdint>

namespace regodem {

enum class HeatPartitionModel : std::uint8_t { equal, fixed, conductivity, effusivity };

inline const char* to_string(HeatPartitionModel model) {
  switch (model) {
    case HeatPartitionModel::equal: return "equal";
    case HeatPartitionModel::fixed: return "fixed";
    case HeatPartitionModel::conductivity: return "conductivity";
    case HeatPartitionModel::effusivity: return "effusivity";
  }
  return "fixed";
}

/// A body's weight from its conductivity, density and specific heat.
inline double heat_partition_weight(HeatPartitionModel model, double conductivity_W_per_mK, double density_kg_per_m3,
                                    double specific_heat_J_per_kgK) {
  switch (model) {
    case HeatPartitionModel::conductivity: return conductivity_W_per_mK;
    case HeatPartitionModel::effusivity:
      return std::sqrt(conductivity_W_per_mK * density_kg_per_m3 * specific_heat_J_per_kgK);
    case HeatPartitionModel::equal:
    case HeatPartitionModel::fixed: return 1.0;
  }
  return 1.0;
}

/// The share of body a, from the two weights (half each when neither has any).
inline double heat_share_of_first(double weight_a, double weight_b) {
  const double sum = weight_a + weight_b;
  return sum > 0.0 ? weight_a / sum : 0.5;
}

}  // namespace regodem
