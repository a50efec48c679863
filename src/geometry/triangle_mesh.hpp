#pragma once
// A triangle mesh as the mesh walls will use it: unique vertices and triangles that
// index them, so triangles sharing an edge or a vertex share the indices (the contact
// code needs that to count an edge or vertex touch once, not once per triangle).
// The file readers (io/stl_reader, io/obj_reader) build meshes through
// TriangleMeshBuilder, which merges vertices whose coordinates are exactly equal and
// drops degenerate triangles; a placement (scale, rotation, translation) is applied
// afterwards with MeshTransform, since files are often in millimetres.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/matrix3.hpp"
#include "core/vec3.hpp"

namespace regodem {

struct Aabb {
  Vec3 lo_m;
  Vec3 hi_m;
};

/// x -> R (s x) + t: scale about the file's origin, then rotate about it, then translate.
struct MeshTransform {
  double scale = 1.0;                                          // e.g. 1e-3 for a file in mm
  Matrix3 rotation = identity_matrix3();  // proper rotation
  Vec3 translation_m;

  /// Rotation by angle_rad about axis (need not be unit; right-hand rule), Rodrigues' formula.
  /// Throws InputError for a zero or non-finite axis, a non-finite angle, or a bad scale.
  static MeshTransform from_axis_angle(double scale, const Vec3& axis, double angle_rad, const Vec3& translation_m);
  /// Rotation given as a matrix; throws InputError unless it is orthonormal with
  /// determinant +1 (within 1e-9), or when the scale is not finite and positive.
  static MeshTransform from_matrix(double scale, const Matrix3& rotation, const Vec3& translation_m);

  Vec3 apply(const Vec3& x) const;
  /// Rotation only (for normals and directions).
  Vec3 rotate(const Vec3& v) const;
};

struct TriangleMesh {
  std::vector<Vec3> vertices;                         // unique (exact-equality merge)
  std::vector<std::array<std::uint32_t, 3>> triangles;  // indices into vertices; winding as in the file
  std::size_t dropped_degenerate_triangles = 0;       // zero-area triangles removed on reading
  std::size_t merged_duplicate_vertices = 0;          // vertex references that reused an existing vertex
  std::string source;                                 // file it came from (for messages); may be empty

  std::size_t triangle_count() const { return triangles.size(); }
  const Vec3& corner(std::size_t triangle, int k) const {
    return vertices[triangles[triangle][static_cast<std::size_t>(k)]];
  }
  /// Unit normal by the right-hand rule on the stored winding (the STL normal is not kept).
  Vec3 normal(std::size_t triangle) const;
  double triangle_area(std::size_t triangle) const;
  double area() const;
  /// Exact: the componentwise min and max over the vertices. Zero box for an empty mesh.
  Aabb bounding_box() const;
  /// Moves every vertex in place; a positive scale and a proper rotation keep the winding.
  void apply(const MeshTransform& transform);
};

/// Builds a TriangleMesh from triangles given by their corner positions.
///
/// Vertices are merged only when their coordinates are bit-for-bit equal (after
/// treating -0.0 as 0.0), through a hash map; nearly equal vertices stay distinct, so
/// a mesh whose neighbours disagree in the last bit keeps a crack there. STL files
/// from CAD exporters repeat each shared vertex exactly, which this catches.
///
/// A triangle is degenerate, and dropped and counted, when its area is no more than
/// 1e-12 of |e1| |e2| (the sine of its angle at the first corner is below 1e-12:
/// the corners are collinear to rounding), which includes repeated corners.
/// Corners must be finite; the readers check that before calling add_triangle.
class TriangleMeshBuilder {
 public:
  /// Returns false (and counts it) when the triangle is degenerate and was dropped.
  bool add_triangle(const Vec3& a, const Vec3& b, const Vec3& c);
  std::size_t triangle_count() const { return mesh_.triangles.size(); }
  std::size_t dropped_degenerate_triangles() const { return mesh_.dropped_degenerate_triangles; }
  TriangleMesh finish(std::string source) &&;

 private:
  using Key = std::array<std::uint64_t, 3>;
  struct KeyHash {
    std::size_t operator()(const Key& k) const noexcept;
  };
  std::uint32_t vertex_index(const Vec3& p);

  TriangleMesh mesh_;
  std::unordered_map<Key, std::uint32_t, KeyHash> index_of_;
};

}  // namespace regodem
