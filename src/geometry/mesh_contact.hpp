#pragma once
// Sphere–triangle-mesh contact geometry: the closest point of a triangle to a point,
// classified by the feature it lies on, and the set of contacts of a sphere with a
// mesh, each touched face, edge or vertex counted once.
//
// Counting each touch once. A sphere resting across the shared diagonal of two
// coplanar triangles is closest to the same point of both; a sphere over a vertex
// shared by a fan of six triangles is closest to that vertex in all six. Physically
// that is one contact, as on a plane. The rule (see mesh_contacts) keeps a contact
// only where the closest point is a local minimum of the distance over every
// triangle around it, and then merges contacts at the same point:
//
//  1. Collect, for each candidate triangle, its closest point to the centre, if
//     closer than the radius.
//  2. Drop an edge or vertex contact when another collected triangle that contains
//     that edge (both its vertex indices) or that vertex has its closest point
//     elsewhere (more than the tolerance away). That triangle contains this contact
//     point, and a triangle's closest point is unique, so its own is strictly closer:
//     this point is no local minimum of the distance to the surface (the sphere
//     touches that triangle's face, or another edge, instead). A triangle containing
//     the feature that was not collected is no closer than the radius, so it cannot
//     dominate. Face contacts are never dropped. Points are compared, not distances:
//     a centre a small offset delta off a shared edge changes the distances by only
//     about delta^2 / d, which no distance tolerance can resolve, but the points by delta.
//  3. Merge contacts whose points coincide (within the tolerance), and edge contacts
//     with the same edge key and vertex contacts with the same vertex. The one kept is
//     a face before an edge before a vertex (the face's point is the foot of the
//     perpendicular, so its normal is exactly the plane's), then the shorter distance,
//     then the lower triangle index.
//
// Steps 2 and 3 do not depend on two triangles labelling a point on their shared
// boundary alike: where rounding makes one say "edge" and the other "face" or
// "vertex" for the same point, neither is apart from the other, neither is dropped,
// and step 3 merges them.
//
// Tolerance: 1e-9 x radius, plus 64 ulps of the largest coordinate involved (a mesh
// far from the origin rounds at the 1e-16 level of its coordinates, not of the
// radius). Two distinct contacts less than 1e-9 radius apart do not occur in a valid
// mesh; the 1e-12 x radius first suggested would be too tight for a mesh placed metres
// from the origin with millimetre particles.
//
// Concave places are counted right: a sphere in the inside corner of a box touches
// three faces and gets three contacts (face contacts are never dropped, and the three
// points lie far apart), and in the inside edge two. A convex box edge gives one edge
// contact with the normal along the bisector, a convex corner one vertex contact.
//
// Normals point from the sphere centre towards the contact point, as in
// WallProximity. Where the centre lies on the surface (distance 0) the normal is
// minus the triangle's winding normal.
#include <array>
#include <cstdint>
#include <vector>

#include "core/vec3.hpp"
#include "geometry/mesh_grid.hpp"
#include "geometry/triangle_mesh.hpp"

namespace regodem {

enum class MeshFeature : std::uint8_t { face, edge, vertex };

/// The closest point of triangle (a, b, c) to a point, and where on the triangle it
/// lies. local: for an edge, k means the edge from corner k to corner (k + 1) % 3
/// (0: ab, 1: bc, 2: ca); for a vertex, the corner k; 0 for the face.
struct TriangleClosestPoint {
  Vec3 point_m;
  MeshFeature feature = MeshFeature::face;
  int local = 0;
};

/// Ericson's Voronoi-region test (Real-Time Collision Detection, 5.1.5). Boundaries
/// between regions go to the lower-dimensional feature (a point exactly over an edge
/// is an edge point). The triangle must not be degenerate.
TriangleClosestPoint closest_point_on_triangle(const Vec3& p_m, const Vec3& a_m, const Vec3& b_m,
                                               const Vec3& c_m);

struct MeshContact {
  double distance_m = 0.0;  // from the sphere centre to the contact point (< radius)
  Vec3 normal;              // unit, from the sphere centre towards the contact point
  Vec3 contact_point_m;     // closest mesh point
  std::uint32_t triangle = 0;
  MeshFeature feature = MeshFeature::face;
  /// Mesh vertex indices of the feature: an edge's two, ascending; a vertex's index
  /// twice; for a face, the triangle's first two corners (not meaningful).
  std::array<std::uint32_t, 2> vertices = {0, 0};
};

/// Scratch buffers, to keep the per-particle query free of allocations once warm.
struct MeshContactScratch {
  std::vector<std::uint32_t> candidates;
  std::vector<MeshContact> collected;
};

/// All contacts of the sphere (centre_m, radius_m) with the mesh, by the rule above,
/// among the triangles the grid returns for that sphere. Sorted by triangle, then
/// feature. `out` is overwritten. The grid must have been built from this mesh.
void mesh_contacts(const TriangleMesh& mesh, const MeshGrid& grid, const Vec3& centre_m, double radius_m,
                   std::vector<MeshContact>& out, MeshContactScratch& scratch);
void mesh_contacts(const TriangleMesh& mesh, const MeshGrid& grid, const Vec3& centre_m, double radius_m,
                   std::vector<MeshContact>& out);

/// The same rule over a given candidate list (ascending triangle indices), e.g. every
/// triangle of the mesh for a brute-force reference.
void mesh_contacts_among(const TriangleMesh& mesh, const std::vector<std::uint32_t>& candidates,
                         const Vec3& centre_m, double radius_m, std::vector<MeshContact>& out,
                         std::vector<MeshContact>& collected);

}  // namespace regodem
