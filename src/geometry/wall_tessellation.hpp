#pragma once
// Triangles of the analytic walls, for pictures (ParaView), never for contacts: planes
// clipped to the domain box, disks as fans, cylinder shells as bands of quads. Each
// triangle remembers its wall body (a sieve segment is a body of its own) and the
// primitive it comes from (kNoPrimitive for a mesh wall's triangles, which are the
// mesh's own, at the wall's current pose).
#include <array>
#include <cstdint>
#include <vector>

#include "core/vec3.hpp"
#include "geometry/wall_set.hpp"

namespace regodem {

inline constexpr std::uint32_t kNoPrimitive = 0xFFFFFFFFu;

struct WallSurface {
  std::vector<Vec3> points_m;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<std::uint32_t> body;       // per triangle: index into WallSet::bodies
  std::vector<std::uint32_t> primitive;  // per triangle: index into WallSet::primitives, or kNoPrimitive
};

/// The walls at their current positions. `segments_around`: edges of a full circle
/// (at least 3). A plane that misses the domain box gives no triangles.
WallSurface tessellate_walls(const WallSet& walls, const Vec3& domain_min_m, const Vec3& domain_max_m,
                             int segments_around = 64);

/// The polygon where a plane cuts an axis-aligned box, its corners in order around the
/// plane's normal; empty when the plane misses the box or only touches an edge.
std::vector<Vec3> clip_plane_to_box(const Vec3& point_m, const Vec3& unit_normal, const Vec3& box_min_m,
                                    const Vec3& box_max_m);

}  // namespace regodem
