#include "geometry/wall_tessellation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace regodem {
namespace {

/// Two unit vectors that make (e1, e2, axis) a right-handed orthonormal basis.
void basis_around(const Vec3& axis, Vec3& e1, Vec3& e2) {
  const Vec3 helper = std::abs(axis.x) < 0.9 ? Vec3{1.0, 0.0, 0.0} : Vec3{0.0, 1.0, 0.0};
  e1 = normalized(cross(helper, axis));
  e2 = cross(axis, e1);
}

class SurfaceBuilder {
 public:
  SurfaceBuilder(WallSurface& surface, std::uint32_t body, std::uint32_t primitive)
      : surface_(surface), body_(body), primitive_(primitive) {}

  std::uint32_t point(const Vec3& p) {
    surface_.points_m.push_back(p);
    return static_cast<std::uint32_t>(surface_.points_m.size() - 1);
  }
  void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    surface_.triangles.push_back({a, b, c});
    surface_.body.push_back(body_);
    surface_.primitive.push_back(primitive_);
  }

 private:
  WallSurface& surface_;
  std::uint32_t body_, primitive_;
};

/// `n` points on a circle, counter-clockwise about the axis; returns the first index.
std::uint32_t ring(SurfaceBuilder& out, const Vec3& centre, const Vec3& axis, double radius, int n) {
  Vec3 e1, e2;
  basis_around(axis, e1, e2);
  std::uint32_t first = 0;
  for (int k = 0; k < n; ++k) {
    const double angle = 2.0 * std::numbers::pi * k / n;
    const std::uint32_t index = out.point(centre + radius * (std::cos(angle) * e1 + std::sin(angle) * e2));
    if (k == 0) first = index;
  }
  return first;
}

}  // namespace

std::vector<Vec3> clip_plane_to_box(const Vec3& point_m, const Vec3& unit_normal, const Vec3& box_min_m,
                                    const Vec3& box_max_m) {
  Vec3 corners[8];
  double height[8];
  for (int c = 0; c < 8; ++c) {
    corners[c] = {(c & 1) ? box_max_m.x : box_min_m.x, (c & 2) ? box_max_m.y : box_min_m.y,
                  (c & 4) ? box_max_m.z : box_min_m.z};
    height[c] = dot(corners[c] - point_m, unit_normal);
  }
  std::vector<Vec3> polygon;
  for (int c = 0; c < 8; ++c)
    if (height[c] == 0.0) polygon.push_back(corners[c]);
  for (int a = 0; a < 8; ++a)
    for (int bit = 1; bit < 8; bit <<= 1) {
      const int b = a | bit;
      if (b == a) continue;  // each edge once, from its lower corner
      if (height[a] * height[b] >= 0.0) continue;  // same side, or a corner on the plane (taken above)
      const double t = height[a] / (height[a] - height[b]);
      polygon.push_back(corners[a] + t * (corners[b] - corners[a]));
    }
  if (polygon.size() < 3) return {};
  Vec3 centre;
  for (const Vec3& p : polygon) centre += p;
  centre = centre / static_cast<double>(polygon.size());
  Vec3 e1, e2;
  basis_around(unit_normal, e1, e2);
  std::sort(polygon.begin(), polygon.end(), [&](const Vec3& p, const Vec3& q) {
    return std::atan2(dot(p - centre, e2), dot(p - centre, e1)) < std::atan2(dot(q - centre, e2), dot(q - centre, e1));
  });
  // A plane through a box corner or edge meets it in repeated points: drop them.
  const double tolerance = 1e-12 * norm(box_max_m - box_min_m);
  std::vector<Vec3> unique;
  for (const Vec3& p : polygon)
    if (unique.empty() || norm(p - unique.back()) > tolerance) unique.push_back(p);
  while (unique.size() > 1 && norm(unique.front() - unique.back()) <= tolerance) unique.pop_back();
  if (unique.size() < 3) return {};
  return unique;
}

WallSurface tessellate_walls(const WallSet& walls, const Vec3& domain_min_m, const Vec3& domain_max_m,
                             int segments_around) {
  const int n = std::max(segments_around, 3);
  WallSurface surface;
  for (std::uint32_t index = 0; index < walls.primitives.size(); ++index) {
    const WallPrimitive& w = walls.primitives[index];
    SurfaceBuilder out(surface, w.body, index);
    switch (w.shape) {
      case PrimitiveShape::plane: {
        const std::vector<Vec3> polygon = clip_plane_to_box(w.point_m, w.axis, domain_min_m, domain_max_m);
        if (polygon.empty()) break;
        const auto first = static_cast<std::uint32_t>(surface.points_m.size());
        for (const Vec3& p : polygon) out.point(p);
        for (std::uint32_t k = 1; k + 1 < polygon.size(); ++k) out.triangle(first, first + k, first + k + 1);
        break;
      }
      case PrimitiveShape::disk: {
        const std::uint32_t centre = out.point(w.point_m);
        const std::uint32_t first = ring(out, w.point_m, w.axis, w.radius_m, n);
        for (int k = 0; k < n; ++k)
          out.triangle(centre, first + static_cast<std::uint32_t>(k), first + static_cast<std::uint32_t>((k + 1) % n));
        break;
      }
      case PrimitiveShape::cylinder: {
        const std::uint32_t bottom = ring(out, w.point_m, w.axis, w.radius_m, n);
        const std::uint32_t top = ring(out, w.point_m + w.length_m * w.axis, w.axis, w.radius_m, n);
        for (int k = 0; k < n; ++k) {
          const auto a = static_cast<std::uint32_t>(k), b = static_cast<std::uint32_t>((k + 1) % n);
          out.triangle(bottom + a, bottom + b, top + b);  // outward normals
          out.triangle(bottom + a, top + b, top + a);
        }
        break;
      }
    }
  }
  // Mesh walls as they stand now (their pose applied); no analytic primitive.
  for (const MeshWall& mesh : walls.meshes) {
    SurfaceBuilder out(surface, mesh.body, kNoPrimitive);
    const auto first = static_cast<std::uint32_t>(surface.points_m.size());
    for (const Vec3& v : mesh.mesh.vertices) out.point(walls.bodies[mesh.body].pose.to_world(v));
    for (const auto& t : mesh.mesh.triangles) out.triangle(first + t[0], first + t[1], first + t[2]);
  }
  return surface;
}

}  // namespace regodem
