#include "io/stl_writer.hpp"

#include <fmt/format.h>

#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/error.hpp"
#include "io/atomic_file.hpp"

namespace regodem {
namespace {

constexpr std::size_t header_bytes = 80;

std::string sanitized(std::string_view name) {
  std::string out(name.empty() ? std::string_view("regodem") : name);
  for (char& c : out)
    if (std::isspace(static_cast<unsigned char>(c)) || c == '\0') c = '_';
  return out;
}

void check_finite(const TriangleMesh& mesh) {
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Vec3& v = mesh.vertices[i];
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
      throw InputError(fmt::format("STL writer: vertex {} ({}, {}, {}) is not finite", i, v.x, v.y, v.z));
  }
}

// STL binary is little-endian whatever the host: write byte by byte.
void put_u32(std::string& out, std::uint32_t value) {
  for (int b = 0; b < 4; ++b) out.push_back(static_cast<char>((value >> (8 * b)) & 0xffU));
}

void put_f32(std::string& out, double value) {
  const float f = static_cast<float>(value);
  if (!std::isfinite(f))
    throw InputError(fmt::format("STL writer: coordinate {} does not fit in a 32-bit float (binary STL)", value));
  put_u32(out, std::bit_cast<std::uint32_t>(f));
}

std::string binary_bytes(const TriangleMesh& mesh, std::string_view name) {
  const std::size_t count = mesh.triangle_count();
  if (count > std::numeric_limits<std::uint32_t>::max())
    throw InputError(fmt::format("STL writer: {} triangles do not fit a binary STL's 32-bit count", count));
  std::string out = "binary STL from RegoDEM: " + sanitized(name);
  out.resize(header_bytes, ' ');
  put_u32(out, static_cast<std::uint32_t>(count));
  out.reserve(header_bytes + 4 + 50 * count);
  for (std::size_t t = 0; t < count; ++t) {
    const Vec3 n = mesh.normal(t);  // zero for a degenerate triangle
    put_f32(out, n.x);
    put_f32(out, n.y);
    put_f32(out, n.z);
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = mesh.corner(t, k);
      put_f32(out, p.x);
      put_f32(out, p.y);
      put_f32(out, p.z);
    }
    out.push_back('\0');  // attribute byte count: 0
    out.push_back('\0');
  }
  return out;
}

std::string ascii_bytes(const TriangleMesh& mesh, std::string_view name) {
  const std::string solid = sanitized(name);
  std::string out = fmt::format("solid {}\n", solid);
  // {} formats a double as the shortest text that parses back to it (fmt's default).
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const Vec3 n = mesh.normal(t);  // zero for a degenerate triangle
    out += fmt::format("  facet normal {} {} {}\n    outer loop\n", n.x, n.y, n.z);
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = mesh.corner(t, k);
      out += fmt::format("      vertex {} {} {}\n", p.x, p.y, p.z);
    }
    out += "    endloop\n  endfacet\n";
  }
  out += fmt::format("endsolid {}\n", solid);
  return out;
}

}  // namespace

// ---------------------------------------------------------------------------------
std::string stl_bytes(const TriangleMesh& mesh, StlFormat format, std::string_view solid_name) {
  check_finite(mesh);
  return format == StlFormat::binary ? binary_bytes(mesh, solid_name) : ascii_bytes(mesh, solid_name);
}

void write_stl(const std::filesystem::path& path, const TriangleMesh& mesh, StlFormat format,
               std::string_view solid_name) {
  write_file_atomically(path, stl_bytes(mesh, format, solid_name));
}

}  // namespace regodem
