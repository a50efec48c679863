#pragma once
// The walls of a simulation: user-level bodies (a name, a motion, the force and torque
// the particles exert on it) and what they are made of: analytic primitives and
// triangle meshes.
#include <string>
#include <vector>

#include "geometry/mesh_wall.hpp"
#include "geometry/rigid_pose.hpp"
#include "geometry/wall_motion.hpp"
#include "geometry/wall_primitive.hpp"

namespace regodem {

struct WallBody {
  std::string name;
  WallMotion motion;
  Vec3 force_N;               // reaction of the particles on the wall, last step
  Vec3 torque_N_m;            // about motion.axis_point_m, last step
  Vec3 displacement_m;        // total translation since the start
  RigidPose pose;             // reference frame -> world (mesh walls)
  double travel_m = 0.0;      // distance moved along the feed (the velocity)
  double depth_at_start_m = 0.0;  // drill depth = depth_at_start_m + travel_m
  // Unit directions of the motion as given (kept after the feed stops): the drill's
  // thrust is -force . feed_direction, its torque -torque . spin_axis.
  Vec3 feed_direction;
  Vec3 spin_axis;
  // Upper bound on how far any surface point moved since the neighbour lists were
  // built: the translation plus, for a turning mesh, the arc its farthest point swept.
  double displacement_since_build_m = 0.0;
  // Farthest mesh vertex from the spin axis, cached with the axis (reference frame) it
  // was found for.
  bool spin_reach_cached = false;
  Vec3 spin_reach_axis, spin_reach_point;
  double spin_reach_m = 0.0;

  double depth_m() const { return depth_at_start_m + travel_m; }
  /// A drill's motion: fed along a direction, turned about an axis (the outputs' depth,
  /// thrust, drive torque and work are given for such walls).
  bool fed() const { return norm2(feed_direction) > 0.0; }
  bool spun() const { return norm2(spin_axis) > 0.0; }
  bool fed_or_spun() const { return fed() || spun(); }
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

  /// A triangle mesh given in the reference frame (its placement at the start).
  /// cell_size_m: its contact grid's cell edge (<= 0: the mesh's mean edge length).
  void add_mesh(std::uint32_t body, TriangleMesh mesh, MaterialIndex material, double cell_size_m = 0.0);

  /// Moves the walls whose motion is active during [time_s, time_s + dt_s).
  void advance(double time_s, double dt_s);
  /// Per body: the largest distance a point of its surface moves in one step of dt_s
  /// from time_s (feed plus spin times its meshes' reach from the axis; 0 at rest).
  std::vector<double> surface_steps_m(double time_s, double dt_s);
  /// The speed of the body's fastest surface point under its motion as given (feed plus
  /// spin times its meshes' reach from the axis), whether or not the motion is active.
  double fastest_surface_speed_m_per_s(std::uint32_t body);
  /// Largest wall translation since the neighbour list was built.
  double max_displacement_since_build_m() const;
  void mark_neighbor_build();

  std::vector<WallBody> bodies;
  std::vector<WallPrimitive> primitives;
  std::vector<MeshWall> meshes;

 private:
  /// Farthest vertex of the body's meshes from its spin axis (0 without meshes).
  double spin_reach_m(std::uint32_t body);
};

}  // namespace regodem
