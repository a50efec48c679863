#pragma once
// A mesh cut into equal axial slices, for a drill that is a rod of lumped segments
// (thermal/thermal_wall.hpp, WallRod): each triangle belongs to the slice that holds its
// centroid, slice 0 at the lowest s = dot(x, axis) (an auger's tip, its axis pointing up).
#include <cstdint>
#include <vector>

#include "geometry/triangle_mesh.hpp"

namespace regodem {

struct MeshAxialSegments {
  std::vector<std::uint16_t> triangle_segment;  // per triangle
  std::vector<double> area_m2;                  // per slice: its triangles' area
  double length_m = 0.0;                        // the mesh's extent along the axis
};

/// Throws InputError when count is outside [1, 65535], the axis is zero, the mesh has no
/// extent along it, or a slice holds no triangle (it would have no heat capacity).
MeshAxialSegments split_mesh_along_axis(const TriangleMesh& mesh, const Vec3& axis, int count);

}  // namespace regodem
