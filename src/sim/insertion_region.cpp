#include "sim/insertion_region.hpp"

#include <cmath>
#include <numbers>

namespace regodem {
namespace {

/// Two unit vectors completing `axis` to an orthonormal frame.
void perpendicular_frame(const Vec3& axis, Vec3& e1, Vec3& e2) {
  const Vec3 helper = std::abs(axis.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  e1 = normalized(cross(axis, helper));
  e2 = cross(axis, e1);
}

}  // namespace

double InsertionRegion::volume_m3() const {
  if (shape == InsertionShape::box) {
    const Vec3 e = max_m - min_m;
    return e.x * e.y * e.z;
  }
  const double inner = shape == InsertionShape::annulus ? inner_radius_m : 0.0;
  return std::numbers::pi * (radius_m * radius_m - inner * inner) * length_m;
}

void InsertionRegion::bounds(Vec3& lo, Vec3& hi) const {
  if (shape == InsertionShape::box) {
    lo = min_m;
    hi = max_m;
    return;
  }
  // Each end disk spans radius * sqrt(1 - axis_k^2) along coordinate k.
  const Vec3 top = base_m + axis * length_m;
  auto extent = [this](double a) { return radius_m * std::sqrt(std::max(0.0, 1.0 - a * a)); };
  const Vec3 half{extent(axis.x), extent(axis.y), extent(axis.z)};
  lo = {std::min(base_m.x, top.x) - half.x, std::min(base_m.y, top.y) - half.y, std::min(base_m.z, top.z) - half.z};
  hi = {std::max(base_m.x, top.x) + half.x, std::max(base_m.y, top.y) + half.y, std::max(base_m.z, top.z) + half.z};
}

bool InsertionRegion::sample_centre(Rng& rng, double r, Vec3& centre) const {
  if (shape == InsertionShape::box) {
    const Vec3 lo = min_m + Vec3{r, r, r}, hi = max_m - Vec3{r, r, r};
    if (lo.x > hi.x || lo.y > hi.y || lo.z > hi.z) return false;
    centre = {rng.uniform(lo.x, hi.x), rng.uniform(lo.y, hi.y), rng.uniform(lo.z, hi.z)};
    return true;
  }
  const double outer = radius_m - r;
  const double inner = shape == InsertionShape::annulus ? inner_radius_m + r : 0.0;
  if (outer < inner || length_m < 2.0 * r) return false;
  Vec3 e1, e2;
  perpendicular_frame(axis, e1, e2);
  // Uniform over the annulus area: rho^2 uniform between inner^2 and outer^2.
  const double rho = std::sqrt(rng.uniform(inner * inner, outer * outer));
  const double angle = rng.uniform(0.0, 2.0 * std::numbers::pi);
  const double along = rng.uniform(r, length_m - r);
  centre = base_m + axis * along + e1 * (rho * std::cos(angle)) + e2 * (rho * std::sin(angle));
  return true;
}

bool InsertionRegion::contains_sphere(const Vec3& x, double r) const {
  if (shape == InsertionShape::box)
    return x.x >= min_m.x + r && x.y >= min_m.y + r && x.z >= min_m.z + r && x.x <= max_m.x - r &&
           x.y <= max_m.y - r && x.z <= max_m.z - r;
  const Vec3 offset = x - base_m;
  const double along = dot(offset, axis);
  if (along < r || along > length_m - r) return false;
  const double rho = norm(offset - axis * along);
  const double inner = shape == InsertionShape::annulus ? inner_radius_m + r : 0.0;
  return rho <= radius_m - r && (shape != InsertionShape::annulus || rho >= inner);
}

}  // namespace regodem
