#include "parallel/ghost_reach.hpp"

#include <algorithm>

namespace regodem {
namespace {

std::size_t band_of(double radius_m, double largest_m) {
  if (radius_m > 0.5 * largest_m) return 0;
  if (radius_m > 0.25 * largest_m) return 1;
  return 2;
}

void add_to(RadiusBand& band, const Vec3& x, double radius_m) {
  if (band.largest_radius_m == 0.0) band.centres = Brick{x, x};
  band.largest_radius_m = std::max(band.largest_radius_m, radius_m);
  Vec3& lo = band.centres.lo_m;
  Vec3& hi = band.centres.hi_m;
  lo = {std::min(lo.x, x.x), std::min(lo.y, x.y), std::min(lo.z, x.z)};
  hi = {std::max(hi.x, x.x), std::max(hi.y, x.y), std::max(hi.z, x.z)};
}

}  // namespace

std::vector<int> GhostReach::bricks_near(const Brick& box, double largest_radius_m, int except) const {
  std::vector<int> near;
  for (std::size_t b = 0; b < bands.size(); ++b) {
    const auto rank = static_cast<int>(b / kBandsPerBrick);
    if (rank == except || (!near.empty() && near.back() == rank) || bands[b].largest_radius_m <= 0.0) continue;
    // As wanted(): the particle's radius + the band's + the skin, added in that order.
    if (bands[b].centres.distance_m(box) <= largest_radius_m + bands[b].largest_radius_m + skin_m) near.push_back(rank);
  }
  return near;
}

CentresBox centres_box(std::span<const Vec3> positions, std::span<const double> radii_m) {
  RadiusBand all;  // one band of every radius
  for (std::size_t p = 0; p < positions.size(); ++p) add_to(all, positions[p], radii_m[p]);
  return {all.centres, all.largest_radius_m};
}

std::array<RadiusBand, GhostReach::kBandsPerBrick> radius_bands(std::span<const Vec3> positions,
                                                                std::span<const double> radii_m) {
  std::array<RadiusBand, GhostReach::kBandsPerBrick> bands{};
  double largest = 0.0;
  for (const double r : radii_m) largest = std::max(largest, r);
  for (std::size_t p = 0; p < positions.size(); ++p) add_to(bands[band_of(radii_m[p], largest)], positions[p], radii_m[p]);
  return bands;
}

std::vector<RadiusBand> radius_bands_by_brick(const RecursiveBisection& bricks, std::span<const Vec3> positions,
                                              std::span<const double> radii_m) {
  const auto ranks = static_cast<std::size_t>(bricks.ranks());
  std::vector<std::size_t> brick_of(positions.size());
  std::vector<double> largest(ranks, 0.0);
  for (std::size_t p = 0; p < positions.size(); ++p) {
    brick_of[p] = static_cast<std::size_t>(bricks.rank_of(positions[p]));
    largest[brick_of[p]] = std::max(largest[brick_of[p]], radii_m[p]);
  }
  std::vector<RadiusBand> bands(ranks * GhostReach::kBandsPerBrick);
  for (std::size_t p = 0; p < positions.size(); ++p) {
    const std::size_t b = brick_of[p];
    add_to(bands[b * GhostReach::kBandsPerBrick + band_of(radii_m[p], largest[b])], positions[p], radii_m[p]);
  }
  return bands;
}

std::vector<double> band_values(std::span<const RadiusBand> bands) {
  std::vector<double> values;
  values.reserve(bands.size() * GhostReach::kValuesPerBand);
  for (const RadiusBand& b : bands)
    values.insert(values.end(), {b.largest_radius_m, b.centres.lo_m.x, b.centres.lo_m.y, b.centres.lo_m.z,
                                 b.centres.hi_m.x, b.centres.hi_m.y, b.centres.hi_m.z});
  return values;
}

std::vector<RadiusBand> bands_of_values(std::span<const double> values) {
  std::vector<RadiusBand> bands(values.size() / GhostReach::kValuesPerBand);
  for (std::size_t b = 0; b < bands.size(); ++b) {
    const double* v = values.data() + b * GhostReach::kValuesPerBand;
    bands[b] = RadiusBand{v[0], Brick{{v[1], v[2], v[3]}, {v[4], v[5], v[6]}}};
  }
  return bands;
}

}  // namespace regodem
