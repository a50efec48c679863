#pragma once
// Analytic wall shapes and their one geometric query: the closest wall point to a
// sphere centre. A user's wall (a capped cylinder) is made of several primitives
// that share its motion, material and force tally through `body`.
#include <cstdint>

#include "core/particle_store.hpp"
#include "core/vec3.hpp"

namespace regodem {

enum class PrimitiveShape : std::uint8_t { plane, disk, cylinder };

struct WallPrimitive {
  PrimitiveShape shape = PrimitiveShape::plane;
  Vec3 point_m;     // plane: a point on it; disk: centre; cylinder: centre of the bottom end
  Vec3 axis;        // unit. plane: normal towards the particles; disk: normal; cylinder: bottom -> top
  double radius_m = 0.0;   // disk, cylinder
  double length_m = 0.0;   // cylinder
  bool contact_inside = true;    // cylinder: particles inside it feel it
  bool contact_outside = false;  // cylinder: particles outside it feel it
  bool rim_bottom = false;       // cylinder: open bottom end has an edge particles can touch
  bool rim_top = false;          // cylinder: open top end has an edge
  MaterialIndex material = 0;
  std::uint32_t body = 0;        // index of the wall (WallBody) it belongs to
};

struct WallProximity {
  bool candidate = false;   // false: this primitive cannot touch the sphere from where it is
  double distance_m = 0.0;  // from the sphere centre to the closest wall point (may be < 0 behind a plane)
  Vec3 normal;              // unit, from the sphere centre towards the wall point
  Vec3 contact_point_m;     // closest wall point
};

WallProximity closest_wall_point(const WallPrimitive& wall, const Vec3& centre_m);

/// Whether the segment between two sphere centres passes through the wall's surface (a
/// disk's face, a cylinder shell between its ends). Walls have no thickness, so two
/// particles pressed against a sieve from opposite sides overlap each other through
/// it; such pairs are kept out of the neighbour lists, or they would push and conduct
/// straight through the wall. A plane is one-sided: nothing lies behind it.
bool segment_crosses_wall(const WallPrimitive& wall, const Vec3& a_m, const Vec3& b_m);

}  // namespace regodem
