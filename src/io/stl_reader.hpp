#pragma once
// Reads an STL file (binary or ASCII) into a TriangleMesh with shared vertices.
//
// Binary vs ASCII: a file whose size is exactly 84 + 50 n, n being the triangle count
// in its header, is binary even when its 80-byte header starts with "solid" (many
// exporters write that). Otherwise a file starting with "solid" that holds no NUL
// byte is read as ASCII; anything else is a binary file of the wrong size, refused
// as truncated or as having a wrong triangle count.
//
// Coordinates are returned as stored (often millimetres): apply a MeshTransform with
// the scale. The facet normals in the file are ignored; the winding gives the normal.
// Exactly equal vertices are merged and zero-area triangles dropped and counted
// (see TriangleMeshBuilder). Every problem throws InputError naming the file and, in
// ASCII, the line, or, in binary, the triangle index (from 0).
#include <string>

#include "geometry/triangle_mesh.hpp"

namespace regodem {

TriangleMesh read_stl(const std::string& path);

}  // namespace regodem
