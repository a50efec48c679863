#pragma once
// Inside/outside and volume of a closed triangle mesh, or of a union of closed
// shells (the generated auger is one: a core and a blade per flute, overlapping).
//
// The generalized winding number w(p) = sum over triangles of the signed solid angle
// the triangle subtends at p, divided by 4 pi. For a closed, outward-wound shell it is
// 1 inside and 0 outside; over a union of such shells it counts the shells that hold
// p, so "inside the union" is w >= 1/2. It tolerates small cracks and overlaps (it
// varies smoothly across a hole instead of jumping), which ray casting does not.
// A point exactly on the surface is neither reliably in nor out: the triangle it lies
// on contributes +-1/2 or 0 depending on the sign of a rounded zero. Cost: one pass
// over all triangles per point (no grid); fine for tests and set-up checks, not for
// the force loop.
#include "core/vec3.hpp"
#include "geometry/triangle_mesh.hpp"

namespace regodem {

/// Generalized winding number of the mesh about p (see above).
double winding_number(const TriangleMesh& mesh, const Vec3& p);

/// winding_number(mesh, p) >= 0.5.
bool point_inside(const TriangleMesh& mesh, const Vec3& p);

/// Signed volume enclosed by a closed mesh, by the divergence theorem: the sum of the
/// signed tetrahedra (o, a, b, c) / 6 over its triangles, o being any fixed point (the
/// first vertex, to keep the terms small). Positive for an outward winding. For a
/// union of shells, the sum of the shells' volumes (overlaps counted twice).
double enclosed_volume(const TriangleMesh& mesh);

}  // namespace regodem
