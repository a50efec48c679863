// The cost model of a run over many ranks (src/parallel/rank_cost_model.hpp): the cut's
// own particles, ghosts and partners on a lattice, counted by hand, and the projection's
// limits (one rank is one process; a free network leaves the ghosts' extra work alone).
#include <gtest/gtest.h>

#include <algorithm>

#include "parallel/ghost_reach.hpp"
#include "parallel/rank_cost_model.hpp"

namespace regodem {
namespace {

// 10 x 10 x 10 points at the centres of cells of side d in a cube of 10 d: the cuts fall
// between layers, at 5 d (RecursiveBisection cuts midway between distinct coordinates).
constexpr double d = 1e-3;
std::vector<Vec3> lattice() {
  std::vector<Vec3> points;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j)
      for (int k = 0; k < 10; ++k) points.push_back({(i + 0.5) * d, (j + 0.5) * d, (k + 0.5) * d});
  return points;
}
const Brick cube{{0, 0, 0}, {10 * d, 10 * d, 10 * d}};
// One radius for every point: the ghosts' reach is then 2 r + the skin.
std::vector<double> radii(const std::vector<Vec3>& points, double radius_m) {
  return std::vector<double>(points.size(), radius_m);
}

TEST(RankCostModel, TwoBricksEachHoldTheOthersNearestLayerAsGhosts) {
  const std::vector<Vec3> points = lattice();
  // The other brick's nearest layer is 1.0 d from the box of this brick's centres, the
  // next 2.0 d; the reach is 2 x 0.45 d + 0.2 d = 1.1 d.
  const RankShares shares = cut_into_bricks(cube, points, radii(points, 0.45 * d), {}, 0.2 * d, 2);
  for (int r = 0; r < 2; ++r) {
    EXPECT_EQ(shares.own[r], 500u);
    EXPECT_EQ(shares.ghosts[r], 100u);
    EXPECT_EQ(shares.partners[r], 1);
  }
  EXPECT_DOUBLE_EQ(shares.total_work, 1000.0);
}

TEST(RankCostModel, EightBricksTakeFacesEdgesAndCornersWithinReach) {
  const std::vector<Vec3> points = lattice();
  // Each brick is 5 x 5 x 5 in a corner of the cube, its centres 0.5-4.5 d. Its three face
  // neighbours' nearest layers (25 points each) are 1.0 d from them, the three edge
  // neighbours' nearest rows (5 each) 1.41 d, the corner neighbour's nearest point 1.73 d,
  // the next layers 2.0 d or more. Reaches of 1.1 d and 1.8 d.
  const RankShares faces = cut_into_bricks(cube, points, radii(points, 0.45 * d), {}, 0.2 * d, 8);
  const RankShares all = cut_into_bricks(cube, points, radii(points, 0.8 * d), {}, 0.2 * d, 8);
  for (int r = 0; r < 8; ++r) {
    EXPECT_EQ(faces.own[r], 125u);
    EXPECT_EQ(faces.ghosts[r], 75u);
    EXPECT_EQ(faces.partners[r], 3);
    EXPECT_EQ(all.ghosts[r], 75u + 15u + 1u);
    EXPECT_EQ(all.partners[r], 7);
  }
}

// Two sizes: the fine grains (r = 0.1 d) in the lower half of the lattice (z < 5 d), the
// coarse (r = 0.4 d) above; the domain is longest along x, so the cut falls across x
// between the layers at 4.5 and 5.5 d and each brick holds both sizes, its coarse centres
// in a box at z = 5.5-9.5 d and its fine ones at z = 0.5-4.5 d. With a skin of 0.5 d a
// coarse grain of the other brick's nearest layer (1.0 d from the coarse box) is within
// 0.4 + 0.4 + 0.5 = 1.3 d of it (50 grains), its next layer (2.0 d) is not; a fine grain of
// that layer is 1.0 d from the fine box, beyond 0.1 + 0.1 + 0.5 = 0.7 d, and at least
// 1.41 d from the coarse box, beyond 0.1 + 0.4 + 0.5 = 1.0 d: none, and none of them can
// pair with this brick's grains (the nearest fine-fine pair is 1.0 d apart, fine-coarse
// 1.41 d). Reaching from the brick's face (0.5 d from the nearest layer) with its largest
// radius would take the fine layer too (100); a uniform reach of 1.3 d, 100 as well.
TEST(RankCostModel, AGrainsReachIsItsRadiusItsSizeBandsLargestAndTheSkinFromTheBandsCentres) {
  const std::vector<Vec3> points = lattice();
  std::vector<double> radius;
  for (const Vec3& x : points) radius.push_back(x.z < 5 * d ? 0.1 * d : 0.4 * d);
  const Brick long_in_x{{0, 0, 0}, {10.5 * d, 10 * d, 10 * d}};
  const RankShares two = cut_into_bricks(long_in_x, points, radius, {}, 0.5 * d, 2);
  for (int r = 0; r < 2; ++r) {
    EXPECT_EQ(two.own[r], 500u);
    EXPECT_EQ(two.ghosts[r], 50u);
  }
}

// A brick asks only the bricks near its own grains (GhostReach::bricks_near): every brick
// that wants one of its grains must be among them, and on 64 bricks of a cube most are not.
TEST(RankCostModel, ABrickAsksOnlyTheBricksNearItsGrains) {
  std::vector<Vec3> points = lattice();
  std::vector<double> radius;
  for (std::size_t p = 0; p < points.size(); ++p) radius.push_back(p % 7 == 0 ? 0.4 * d : 0.1 * d);
  const RecursiveBisection bricks(cube, points, {}, 64);
  const GhostReach reach{0.2 * d, radius_bands_by_brick(bricks, points, radius)};
  std::size_t asked = 0;
  for (int r = 0; r < 64; ++r) {
    std::vector<Vec3> x;
    std::vector<double> radii_of_r;
    for (std::size_t p = 0; p < points.size(); ++p)
      if (bricks.rank_of(points[p]) == r) {
        x.push_back(points[p]);
        radii_of_r.push_back(radius[p]);
      }
    const CentresBox box = centres_box(x, radii_of_r);
    const std::vector<int> near = reach.bricks_near(box.box, box.largest_radius_m, r);
    asked += near.size();
    EXPECT_EQ(std::count(near.begin(), near.end(), r), 0);
    for (std::size_t k = 0; k < x.size(); ++k)
      for (int other = 0; other < 64; ++other)
        if (other != r && reach.wanted(other, x[k], radii_of_r[k])) {
          EXPECT_EQ(std::count(near.begin(), near.end(), other), 1) << "brick " << r << " misses " << other;
        }
  }
  // A 4 x 4 x 4 cut: a brick's neighbours across faces, edges and corners are at most 26.
  EXPECT_LE(asked, 64u * 26u);
  EXPECT_GT(asked, 0u);
}

TEST(RankCostModel, OneRankIsOneProcess) {
  const std::vector<Vec3> points = lattice();
  const OneProcessStep one{1000.0, 1e-3, 0.1};
  const RankStepCost cost = project_step(cut_into_bricks(cube, points, radii(points, 0.25 * d), {}, 0.1 * d, 1), one, NetworkModel{}, code_traffic());
  EXPECT_EQ(cost.step_s, 1e-3);
  EXPECT_EQ(cost.efficiency, 1.0);
  EXPECT_EQ(project_gather_s(1000.0, 200.0, 1, 1e-3, NetworkModel{}), 0.0);
}

TEST(RankCostModel, AFreeNetworkLeavesTheGhostsWork) {
  const std::vector<Vec3> points = lattice();
  NetworkModel free;
  free.latency_s = 0.0;
  free.bandwidth_bytes_per_s = std::numeric_limits<double>::infinity();
  // Each rank steps its 125 own particles and its 91 ghosts, at one process's cost per
  // particle; the counts scale with the run's particles (2,000 for this sample of 1,000).
  const OneProcessStep one{2000.0, 1e-3, 0.1};
  const RankStepCost cost = project_step(cut_into_bricks(cube, points, radii(points, 0.8 * d), {}, 0.2 * d, 8), one, free, code_traffic());
  EXPECT_NEAR(cost.step_s, 1e-3 * (125.0 + 91.0) / 1000.0, 1e-15);
  EXPECT_NEAR(cost.efficiency, 1000.0 / (8.0 * 216.0), 1e-12);
  EXPECT_DOUBLE_EQ(cost.own, 250.0);
  EXPECT_DOUBLE_EQ(cost.ghosts, 182.0);
}

// A brick of 20 x 20 x 20 lattice points: the points of the lattice around it within 2 d
// of it, counted one by one, against the shell's volume x the lattice's density. The
// lattice's layers lie at 0.5 d and 1.5 d from the faces, so its count differs from the
// volume's by a few per cent at most (2 % allowed).
TEST(RankCostModel, ACubicBricksGhostsAreItsShellWithinReach) {
  const double reach = 2.0 * d;
  std::size_t counted = 0;
  for (int i = -3; i < 23; ++i)
    for (int j = -3; j < 23; ++j)
      for (int k = -3; k < 23; ++k) {
        const Vec3 x{(i + 0.5) * d, (j + 0.5) * d, (k + 0.5) * d};
        const Brick brick{{0, 0, 0}, {20 * d, 20 * d, 20 * d}};
        const double distance = brick.distance_m(x);
        if (distance > 0.0 && distance <= reach) ++counted;
      }
  const double ghosts = cubic_brick_ghosts(8000.0, 1.0 / (d * d * d), reach);
  EXPECT_NEAR(ghosts, static_cast<double>(counted), 0.02 * static_cast<double>(counted));
}

TEST(RankCostModel, UniformSharesStepEveryRanksOwnAndGhosts) {
  NetworkModel free;
  free.latency_s = 0.0;
  free.bandwidth_bytes_per_s = std::numeric_limits<double>::infinity();
  const RankShares shares = uniform_shares(64, 1000, 500);
  EXPECT_EQ(shares.partners[0], 26);
  EXPECT_EQ(uniform_shares(8, 1000, 500).partners[0], 7);
  // 64 ranks of 1,000 particles: one process would step 64,000 in 64 ms.
  const RankStepCost cost = project_step(shares, OneProcessStep{64000.0, 64e-3, 0.0}, free, code_traffic());
  EXPECT_NEAR(cost.step_s, 1.5e-3, 1e-15);
}

// Two bricks of the lattice (500 own grains, 100 ghosts, 1 partner each) on a network of
// 1 us and 1 GB/s, one process stepping the 1,000 grains in 1 ms, no builds; by hand:
// compute 1 ms x 600/1000 = 600 us; the refresh: the all-to-all of counts (1 round, 1 us,
// 4 x 2 x 1 bytes = 0.008 us) and one message (1 us), the ghosts' 100 x 88 B = 8.8 us;
// 4 collectives of 1 round, 4 us. A gather of the 1,000 grains at 300 B each: 2 rounds
// (2 us), 300 us of bytes, and the one-process step (1 ms).
TEST(RankCostModel, AFiniteNetworkAddsTheHaloAndTheCollectivesByHand) {
  const std::vector<Vec3> points = lattice();
  NetworkModel network;
  network.latency_s = 1e-6;
  network.bandwidth_bytes_per_s = 1e9;
  const CodeTraffic traffic = code_traffic();
  ASSERT_EQ(traffic.refresh_bytes_per_ghost, 88u);  // 3 vectors and 2 scalars of doubles
  const RankStepCost cost =
      project_step(cut_into_bricks(cube, points, radii(points, 0.45 * d), {}, 0.2 * d, 2), OneProcessStep{1000.0, 1e-3, 0.0}, network, traffic);
  EXPECT_NEAR(cost.compute_s, 600e-6, 1e-15);
  EXPECT_NEAR(cost.halo_s, 1e-6 + 0.008e-6 + 1e-6 + 8.8e-6, 1e-15);
  EXPECT_NEAR(cost.collectives_s, 4e-6, 1e-15);
  EXPECT_NEAR(cost.step_s, 600e-6 + 10.808e-6 + 4e-6, 1e-15);
  // Six collectives of one round each at 2 ranks, the bytes, one step of one process.
  EXPECT_NEAR(project_gather_s(1000.0, 300.0, 2, 1e-3, network), 6e-6 + 300e-6 + 1e-3, 1e-15);
}

TEST(RankCostModel, ACollectiveTakesLog2RanksRounds) {
  EXPECT_EQ(collective_rounds(1), 0);
  EXPECT_EQ(collective_rounds(2), 1);
  EXPECT_EQ(collective_rounds(3), 2);
  EXPECT_EQ(collective_rounds(1024), 10);
  EXPECT_EQ(collective_rounds(1025), 11);
}

}  // namespace
}  // namespace regodem
