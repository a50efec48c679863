#pragma once
// The walls of a simulation: user-level bodies (a name, a motion, the force and torque
// the particles exert on it) and the analytic primitives they are made of.
#include <string>
#include <vector>

#include "geometry/wall_motion.hpp"
#include "geometry/wall_primitive.hpp"

namespace regodem {

struct WallBody {
  std::string name;
  WallMotion motion;
  Vec3 force_N;               // reaction of the particles on the wall, last step
  Vec3 torque_N_m;            // about motion.axis_point_m, last step
  Vec3 displacement_m;        // total translation since the start
  double displacement_since_build_m = 0.0;  // for the neighbour-list skin check
};

class WallSet {
 public:
  /// Adds a body; returns its index for the primitives that make it up.
  std::uint32_t add_body(const std::string& name, const WallMotion& motion);
  void add_plane(std::uint32_t body, const Vec3& point_m, const Vec3& normal, MaterialIndex material);
  void add_disk(std::uint32_t body, const Vec3& centre_m, const Vec3& normal, double radius_m,
                MaterialIndex material);
  /// A finite cylinder shell, contact from the inside, the outside or both, each end
  /// open (an edge particles can touch) or capped (a disk).
  void add_cylinder(std::uint32_t body, const Vec3& base_centre_m, const Vec3& axis, double radius_m,
                    double length_m, bool contact_inside, bool contact_outside, bool cap_bottom,
                    bool cap_top, MaterialIndex material);

  /// One segment of a segmented cylinder ("thermal sieve", DESIGN.md section 2):
  /// contact from both sides; an open end has an edge only where it is an end of the
  /// whole sieve (interior joints have none, or a particle there would feel two edges);
  /// cap_bottom closes the segment's bottom with a two-sided disk.
  void add_sieve_segment(std::uint32_t body, const Vec3& base_centre_m, const Vec3& axis, double radius_m,
                         double length_m, bool outer_bottom_end, bool outer_top_end, bool cap_bottom,
                         MaterialIndex material);

  /// Moves the walls whose motion is active during [time_s, time_s + dt_s).
  void advance(double time_s, double dt_s);
  /// Largest wall translation since the neighbour list was built.
  double max_displacement_since_build_m() const;
  void mark_neighbor_build();

  std::vector<WallBody> bodies;
  std::vector<WallPrimitive> primitives;
};

}  // namespace regodem
