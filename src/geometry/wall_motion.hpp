#pragma once
// Prescribed rigid motion of a wall: translation at a constant velocity plus rotation
// at a constant angular velocity about an axis through axis_point, active for
// start_s <= t < stop_s; the translation (a drill's feed) also ends once the wall has
// travelled max_travel_m along it. Analytic walls may rotate only about their own
// symmetry axis, so their shape stays put and only their surface moves; mesh walls
// turn as rigid bodies.
#include <limits>

#include "core/vec3.hpp"

namespace regodem {

struct WallMotion {
  Vec3 velocity_m_per_s;
  Vec3 angular_velocity_rad_per_s;
  Vec3 axis_point_m;  // moves with the translation
  double start_s = 0.0;
  double stop_s = std::numeric_limits<double>::infinity();
  double max_travel_m = std::numeric_limits<double>::infinity();  // along velocity; the feed then stops
  // The feed also stops for good once the particles push back against it with this
  // force (the thrust, -F . feed direction): a piston lowered onto a bed until it
  // carries a chosen load, a drill at its thrust limit.
  double max_thrust_N = std::numeric_limits<double>::infinity();

  bool active_at(double time_s) const { return time_s >= start_s && time_s < stop_s; }
  bool moves() const { return norm2(velocity_m_per_s) > 0.0 || norm2(angular_velocity_rad_per_s) > 0.0; }

  /// Velocity of the wall's material point at p while the motion is active.
  Vec3 surface_velocity(const Vec3& p, double time_s) const {
    if (!active_at(time_s)) return {};
    return velocity_m_per_s + cross(angular_velocity_rad_per_s, p - axis_point_m);
  }
};

}  // namespace regodem
