#pragma once
// The domain cut into one brick per rank by recursive coordinate bisection (Berger &
// Bokhari 1987; LAMMPS `balance rcb`): the first step of running over MPI (issue 19).
// Each cut halves the ranks of a box (the larger half to the high side for an odd count)
// and is placed across the box's longest side where the weight below it is the share of
// the ranks below it, so each brick holds about the same weight. The weight of a particle
// is the work it brings (1 + its contacts and bonds, say): the drilling region, dense in
// work, gets small bricks and the coarse ring large ones.
//
// The cuts depend only on the points' coordinates and weights, never on their order, so
// every rank that is given the same particles computes the same bricks.
#include <span>
#include <vector>

#include "core/vec3.hpp"

namespace regodem {

/// An axis-aligned box, lo <= x < hi on each axis (a brick's high faces belong to the
/// next brick).
struct Brick {
  Vec3 lo_m, hi_m;
  double volume_m3() const { return (hi_m.x - lo_m.x) * (hi_m.y - lo_m.y) * (hi_m.z - lo_m.z); }
  /// The distance from x to the nearest point of the brick (0 inside).
  double distance_m(const Vec3& x) const;
  /// The distance between the nearest points of the two bricks (0 where they touch):
  /// never more than distance_m(x) for any x in `other` (the same rounding, monotone).
  double distance_m(const Brick& other) const;
};

class RecursiveBisection {
 public:
  /// Cuts `domain` into `ranks` (1 or more) bricks of equal shares of the weights of the
  /// points inside it (points outside count for the brick nearest to them). `weights`
  /// is empty (every point weighs 1) or one positive value per point.
  RecursiveBisection(const Brick& domain, std::span<const Vec3> points, std::span<const double> weights, int ranks);

  int ranks() const { return static_cast<int>(bricks_.size()); }
  const Brick& brick(int rank) const { return bricks_[static_cast<std::size_t>(rank)]; }
  /// The rank whose brick holds x; a point outside the domain belongs to the brick
  /// nearest to it across the domain's faces.
  int rank_of(const Vec3& x) const;

 private:
  struct Node {  // a box cut in two, or (axis < 0) a brick
    int axis = -1;
    double cut_m = 0.0;
    int low = -1, high = -1;  // children, as node indices
    int rank = 0;             // for a brick
  };
  int split(const Brick& box, std::vector<std::size_t>& order, std::size_t first, std::size_t count,
            std::span<const Vec3> points, std::span<const double> weights, int first_rank, int ranks);

  std::vector<Node> nodes_;  // nodes_[0] is the whole domain
  std::vector<Brick> bricks_;
};

}  // namespace regodem
