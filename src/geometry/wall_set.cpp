#include "geometry/wall_set.hpp"

#include <algorithm>
#include <utility>

namespace regodem {

std::uint32_t WallSet::add_body(const std::string& name, const WallMotion& motion) {
  WallBody body;
  body.name = name;
  body.motion = motion;
  body.feed_direction = normalized(motion.velocity_m_per_s);
  body.spin_axis = normalized(motion.angular_velocity_rad_per_s);
  bodies.push_back(body);
  return static_cast<std::uint32_t>(bodies.size() - 1);
}

void WallSet::add_plane(std::uint32_t body, const Vec3& point_m, const Vec3& normal, MaterialIndex material) {
  WallPrimitive p;
  p.shape = PrimitiveShape::plane;
  p.point_m = point_m;
  p.axis = normalized(normal);
  p.material = material;
  p.body = body;
  primitives.push_back(p);
}

void WallSet::add_disk(std::uint32_t body, const Vec3& centre_m, const Vec3& normal, double radius_m,
                       MaterialIndex material) {
  WallPrimitive p;
  p.shape = PrimitiveShape::disk;
  p.point_m = centre_m;
  p.axis = normalized(normal);
  p.radius_m = radius_m;
  p.material = material;
  p.body = body;
  primitives.push_back(p);
}

void WallSet::add_cylinder(std::uint32_t body, const Vec3& base_centre_m, const Vec3& axis, double radius_m,
                           double length_m, bool contact_inside, bool contact_outside, bool cap_bottom,
                           bool cap_top, MaterialIndex material) {
  WallPrimitive p;
  p.shape = PrimitiveShape::cylinder;
  p.point_m = base_centre_m;
  p.axis = normalized(axis);
  p.radius_m = radius_m;
  p.length_m = length_m;
  p.contact_inside = contact_inside;
  p.contact_outside = contact_outside;
  // A capped end's edge belongs to its disk; counting it twice would double the force.
  p.rim_bottom = !cap_bottom;
  p.rim_top = !cap_top;
  p.material = material;
  p.body = body;
  primitives.push_back(p);
  if (cap_bottom) add_disk(body, base_centre_m, p.axis, radius_m, material);
  if (cap_top) add_disk(body, base_centre_m + length_m * p.axis, p.axis, radius_m, material);
}

void WallSet::add_sieve_segment(std::uint32_t body, const Vec3& base_centre_m, const Vec3& axis, double radius_m,
                                double length_m, bool outer_bottom_end, bool outer_top_end, bool cap_bottom,
                                MaterialIndex material) {
  add_cylinder(body, base_centre_m, axis, radius_m, length_m, true, true, cap_bottom, false, material);
  WallPrimitive& shell = primitives[primitives.size() - (cap_bottom ? 2 : 1)];
  shell.rim_bottom = !cap_bottom && outer_bottom_end;
  shell.rim_top = outer_top_end;
}

void WallSet::add_mesh(std::uint32_t body, TriangleMesh mesh, MaterialIndex material, double cell_size_m) {
  meshes.emplace_back(std::move(mesh), body, material, cell_size_m);
}

double WallSet::spin_reach_m(std::uint32_t body) {
  WallBody& b = bodies[body];
  // The spin axis in the body's reference frame stays put while the body turns about
  // it and shifts along with it, so the farthest vertex from it is found once.
  const Vec3 axis = normalized(multiply_transposed(b.pose.rotation, b.motion.angular_velocity_rad_per_s));
  const Vec3 point = b.pose.to_reference(b.motion.axis_point_m);
  if (b.spin_reach_cached && axis == b.spin_reach_axis && point == b.spin_reach_point) return b.spin_reach_m;
  double reach = 0.0;
  for (const MeshWall& m : meshes)
    if (m.body == body)
      for (const Vec3& v : m.mesh.vertices) reach = std::max(reach, norm(cross(v - point, axis)));
  b.spin_reach_cached = true;
  b.spin_reach_axis = axis;
  b.spin_reach_point = point;
  b.spin_reach_m = reach;
  return reach;
}

void WallSet::advance(double time_s, double dt_s) {
  for (std::uint32_t b = 0; b < bodies.size(); ++b) {
    WallBody& body = bodies[b];
    WallMotion& motion = body.motion;
    if (!motion.active_at(time_s) || !motion.moves()) continue;
    // The force is the last step's: the feed stops before the step after the one on
    // which the thrust reached its limit.
    if (norm2(motion.velocity_m_per_s) > 0.0 && -dot(body.force_N, body.feed_direction) >= motion.max_thrust_N)
      motion.velocity_m_per_s = {};
    // The feed ends on the step that reaches max_travel_m, exactly there.
    Vec3 step = motion.velocity_m_per_s * dt_s;
    const double remaining_m = motion.max_travel_m - body.travel_m;
    if (norm(step) >= remaining_m) {
      step = normalized(motion.velocity_m_per_s) * std::max(0.0, remaining_m);
      motion.velocity_m_per_s = {};
    }
    const Vec3 turn = motion.angular_velocity_rad_per_s * dt_s;
    // A turn moves a mesh's points by up to the angle times their farthest distance
    // from the axis (analytic walls turn about their own axis: their surface stays).
    if (norm2(turn) > 0.0) body.displacement_since_build_m += norm(turn) * spin_reach_m(b);
    body.displacement_since_build_m += norm(step);
    body.pose.turn_and_shift(turn, motion.axis_point_m, step);
    body.travel_m += norm(step);
    body.displacement_m += step;
    motion.axis_point_m += step;
    for (WallPrimitive& p : primitives)
      if (p.body == b) p.point_m += step;
  }
}

std::vector<double> WallSet::surface_steps_m(double time_s, double dt_s) {
  std::vector<double> steps(bodies.size(), 0.0);
  for (std::uint32_t b = 0; b < bodies.size(); ++b) {
    const WallMotion& motion = bodies[b].motion;
    if (!motion.active_at(time_s) || !motion.moves()) continue;
    steps[b] = dt_s * fastest_surface_speed_m_per_s(b);
  }
  return steps;
}

double WallSet::fastest_surface_speed_m_per_s(std::uint32_t body) {
  const WallMotion& motion = bodies[body].motion;
  if (!motion.moves()) return 0.0;
  return norm(motion.velocity_m_per_s) + norm(motion.angular_velocity_rad_per_s) * spin_reach_m(body);
}

double WallSet::max_displacement_since_build_m() const {
  double largest = 0.0;
  for (const WallBody& b : bodies) largest = std::max(largest, b.displacement_since_build_m);
  return largest;
}

void WallSet::mark_neighbor_build() {
  for (WallBody& b : bodies) b.displacement_since_build_m = 0.0;
}

}  // namespace regodem
