#include "geometry/mesh_wall.hpp"

#include <algorithm>
#include <utility>

namespace regodem {

MeshWall::MeshWall(TriangleMesh reference_mesh, std::uint32_t body_index, MaterialIndex material_index,
                   double cell_size_m)
    : mesh(std::move(reference_mesh)), grid(mesh, cell_size_m), body(body_index), material(material_index) {
  const Aabb box = mesh.bounding_box();
  bounding_centre_m = 0.5 * (box.lo_m + box.hi_m);
  for (const Vec3& v : mesh.vertices) bounding_radius_m = std::max(bounding_radius_m, norm(v - bounding_centre_m));
}

void MeshTouchFinder::find(const MeshWall& wall, const RigidPose& pose, const std::uint32_t* triangles,
                           std::uint32_t count, const Vec3& centre_m, double radius_m, std::vector<MeshTouch>& out) {
  out.clear();
  candidates_.assign(triangles, triangles + count);
  mesh_contacts_among(wall.mesh, candidates_, pose.to_reference(centre_m), radius_m, contacts_, collected_);
  for (const MeshContact& c : contacts_) {
    MeshTouch touch;
    touch.distance_m = c.distance_m;
    touch.normal = multiply(pose.rotation, c.normal);
    touch.contact_point_m = pose.to_world(c.contact_point_m);
    // Candidates are ascending and each contact names one of them.
    touch.entry = static_cast<std::uint32_t>(std::lower_bound(triangles, triangles + count, c.triangle) - triangles);
    out.push_back(touch);
  }
}

}  // namespace regodem
