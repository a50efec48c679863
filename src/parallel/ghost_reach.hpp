#pragma once
// How far from a rank's brick a particle is wanted there as a ghost (issue 19). A pair is
// listed within R_i + R_j + h_i + h_j (NeighborSkin: each half h at most its largest), so
// particle g can be a partner of a particle of brick r only if it lies within
// R_g + R_r + 2 h_max of the brick, R_r the largest of r's own particles. A fine grain
// then reaches a fine brick by two fine radii and the skin, not by two of the coarsest
// radii: in a multi-level bed (0.6 / 2.4 mm grains) the fine bricks' ghost shells are a
// third as thick as a uniform reach would make them. A brick without particles needs no
// ghosts.
#include <span>
#include <vector>

#include "core/vec3.hpp"
#include "parallel/recursive_bisection.hpp"

namespace regodem {

struct GhostReach {
  double skin_m = 0.0;                   // 2 h_max: the most a pair's two halves of the skin add
  std::vector<double> largest_radius_m;  // by brick: its own particles' largest, 0 when it has none

  /// Whether a particle of `radius_m` at x is wanted as a ghost by brick `rank`.
  bool wanted(const RecursiveBisection& bricks, int rank, const Vec3& x, double radius_m) const {
    const double largest = largest_radius_m[static_cast<std::size_t>(rank)];
    return largest > 0.0 && bricks.brick(rank).distance_m(x) <= radius_m + largest + skin_m;
  }
};

/// The largest radius of the particles in each brick (0 for a brick with none): the
/// per-brick part of GhostReach when every particle is at hand (one process, the model);
/// over ranks each rank's own largest, gathered.
std::vector<double> largest_radius_by_brick(const RecursiveBisection& bricks, std::span<const Vec3> positions,
                                            std::span<const double> radii_m);

}  // namespace regodem
