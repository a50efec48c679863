#include "io/vtp_writer.hpp"

#include <zlib.h>

#include <bit>
#include <cstring>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

#include "io/atomic_file.hpp"

namespace regodem {
namespace {

// VTK's readers accept any block size; larger blocks compress a little better and
// keep the header short.
constexpr std::size_t kCompressionBlockBytes = std::size_t{1} << 16;
// The fast zlib level: snapshots of large beds are written during the run, and
// floating-point fields gain little from harder compression.
constexpr int kCompressionLevel = 1;

std::string xml_escaped(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

void append_u64(std::string& out, std::uint64_t value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

/// One array's block in the appended data: a byte count and the bytes, or VTK's
/// compressed layout (see the header comment).
std::string encoded_block(const std::string& bytes, bool compress) {
  std::string out;
  if (!compress) {
    append_u64(out, bytes.size());
    out += bytes;
    return out;
  }
  const std::size_t full_blocks = bytes.size() / kCompressionBlockBytes;
  const std::size_t last_block = bytes.size() % kCompressionBlockBytes;
  const std::size_t blocks = full_blocks + (last_block > 0 ? 1 : 0);
  std::vector<std::string> compressed(blocks);
  for (std::size_t b = 0; b < blocks; ++b) {
    const std::size_t begin = b * kCompressionBlockBytes;
    const std::size_t size = std::min(kCompressionBlockBytes, bytes.size() - begin);
    uLongf capacity = compressBound(static_cast<uLong>(size));
    compressed[b].resize(capacity);
    const int status = compress2(reinterpret_cast<Bytef*>(compressed[b].data()), &capacity,
                                 reinterpret_cast<const Bytef*>(bytes.data() + begin), static_cast<uLong>(size),
                                 kCompressionLevel);
    if (status != Z_OK) throw std::runtime_error(fmt::format("zlib compression failed (status {})", status));
    compressed[b].resize(capacity);
  }
  append_u64(out, blocks);
  append_u64(out, kCompressionBlockBytes);
  append_u64(out, last_block);
  for (const std::string& block : compressed) append_u64(out, block.size());
  for (const std::string& block : compressed) out += block;
  return out;
}

/// Connectivity and offsets of cells, Int32 while the indices fit (half the bytes).
template <class Index>
std::string index_bytes(const std::vector<std::uint64_t>& values) {
  std::string bytes(values.size() * sizeof(Index), '\0');
  for (std::size_t i = 0; i < values.size(); ++i) {
    const auto v = static_cast<Index>(values[i]);
    std::memcpy(bytes.data() + i * sizeof(Index), &v, sizeof(Index));
  }
  return bytes;
}

}  // namespace

void VtpDocument::add(Place place, const std::string& name, const char* type, int components, std::size_t tuples,
                      const void* data, std::size_t byte_count) {
  Array array{place, name, type, components, tuples, std::string(byte_count, '\0')};
  if (byte_count > 0) std::memcpy(array.bytes.data(), data, byte_count);
  arrays_.push_back(std::move(array));
}

void VtpDocument::check_length(Place place, const std::string& name, std::size_t tuples) const {
  const std::size_t expected = place == Place::point ? point_count_ : cell_count_;
  if (tuples != expected)
    throw std::invalid_argument(fmt::format("VTK array '{}' has {} values for {} {}", name, tuples, expected,
                                            place == Place::point ? "points" : "cells"));
}

void VtpDocument::set_points(std::span<const Vec3> points_m) {
  if (has_points_) throw std::logic_error("VtpDocument: points set twice");
  static_assert(sizeof(Vec3) == 3 * sizeof(double), "Vec3 must be three packed doubles");
  has_points_ = true;
  point_count_ = points_m.size();
  add(Place::points, "Points", "Float64", 3, points_m.size(), points_m.data(), points_m.size_bytes());
}

void VtpDocument::add_vertex_per_point() {
  std::vector<std::uint64_t> connectivity(point_count_), offsets(point_count_);
  for (std::size_t i = 0; i < point_count_; ++i) {
    connectivity[i] = i;
    offsets[i] = i + 1;
  }
  const bool narrow = point_count_ < static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max());
  const char* type = narrow ? "Int32" : "Int64";
  for (auto* values : {&connectivity, &offsets}) {
    const std::string bytes = narrow ? index_bytes<std::int32_t>(*values) : index_bytes<std::int64_t>(*values);
    add(Place::verts, values == &connectivity ? "connectivity" : "offsets", type, 1, values->size(), bytes.data(),
        bytes.size());
  }
  vert_count_ = point_count_;
  cell_count_ = vert_count_ + poly_count_;
}

void VtpDocument::set_triangles(std::span<const std::array<std::uint32_t, 3>> triangles) {
  std::vector<std::uint64_t> connectivity, offsets;
  connectivity.reserve(3 * triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    for (const std::uint32_t corner : triangles[t]) {
      if (corner >= point_count_)
        throw std::invalid_argument(fmt::format("triangle {} names point {} of {}", t, corner, point_count_));
      connectivity.push_back(corner);
    }
    offsets.push_back(3 * (t + 1));
  }
  const bool narrow = connectivity.size() < static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max());
  const char* type = narrow ? "Int32" : "Int64";
  for (auto* values : {&connectivity, &offsets}) {
    const std::string bytes = narrow ? index_bytes<std::int32_t>(*values) : index_bytes<std::int64_t>(*values);
    add(Place::polys, values == &connectivity ? "connectivity" : "offsets", type, 1, values->size(), bytes.data(),
        bytes.size());
  }
  poly_count_ = triangles.size();
  cell_count_ = vert_count_ + poly_count_;
}

void VtpDocument::add_point_data(const std::string& name, std::span<const double> values) {
  check_length(Place::point, name, values.size());
  add(Place::point, name, "Float64", 1, values.size(), values.data(), values.size_bytes());
}
void VtpDocument::add_point_data(const std::string& name, std::span<const Vec3> values) {
  check_length(Place::point, name, values.size());
  add(Place::point, name, "Float64", 3, values.size(), values.data(), values.size_bytes());
}
void VtpDocument::add_point_data(const std::string& name, std::span<const std::uint16_t> values) {
  check_length(Place::point, name, values.size());
  add(Place::point, name, "UInt16", 1, values.size(), values.data(), values.size_bytes());
}
void VtpDocument::add_point_data(const std::string& name, std::span<const std::uint32_t> values) {
  check_length(Place::point, name, values.size());
  add(Place::point, name, "UInt32", 1, values.size(), values.data(), values.size_bytes());
}
void VtpDocument::add_cell_data(const std::string& name, std::span<const double> values) {
  check_length(Place::cell, name, values.size());
  add(Place::cell, name, "Float64", 1, values.size(), values.data(), values.size_bytes());
}
void VtpDocument::add_cell_data(const std::string& name, std::span<const Vec3> values) {
  check_length(Place::cell, name, values.size());
  add(Place::cell, name, "Float64", 3, values.size(), values.data(), values.size_bytes());
}
void VtpDocument::add_cell_data(const std::string& name, std::span<const std::uint32_t> values) {
  check_length(Place::cell, name, values.size());
  add(Place::cell, name, "UInt32", 1, values.size(), values.data(), values.size_bytes());
}
void VtpDocument::add_cell_data(const std::string& name, std::span<const std::uint8_t> values) {
  check_length(Place::cell, name, values.size());
  add(Place::cell, name, "UInt8", 1, values.size(), values.data(), values.size_bytes());
}

void VtpDocument::add_field_data(const std::string& name, std::span<const double> values) {
  add(Place::field, name, "Float64", 1, values.size(), values.data(), values.size_bytes());
}

void VtpDocument::add_field_strings(const std::string& name, const std::vector<std::string>& values) {
  // VTK stores a string array as the characters of each value, each ended by a NUL.
  std::string bytes;
  for (const std::string& value : values) {
    if (value.find('\0') != std::string::npos)
      throw std::invalid_argument(fmt::format("VTK string array '{}' holds a NUL character", name));
    bytes += value;
    bytes += '\0';
  }
  add(Place::field, name, "String", 1, values.size(), bytes.data(), bytes.size());
}

std::string VtpDocument::to_string() const {
  if (!has_points_) throw std::logic_error("VtpDocument: no points set");
  std::string appended;
  std::string xml = fmt::format(
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"{}\" "
      "header_type=\"UInt64\"{}>\n  <PolyData>\n",
      std::endian::native == std::endian::little ? "LittleEndian" : "BigEndian",
      options_.compress ? " compressor=\"vtkZLibDataCompressor\"" : "");

  auto write_arrays = [&](Place place, const char* indent) {
    for (const Array& a : arrays_) {
      if (a.place != place) continue;
      const bool is_string = std::strcmp(a.type, "String") == 0;
      xml += fmt::format("{}<{} type=\"{}\" Name=\"{}\"", indent, is_string ? "Array" : "DataArray", a.type,
                         xml_escaped(a.name));
      if (a.components != 1) xml += fmt::format(" NumberOfComponents=\"{}\"", a.components);
      if (place == Place::field) xml += fmt::format(" NumberOfTuples=\"{}\"", a.tuples);
      xml += fmt::format(" format=\"appended\" offset=\"{}\"/>\n", appended.size());
      appended += encoded_block(a.bytes, options_.compress);
    }
  };
  auto section = [&](const char* tag, Place place) {
    xml += fmt::format("      <{}>\n", tag);
    write_arrays(place, "        ");
    xml += fmt::format("      </{}>\n", tag);
  };

  xml += "    <FieldData>\n";
  write_arrays(Place::field, "      ");
  xml += "    </FieldData>\n";
  xml += fmt::format(
      "    <Piece NumberOfPoints=\"{}\" NumberOfVerts=\"{}\" NumberOfLines=\"0\" NumberOfStrips=\"0\" "
      "NumberOfPolys=\"{}\">\n",
      point_count_, vert_count_, poly_count_);
  section("PointData", Place::point);
  section("CellData", Place::cell);
  section("Points", Place::points);
  if (vert_count_ > 0) section("Verts", Place::verts);
  if (poly_count_ > 0) section("Polys", Place::polys);
  xml += "    </Piece>\n  </PolyData>\n  <AppendedData encoding=\"raw\">\n   _";
  xml += appended;
  xml += "\n  </AppendedData>\n</VTKFile>\n";
  return xml;
}

void write_vtp(const std::filesystem::path& path, const VtpDocument& document) {
  write_file_atomically(path, document.to_string());
}

}  // namespace regodem
