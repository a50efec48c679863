#include "geometry/mesh_inside.hpp"

#include <cmath>
#include <numbers>

namespace regodem {

// ---------------------------------------------------------------------------------
double winding_number(const TriangleMesh& mesh, const Vec3& p) {
  double sum = 0.0;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const Vec3 a = mesh.corner(t, 0) - p;
    const Vec3 b = mesh.corner(t, 1) - p;
    const Vec3 c = mesh.corner(t, 2) - p;
    const double la = norm(a), lb = norm(b), lc = norm(c);
    // Van Oosterom & Strackee (IEEE Trans. Biomed. Eng. 30, 1983):
    // tan(Omega / 2) = a.(b x c) / (|a||b||c| + (a.b)|c| + (a.c)|b| + (b.c)|a|).
    // atan2 keeps the quadrant, so Omega spans (-2 pi, 2 pi].
    const double numerator = dot(a, cross(b, c));
    const double denominator = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
    sum += 2.0 * std::atan2(numerator, denominator);
  }
  return sum / (4.0 * std::numbers::pi);
}

bool point_inside(const TriangleMesh& mesh, const Vec3& p) { return winding_number(mesh, p) >= 0.5; }

double enclosed_volume(const TriangleMesh& mesh) {
  if (mesh.vertices.empty()) return 0.0;
  const Vec3 o = mesh.vertices.front();
  double six_volume = 0.0;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
    six_volume += dot(mesh.corner(t, 0) - o, cross(mesh.corner(t, 1) - o, mesh.corner(t, 2) - o));
  return six_volume / 6.0;
}

}  // namespace regodem
