#pragma once
// The deepest overlap among a set of spheres, found without a neighbour list: a packing
// read from a file is checked before it runs, and a run's t = 0 sample reports the
// overlaps it starts with (the contact pass has not run yet then).
#include <cstddef>
#include <span>

#include "core/vec3.hpp"

namespace regodem {

struct DeepestOverlap {
  double fraction = 0.0;  // overlap r_i + r_j − |x_j − x_i| over the smaller diameter; 0: none
  std::size_t i = 0, j = 0;  // the pair (i < j), when fraction > 0
};

/// O(N log N): spheres sorted into cells of the largest diameter, each pair within
/// reach tested once.
DeepestOverlap deepest_overlap(std::span<const Vec3> positions_m, std::span<const double> radii_m);

}  // namespace regodem
