#include "parallel/ghost_reach.hpp"

#include <algorithm>

namespace regodem {

std::vector<double> largest_radius_by_brick(const RecursiveBisection& bricks, std::span<const Vec3> positions,
                                            std::span<const double> radii_m) {
  std::vector<double> largest(static_cast<std::size_t>(bricks.ranks()), 0.0);
  for (std::size_t p = 0; p < positions.size(); ++p) {
    double& of_brick = largest[static_cast<std::size_t>(bricks.rank_of(positions[p]))];
    of_brick = std::max(of_brick, radii_m[p]);
  }
  return largest;
}

}  // namespace regodem
