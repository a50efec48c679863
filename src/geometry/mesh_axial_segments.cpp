#include "geometry/mesh_axial_segments.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"

namespace regodem {

MeshAxialSegments split_mesh_along_axis(const TriangleMesh& mesh, const Vec3& axis, int count) {
  if (count < 1 || count > 65535) throw InputError(fmt::format("a mesh takes 1 to 65535 segments, got {}", count));
  if (!(norm(axis) > 0.0)) throw InputError("the axis to cut a mesh along is zero");
  const Vec3 unit = normalized(axis);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Vec3& v : mesh.vertices) {
    lo = std::min(lo, dot(v, unit));
    hi = std::max(hi, dot(v, unit));
  }
  if (!(hi > lo)) throw InputError("the mesh has no length along its axis to cut into segments");
  MeshAxialSegments out;
  out.length_m = hi - lo;
  out.area_m2.assign(static_cast<std::size_t>(count), 0.0);
  out.triangle_segment.resize(mesh.triangle_count());
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const double s = dot((mesh.corner(t, 0) + mesh.corner(t, 1) + mesh.corner(t, 2)) * (1.0 / 3.0), unit);
    const int k = std::clamp(static_cast<int>(std::floor((s - lo) / out.length_m * count)), 0, count - 1);
    out.triangle_segment[t] = static_cast<std::uint16_t>(k);
    out.area_m2[static_cast<std::size_t>(k)] += mesh.triangle_area(t);
  }
  for (int k = 0; k < count; ++k)
    if (!(out.area_m2[static_cast<std::size_t>(k)] > 0.0))
      throw InputError(fmt::format("segment {} of {} along the mesh holds no triangle: use fewer segments (or a finer "
                                   "mesh)",
                                   k + 1, count));
  return out;
}

}  // namespace regodem
