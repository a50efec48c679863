#pragma once
// Reads the geometry of a Wavefront OBJ file into a TriangleMesh.
//
// Understood: `v x y z [w ...]` (extra numbers such as w or vertex colours are
// ignored) and `f` with corners written `v`, `v/vt`, `v//vn` or `v/vt/vn`; indices are
// 1-based, negative ones count back from the last vertex defined before the face.
// Polygons are fan-triangulated from their first corner (right for the convex faces
// exporters write). Every other line (vt, vn, o, g, s, usemtl, mtllib, l, #...) is
// ignored. Positions go through TriangleMeshBuilder: exactly equal positions are
// merged, unused `v` lines are left out, zero-area triangles dropped and counted.
// Coordinates are returned as stored; scale them with a MeshTransform.
// Every problem throws InputError naming the file and the line.
#include <string>

#include "geometry/triangle_mesh.hpp"

namespace regodem {

TriangleMesh read_obj(const std::string& path);

}  // namespace regodem
