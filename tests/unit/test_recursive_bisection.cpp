// The domain's bricks by recursive coordinate bisection (src/parallel/recursive_bisection.hpp).
// Bounds stated before running:
//  * the bricks tile the domain: their volumes sum to its volume (to 1e-12 of it), and
//    every point lies in the brick of the rank rank_of gives it;
//  * balance: each cut puts below it the weight nearest its target among the cuts between
//    distinct coordinates, so with distinct coordinates it misses by at most half the
//    largest weight, and a brick's weight misses its share W/N by at most the largest
//    weight times the number of cuts above it (ceil(log2 N));
//  * the bricks depend on the points, not on their order: the same cuts, bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.hpp"
#include "core/rng.hpp"
#include "parallel/recursive_bisection.hpp"

namespace regodem {
namespace {

const Brick kDomain{{-0.05, -0.05, 0.0}, {0.05, 0.05, 0.2}};

std::vector<Vec3> random_points(Rng& rng, std::size_t count, const Brick& box) {
  std::vector<Vec3> p(count);
  for (Vec3& x : p)
    x = {rng.uniform(box.lo_m.x, box.hi_m.x), rng.uniform(box.lo_m.y, box.hi_m.y), rng.uniform(box.lo_m.z, box.hi_m.z)};
  return p;
}

bool inside(const Brick& b, const Vec3& x) {
  for (int a = 0; a < 3; ++a)
    if (!(x[a] >= b.lo_m[a] && x[a] < b.hi_m[a])) return false;
  return true;
}

// The weight on each rank, and the largest miss from the share allowed by the header.
void expect_tiled_and_balanced(const RecursiveBisection& rcb, const std::vector<Vec3>& points,
                               const std::vector<double>& weights, int ranks) {
  ASSERT_EQ(rcb.ranks(), ranks);
  double volume = 0.0;
  for (int r = 0; r < ranks; ++r) volume += rcb.brick(r).volume_m3();
  EXPECT_NEAR(volume, kDomain.volume_m3(), 1e-12 * kDomain.volume_m3());
  std::vector<double> load(static_cast<std::size_t>(ranks), 0.0);
  double total = 0.0, largest = 0.0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const int r = rcb.rank_of(points[k]);
    ASSERT_TRUE(r >= 0 && r < ranks);
    EXPECT_TRUE(inside(rcb.brick(r), points[k])) << "point " << k << " rank " << r;
    const double w = weights.empty() ? 1.0 : weights[k];
    load[static_cast<std::size_t>(r)] += w;
    total += w;
    largest = std::max(largest, w);
  }
  const double cuts = std::ceil(std::log2(static_cast<double>(ranks)));
  for (int r = 0; r < ranks; ++r)
    EXPECT_LE(std::abs(load[static_cast<std::size_t>(r)] - total / ranks), largest * cuts + 1e-9 * total)
        << "rank " << r << " of " << ranks;
}

TEST(RecursiveBisection, EqualPointsSplitEvenlyOverAnyRankCount) {
  Rng rng(5);
  const std::vector<Vec3> points = random_points(rng, 10007, kDomain);
  for (int ranks : {1, 2, 3, 4, 5, 7, 8, 16, 24}) {
    const RecursiveBisection rcb(kDomain, points, {}, ranks);
    expect_tiled_and_balanced(rcb, points, {}, ranks);
  }
}

TEST(RecursiveBisection, WeightedWorkGetsSmallBricks) {
  // A drilling bed: the work (weight 20) in a column of radius 1 cm at x = y = 3 cm, light
  // grains (weight 1) around it.
  Rng rng(11);
  const std::vector<Vec3> points = random_points(rng, 20000, kDomain);
  std::vector<double> weights(points.size());
  for (std::size_t k = 0; k < points.size(); ++k)
    weights[k] = std::hypot(points[k].x - 0.03, points[k].y - 0.03) < 0.01 ? 20.0 : 1.0;
  const int ranks = 8;
  const RecursiveBisection rcb(kDomain, points, weights, ranks);
  expect_tiled_and_balanced(rcb, points, weights, ranks);
  // The bricks that hold the column are smaller than an even cut of the volume.
  for (double z : {0.05, 0.15}) {
    const int r = rcb.rank_of({0.03, 0.03, z});
    EXPECT_LT(rcb.brick(r).volume_m3(), 0.7 * kDomain.volume_m3() / ranks) << "rank " << r;
  }
}

TEST(RecursiveBisection, TheBricksDoNotDependOnThePointsOrder) {
  Rng rng(17);
  std::vector<Vec3> points = random_points(rng, 3000, kDomain);
  std::vector<double> weights(points.size());
  for (double& w : weights) w = std::floor(rng.uniform(1.0, 5.0));
  // Ties: a layer of points at one height, as a poured floor makes.
  for (std::size_t k = 0; k < 500; ++k) points[k].z = 0.1;
  const RecursiveBisection first(kDomain, points, weights, 6);
  std::vector<std::size_t> order(points.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = order.size() - 1 - k;
  std::rotate(order.begin(), order.begin() + 1234, order.end());
  std::vector<Vec3> shuffled_points;
  std::vector<double> shuffled_weights;
  for (std::size_t k : order) {
    shuffled_points.push_back(points[k]);
    shuffled_weights.push_back(weights[k]);
  }
  const RecursiveBisection second(kDomain, shuffled_points, shuffled_weights, 6);
  for (int r = 0; r < 6; ++r) {
    EXPECT_EQ(first.brick(r).lo_m, second.brick(r).lo_m) << r;
    EXPECT_EQ(first.brick(r).hi_m, second.brick(r).hi_m) << r;
  }
}

TEST(RecursiveBisection, PointsOutsideAndEmptyDomainsAndBadInput) {
  // No points: the cuts share the volume.
  const RecursiveBisection empty(kDomain, {}, {}, 4);
  for (int r = 0; r < 4; ++r) EXPECT_NEAR(empty.brick(r).volume_m3(), kDomain.volume_m3() / 4, 1e-15);
  // A point beyond a face belongs to the brick across that face.
  Rng rng(3);
  const std::vector<Vec3> points = random_points(rng, 1000, kDomain);
  const RecursiveBisection rcb(kDomain, points, {}, 4);
  const Vec3 below{0.01, -0.02, -1.0}, on_floor{0.01, -0.02, 0.0};
  EXPECT_EQ(rcb.rank_of(below), rcb.rank_of(on_floor));
  EXPECT_THROW(RecursiveBisection(kDomain, points, {}, 0), InputError);
  EXPECT_THROW(RecursiveBisection(kDomain, points, std::vector<double>(3, 1.0), 2), InputError);
  EXPECT_THROW(RecursiveBisection(kDomain, points, std::vector<double>(points.size(), 0.0), 2), InputError);
  EXPECT_THROW(RecursiveBisection(Brick{{0, 0, 0}, {1, 0, 1}}, points, {}, 2), InputError);
}

}  // namespace
}  // namespace regodem
