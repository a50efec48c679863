#pragma once
// Writes a TriangleMesh as an STL file, binary (the default: compact, and exact to
// float precision) or ASCII (readable; coordinates written as the shortest decimal
// that reads back to the same double, so an ASCII round trip is exact).
//
// Facet normals are computed from the winding (right-hand rule), as io/stl_reader
// assumes when it ignores them; a degenerate triangle gets the zero normal. The
// binary header never starts with "solid", so no reader mistakes it for ASCII.
// The file is written whole through write_file_atomically (io/atomic_file.hpp).
//
// Reading a written file back with read_stl gives the same triangles, corner by
// corner and in the same order (binary: each coordinate rounded to float); for a mesh
// built by TriangleMeshBuilder, the vertex and triangle arrays come back identical
// (after that rounding), unless the rounding merges two vertices or makes a triangle
// degenerate.
#include <filesystem>
#include <string>
#include <string_view>

#include "geometry/triangle_mesh.hpp"

namespace regodem {

enum class StlFormat { binary, ascii };

/// The STL file's content. solid_name goes into the ASCII "solid" line and the binary
/// header (whitespace replaced by '_'). Throws InputError for a non-finite vertex, a
/// coordinate too large for a float (binary), or more than 2^32 - 1 triangles. An
/// empty mesh gives a valid file with no facets (which read_stl refuses as empty).
std::string stl_bytes(const TriangleMesh& mesh, StlFormat format = StlFormat::binary,
                      std::string_view solid_name = "regodem");

/// Writes stl_bytes(...) to path atomically. Throws InputError as stl_bytes does and
/// std::system_error naming the file when it cannot be written.
void write_stl(const std::filesystem::path& path, const TriangleMesh& mesh, StlFormat format = StlFormat::binary,
               std::string_view solid_name = "regodem");

}  // namespace regodem
