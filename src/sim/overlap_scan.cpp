#include "sim/overlap_scan.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <vector>

namespace regodem {
namespace {

using CellKey = std::array<std::int64_t, 3>;

CellKey cell_of(const Vec3& x, double cell_m) {
  return {static_cast<std::int64_t>(std::floor(x.x / cell_m)), static_cast<std::int64_t>(std::floor(x.y / cell_m)),
          static_cast<std::int64_t>(std::floor(x.z / cell_m))};
}

}  // namespace

DeepestOverlap deepest_overlap(std::span<const Vec3> positions_m, std::span<const double> radii_m) {
  DeepestOverlap deepest;
  const std::size_t n = positions_m.size();
  if (n < 2) return deepest;
  const double cell_m = 2.0 * *std::max_element(radii_m.begin(), radii_m.end());
  std::vector<CellKey> keys(n);
  for (std::size_t i = 0; i < n; ++i) keys[i] = cell_of(positions_m[i], cell_m);
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return keys[a] != keys[b] ? keys[a] < keys[b] : a < b;
  });
  std::vector<CellKey> sorted_keys(n);
  for (std::size_t k = 0; k < n; ++k) sorted_keys[k] = keys[order[k]];

  for (std::size_t i = 0; i < n; ++i) {
    const CellKey& home = keys[i];
    for (std::int64_t dz = -1; dz <= 1; ++dz)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dx = -1; dx <= 1; ++dx) {
          const CellKey cell{home[0] + dx, home[1] + dy, home[2] + dz};
          const auto [first, last] = std::equal_range(sorted_keys.begin(), sorted_keys.end(), cell);
          for (auto k = first; k != last; ++k) {
            const std::size_t j = order[static_cast<std::size_t>(k - sorted_keys.begin())];
            if (j <= i) continue;
            const double overlap = radii_m[i] + radii_m[j] - norm(positions_m[j] - positions_m[i]);
            const double fraction = overlap / (2.0 * std::min(radii_m[i], radii_m[j]));
            if (fraction > deepest.fraction) deepest = {fraction, i, j};
          }
        }
  }
  return deepest;
}

}  // namespace regodem
