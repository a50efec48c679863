#include "geometry/wall_primitive.hpp"

#include <algorithm>
#include <cmath>

namespace regodem {
namespace {

/// Closest point on a circle (centre c, unit axis u, radius r) to x, given the
/// in-plane offset of x from c.
WallProximity edge_of_circle(const Vec3& x, const Vec3& circle_centre, const Vec3& in_plane,
                             double in_plane_length, double radius) {
  WallProximity out;
  if (in_plane_length == 0.0) return out;  // on the axis: every rim point is equally far
  out.candidate = true;
  out.contact_point_m = circle_centre + in_plane * (radius / in_plane_length);
  const Vec3 to_edge = out.contact_point_m - x;
  out.distance_m = norm(to_edge);
  out.normal = out.distance_m > 0.0 ? to_edge / out.distance_m : Vec3{};
  return out;
}

WallProximity plane_point(const WallPrimitive& w, const Vec3& x) {
  const double height = dot(x - w.point_m, w.axis);
  return {true, height, -w.axis, x - height * w.axis};
}

WallProximity disk_point(const WallPrimitive& w, const Vec3& x) {
  const Vec3 offset = x - w.point_m;
  const double height = dot(offset, w.axis);
  const Vec3 in_plane = offset - height * w.axis;
  const double rho = norm(in_plane);
  if (rho <= w.radius_m) {  // over the face: two-sided
    const Vec3 normal = height >= 0.0 ? -w.axis : w.axis;
    return {true, std::abs(height), normal, w.point_m + in_plane};
  }
  return edge_of_circle(x, w.point_m, in_plane, rho, w.radius_m);
}

WallProximity cylinder_point(const WallPrimitive& w, const Vec3& x) {
  const Vec3 offset = x - w.point_m;
  const double along = dot(offset, w.axis);
  const Vec3 radial = offset - along * w.axis;
  const double rho = norm(radial);
  if (along < 0.0 || along > w.length_m) {
    const bool below = along < 0.0;
    if (below ? !w.rim_bottom : !w.rim_top) return {};
    const Vec3 end_centre = w.point_m + (below ? 0.0 : w.length_m) * w.axis;
    return edge_of_circle(x, end_centre, radial, rho, w.radius_m);
  }
  if (rho == 0.0) return {};
  const Vec3 outward = radial / rho;
  const Vec3 surface = w.point_m + along * w.axis + outward * w.radius_m;
  if (rho < w.radius_m) {
    if (!w.contact_inside) return {};
    return {true, w.radius_m - rho, outward, surface};
  }
  if (!w.contact_outside) return {};
  return {true, rho - w.radius_m, -outward, surface};
}

bool segment_crosses_disk(const WallPrimitive& w, const Vec3& a, const Vec3& b) {
  const double height_a = dot(a - w.point_m, w.axis), height_b = dot(b - w.point_m, w.axis);
  if (height_a * height_b >= 0.0) return false;  // same side (or touching the plane)
  const Vec3 crossing = a + (b - a) * (height_a / (height_a - height_b));
  const Vec3 offset = crossing - w.point_m;
  return norm2(offset - dot(offset, w.axis) * w.axis) <= w.radius_m * w.radius_m;
}

bool segment_crosses_cylinder(const WallPrimitive& w, const Vec3& a, const Vec3& b) {
  const Vec3 offset_a = a - w.point_m, d = b - a;
  const Vec3 radial_a = offset_a - dot(offset_a, w.axis) * w.axis;
  const Vec3 radial_d = d - dot(d, w.axis) * w.axis;
  const Vec3 radial_b = radial_a + radial_d;
  const double r2 = w.radius_m * w.radius_m;
  const double inside_a = norm2(radial_a) - r2, inside_b = norm2(radial_b) - r2;
  if (inside_a * inside_b >= 0.0) return false;  // both inside or both outside the shell
  // |radial_a + t radial_d|^2 = R^2 has exactly one root in (0, 1).
  const double qa = norm2(radial_d), qb = 2.0 * dot(radial_a, radial_d);
  const double root = std::sqrt(std::max(qb * qb - 4.0 * qa * inside_a, 0.0));
  const double t1 = (-qb - root) / (2.0 * qa), t2 = (-qb + root) / (2.0 * qa);
  const double t = (t1 >= 0.0 && t1 <= 1.0) ? t1 : t2;
  const double along = dot(offset_a + d * t, w.axis);
  return along >= 0.0 && along <= w.length_m;
}

}  // namespace

bool segment_crosses_wall(const WallPrimitive& wall, const Vec3& a_m, const Vec3& b_m) {
  switch (wall.shape) {
    case PrimitiveShape::plane: return false;
    case PrimitiveShape::disk: return segment_crosses_disk(wall, a_m, b_m);
    case PrimitiveShape::cylinder: return segment_crosses_cylinder(wall, a_m, b_m);
  }
  return false;
}

WallProximity closest_wall_point(const WallPrimitive& wall, const Vec3& centre_m) {
  switch (wall.shape) {
    case PrimitiveShape::plane: return plane_point(wall, centre_m);
    case PrimitiveShape::disk: return disk_point(wall, centre_m);
    case PrimitiveShape::cylinder: return cylinder_point(wall, centre_m);
  }
  return {};
}

}  // namespace regodem
