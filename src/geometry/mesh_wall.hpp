#pragma once
// A triangle-mesh wall (a drill, a container read from STL/OBJ): its triangles and
// their grid in the reference frame, the body (motion, thermal mode, force tally) it
// belongs to, and the query the contact pass makes of it.
#include <cstdint>
#include <vector>

#include "core/particle_store.hpp"
#include "geometry/mesh_contact.hpp"
#include "geometry/mesh_grid.hpp"
#include "geometry/rigid_pose.hpp"
#include "geometry/triangle_mesh.hpp"

namespace regodem {

struct MeshWall {
  /// cell_size_m: the grid's cell edge (<= 0: the mesh's mean edge length).
  MeshWall(TriangleMesh reference_mesh, std::uint32_t body_index, MaterialIndex material_index,
           double cell_size_m = 0.0);

  TriangleMesh mesh;  // in the reference frame: the body's pose maps it to the world
  MeshGrid grid;
  std::uint32_t body = 0;
  MaterialIndex material = 0;
  // The thermal segment of each triangle, when the wall's body is a segmented lumped
  // wall (geometry/mesh_axial_segments.hpp); empty: the body is one thermal node.
  std::vector<std::uint16_t> triangle_segment;
  // A sphere around every vertex, in the reference frame: cheap rejection of
  // particles far from the mesh, and how far a turn can move its surface.
  Vec3 bounding_centre_m;
  double bounding_radius_m = 0.0;
};

/// One contact of a sphere with a mesh wall, in the world frame.
struct MeshTouch {
  double distance_m = 0.0;  // sphere centre to contact point (< radius)
  Vec3 normal;              // unit, from the sphere centre towards the contact point
  Vec3 contact_point_m;
  std::uint32_t entry = 0;  // index into the candidate triangles passed to find()
};

/// Finds a sphere's contacts with a mesh wall among given candidate triangles, each
/// face, edge or vertex touch once (mesh_contacts_among); holds its scratch space so
/// the per-particle query does not allocate once warm. One per thread.
class MeshTouchFinder {
 public:
  /// triangles[0 .. count): candidate triangle indices, ascending (a particle's
  /// neighbour-list entries for this wall). `out` is overwritten.
  void find(const MeshWall& wall, const RigidPose& pose, const std::uint32_t* triangles, std::uint32_t count,
            const Vec3& centre_m, double radius_m, std::vector<MeshTouch>& out);

 private:
  std::vector<std::uint32_t> candidates_;
  std::vector<MeshContact> contacts_, collected_;
};

}  // namespace regodem
