#include "geometry/triangle_mesh.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <utility>

#include "core/error.hpp"

namespace regodem {
namespace {

void check_scale(double scale) {
  if (!std::isfinite(scale) || scale <= 0.0)
    throw InputError(fmt::format("mesh transform: the scale must be finite and positive, not {}", scale));
}

void check_finite(const Vec3& v, const char* what) {
  if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
    throw InputError(fmt::format("mesh transform: the {} ({}, {}, {}) is not finite", what, v.x, v.y, v.z));
}

}  // namespace

// ---------------------------------------------------------------------------------
MeshTransform MeshTransform::from_axis_angle(double scale, const Vec3& axis, double angle_rad,
                                             const Vec3& translation_m) {
  check_scale(scale);
  check_finite(axis, "rotation axis");
  check_finite(translation_m, "translation");
  if (!std::isfinite(angle_rad))
    throw InputError(fmt::format("mesh transform: the rotation angle {} is not finite", angle_rad));
  const double length = norm(axis);
  if (length == 0.0) throw InputError("mesh transform: the rotation axis is the zero vector");
  const Vec3 k = axis / length;
  const double c = std::cos(angle_rad);
  const double s = std::sin(angle_rad);
  const double t = 1.0 - c;
  MeshTransform xf;
  xf.scale = scale;
  xf.translation_m = translation_m;
  xf.rotation = {{{c + t * k.x * k.x, t * k.x * k.y - s * k.z, t * k.x * k.z + s * k.y},
                  {t * k.y * k.x + s * k.z, c + t * k.y * k.y, t * k.y * k.z - s * k.x},
                  {t * k.z * k.x - s * k.y, t * k.z * k.y + s * k.x, c + t * k.z * k.z}}};
  return xf;
}

MeshTransform MeshTransform::from_matrix(double scale, const Matrix3& rotation, const Vec3& translation_m) {
  check_scale(scale);
  check_finite(translation_m, "translation");
  constexpr double tolerance = 1e-9;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      if (!std::isfinite(rotation[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)]))
        throw InputError("mesh transform: the rotation matrix has a non-finite entry");
    }
  // Columns orthonormal: R^T R = I.
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j) {
      double sum = 0.0;
      for (std::size_t r = 0; r < 3; ++r) sum += rotation[r][i] * rotation[r][j];
      const double expected = i == j ? 1.0 : 0.0;
      if (std::abs(sum - expected) > tolerance)
        throw InputError(fmt::format(
            "mesh transform: the rotation matrix is not orthonormal (column {} . column {} = {}, expected {})", i, j,
            sum, expected));
    }
  const Matrix3& m = rotation;
  const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                     m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  if (std::abs(det - 1.0) > tolerance)
    throw InputError(fmt::format(
        "mesh transform: the rotation matrix has determinant {} (a reflection); a rotation has +1", det));
  MeshTransform xf;
  xf.scale = scale;
  xf.rotation = rotation;
  xf.translation_m = translation_m;
  return xf;
}

Vec3 MeshTransform::rotate(const Vec3& v) const { return multiply(rotation, v); }

Vec3 MeshTransform::apply(const Vec3& x) const { return rotate(x * scale) + translation_m; }

// ---------------------------------------------------------------------------------
Vec3 TriangleMesh::normal(std::size_t triangle) const {
  return normalized(cross(corner(triangle, 1) - corner(triangle, 0), corner(triangle, 2) - corner(triangle, 0)));
}

double TriangleMesh::triangle_area(std::size_t triangle) const {
  return 0.5 * norm(cross(corner(triangle, 1) - corner(triangle, 0), corner(triangle, 2) - corner(triangle, 0)));
}

double TriangleMesh::area() const {
  double sum = 0.0;
  for (std::size_t t = 0; t < triangles.size(); ++t) sum += triangle_area(t);
  return sum;
}

Aabb TriangleMesh::bounding_box() const {
  if (vertices.empty()) return {};
  Aabb box{vertices.front(), vertices.front()};
  for (const Vec3& v : vertices) {
    box.lo_m = {std::min(box.lo_m.x, v.x), std::min(box.lo_m.y, v.y), std::min(box.lo_m.z, v.z)};
    box.hi_m = {std::max(box.hi_m.x, v.x), std::max(box.hi_m.y, v.y), std::max(box.hi_m.z, v.z)};
  }
  return box;
}

void TriangleMesh::apply(const MeshTransform& transform) {
  for (Vec3& v : vertices) v = transform.apply(v);
}

// ---------------------------------------------------------------------------------
std::size_t TriangleMeshBuilder::KeyHash::operator()(const Key& k) const noexcept {
  // splitmix64-style mixing of each coordinate's bits.
  std::uint64_t h = 0x9e3779b97f4a7c15ULL;
  for (std::uint64_t bits : k) {
    std::uint64_t z = bits + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    h ^= z ^ (z >> 31);
  }
  return static_cast<std::size_t>(h);
}

std::uint32_t TriangleMeshBuilder::vertex_index(const Vec3& p) {
  // + 0.0 turns -0.0 into +0.0, so the two zeros (equal as doubles) share a key.
  const Key key = {std::bit_cast<std::uint64_t>(p.x + 0.0), std::bit_cast<std::uint64_t>(p.y + 0.0),
                   std::bit_cast<std::uint64_t>(p.z + 0.0)};
  const auto next = static_cast<std::uint32_t>(mesh_.vertices.size());
  const auto [where, inserted] = index_of_.try_emplace(key, next);
  if (inserted)
    mesh_.vertices.push_back({p.x + 0.0, p.y + 0.0, p.z + 0.0});
  else
    ++mesh_.merged_duplicate_vertices;
  return where->second;
}

bool TriangleMeshBuilder::add_triangle(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 e1 = b - a;
  const Vec3 e2 = c - a;
  const double twice_area = norm(cross(e1, e2));
  if (!(twice_area > 1e-12 * norm(e1) * norm(e2))) {
    ++mesh_.dropped_degenerate_triangles;
    return false;
  }
  const std::uint32_t ia = vertex_index(a);
  const std::uint32_t ib = vertex_index(b);
  const std::uint32_t ic = vertex_index(c);
  mesh_.triangles.push_back({ia, ib, ic});
  return true;
}

TriangleMesh TriangleMeshBuilder::finish(std::string source) && {
  mesh_.source = std::move(source);
  index_of_.clear();
  return std::move(mesh_);
}

}  // namespace regodem
