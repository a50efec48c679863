#pragma once
// VTK XML PolyData (.vtp), the format ParaView reads for point clouds and surfaces.
//
// The arrays go into one raw appended block after the XML header
// (<AppendedData encoding="raw">), each as a UInt64 byte count followed by its bytes,
// or, compressed, as VTK's zlib block layout: a header [block count, block size, size
// of the last block, compressed size of each block] then the zlib streams. Raw
// appended data is what VTK itself writes by default: no base64 inflation, and the
// reader can seek straight to an array. The byte order is the machine's, as declared.
#include <array>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "core/vec3.hpp"

namespace regodem {

struct VtpOptions {
  bool compress = true;  // zlib (fast level): integer fields shrink a lot, doubles a little
};

class VtpDocument {
 public:
  explicit VtpDocument(VtpOptions options = {}) : options_(options) {}

  /// The points (Float64 x, y, z). Call once, before the cells and the point data.
  void set_points(std::span<const Vec3> points_m);
  /// One vertex cell per point, so that every ParaView representation shows them.
  void add_vertex_per_point();
  /// Triangles as three point indices each.
  void set_triangles(std::span<const std::array<std::uint32_t, 3>> triangles);

  // Point data (one tuple per point) and cell data (one per cell); throw
  // std::invalid_argument when the length does not match.
  void add_point_data(const std::string& name, std::span<const double> values);
  void add_point_data(const std::string& name, std::span<const Vec3> values);
  void add_point_data(const std::string& name, std::span<const std::uint16_t> values);
  void add_point_data(const std::string& name, std::span<const std::uint32_t> values);
  void add_cell_data(const std::string& name, std::span<const double> values);
  void add_cell_data(const std::string& name, std::span<const Vec3> values);
  void add_cell_data(const std::string& name, std::span<const std::uint32_t> values);
  void add_cell_data(const std::string& name, std::span<const std::uint8_t> values);

  /// Field data: values about the whole data set ("TimeValue" is ParaView's time).
  void add_field_data(const std::string& name, std::span<const double> values);
  void add_field_strings(const std::string& name, const std::vector<std::string>& values);

  std::size_t point_count() const { return point_count_; }
  std::size_t cell_count() const { return cell_count_; }

  /// The whole file.
  std::string to_string() const;

 private:
  enum class Place { field, point, cell, points, verts, polys };
  struct Array {
    Place place;
    std::string name;
    const char* type;   // VTK type name: Float64, UInt32...
    int components;
    std::size_t tuples;
    std::string bytes;  // the values, native byte order
  };
  void add(Place place, const std::string& name, const char* type, int components, std::size_t tuples,
           const void* data, std::size_t byte_count);
  void check_length(Place place, const std::string& name, std::size_t tuples) const;

  VtpOptions options_;
  std::vector<Array> arrays_;
  std::size_t point_count_ = 0;
  std::size_t cell_count_ = 0;
  std::size_t vert_count_ = 0;
  std::size_t poly_count_ = 0;
  bool has_points_ = false;
};

/// Writes the document to `path` whole (temporary file, then rename).
void write_vtp(const std::filesystem::path& path, const VtpDocument& document);

}  // namespace regodem
