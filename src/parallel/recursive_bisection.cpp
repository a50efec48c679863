#include "parallel/recursive_bisection.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace regodem {
namespace {

double& component(Vec3& v, int axis) { return axis == 0 ? v.x : (axis == 1 ? v.y : v.z); }

}  // namespace

double Brick::distance_m(const Vec3& x) const {
  double d2 = 0.0;
  for (int a = 0; a < 3; ++a) {
    const double outside = std::max({lo_m[a] - x[a], 0.0, x[a] - hi_m[a]});
    d2 += outside * outside;
  }
  return std::sqrt(d2);
}

double Brick::distance_m(const Brick& other) const {
  double d2 = 0.0;
  for (int a = 0; a < 3; ++a) {
    const double outside = std::max({lo_m[a] - other.hi_m[a], 0.0, other.lo_m[a] - hi_m[a]});
    d2 += outside * outside;
  }
  return std::sqrt(d2);
}

RecursiveBisection::RecursiveBisection(const Brick& domain, std::span<const Vec3> points,
                                       std::span<const double> weights, int ranks) {
  if (ranks < 1) throw InputError(fmt::format("a decomposition needs 1 or more ranks, got {}", ranks));
  for (int a = 0; a < 3; ++a)
    if (!(domain.hi_m[a] > domain.lo_m[a]))
      throw InputError(fmt::format("the domain to decompose is empty along axis {}: {} to {} m", a, domain.lo_m[a],
                                   domain.hi_m[a]));
  if (!weights.empty() && weights.size() != points.size())
    throw InputError(fmt::format("{} weights for {} points", weights.size(), points.size()));
  for (double w : weights)
    if (!(w > 0.0 && std::isfinite(w))) throw InputError(fmt::format("a point's weight must be positive, got {}", w));
  bricks_.resize(static_cast<std::size_t>(ranks));
  std::vector<std::size_t> order(points.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  split(domain, order, 0, order.size(), points, weights, 0, ranks);
}

int RecursiveBisection::split(const Brick& box, std::vector<std::size_t>& order, std::size_t first, std::size_t count,
                              std::span<const Vec3> points, std::span<const double> weights, int first_rank,
                              int ranks) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.push_back({});
  if (ranks == 1) {
    nodes_[index].rank = first_rank;
    bricks_[static_cast<std::size_t>(first_rank)] = box;
    return index;
  }
  const int low_ranks = ranks / 2;
  int axis = 0;
  for (int a = 1; a < 3; ++a)
    if (box.hi_m[a] - box.lo_m[a] > box.hi_m[axis] - box.lo_m[axis]) axis = a;
  const double lo = box.lo_m[axis], hi = box.hi_m[axis];

  // The points by coordinate along the axis (inside the box), then by weight: the same
  // sequence, and so the same sums, whatever order the points came in.
  const auto coordinate = [&](std::size_t p) { return std::clamp(points[p][axis], lo, hi); };
  const auto weight = [&](std::size_t p) { return weights.empty() ? 1.0 : weights[p]; };
  const auto begin = order.begin() + static_cast<std::ptrdiff_t>(first);
  std::sort(begin, begin + static_cast<std::ptrdiff_t>(count), [&](std::size_t a, std::size_t b) {
    const double ca = coordinate(a), cb = coordinate(b);
    return ca != cb ? ca < cb : weight(a) < weight(b);
  });
  double total = 0.0;
  for (std::size_t k = first; k < first + count; ++k) total += weight(order[k]);
  const double target = total * low_ranks / ranks;

  // The cut between two distinct coordinates whose weight below is nearest the target;
  // without any (no points, or all at one coordinate), the cut shares the length.
  double cut = lo + (hi - lo) * low_ranks / ranks;
  std::size_t below = 0;
  double best = INFINITY, sum = 0.0;
  for (std::size_t k = first; k < first + count; ++k) {
    if (k > first && coordinate(order[k]) > coordinate(order[k - 1]) && std::abs(sum - target) < best) {
      best = std::abs(sum - target);
      cut = 0.5 * (coordinate(order[k - 1]) + coordinate(order[k]));
      below = k - first;
    }
    sum += weight(order[k]);
  }
  if (best == INFINITY) below = static_cast<std::size_t>(
      std::count_if(begin, begin + static_cast<std::ptrdiff_t>(count), [&](std::size_t p) {
        return coordinate(p) < cut;
      }));

  Brick low_box = box, high_box = box;
  component(low_box.hi_m, axis) = cut;
  component(high_box.lo_m, axis) = cut;
  nodes_[index].axis = axis;
  nodes_[index].cut_m = cut;
  const int low = split(low_box, order, first, below, points, weights, first_rank, low_ranks);
  const int high =
      split(high_box, order, first + below, count - below, points, weights, first_rank + low_ranks, ranks - low_ranks);
  nodes_[index].low = low;
  nodes_[index].high = high;
  return index;
}

int RecursiveBisection::rank_of(const Vec3& x) const {
  int n = 0;
  while (nodes_[n].axis >= 0) n = x[nodes_[n].axis] < nodes_[n].cut_m ? nodes_[n].low : nodes_[n].high;
  return nodes_[n].rank;
}

}  // namespace regodem
