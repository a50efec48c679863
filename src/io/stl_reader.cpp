#include "io/stl_reader.hpp"

#include <fmt/format.h>

#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string_view>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "io/text_words.hpp"

namespace regodem {
namespace {

constexpr std::size_t header_bytes = 84;    // 80-byte header + uint32 triangle count
constexpr std::size_t triangle_bytes = 50;  // normal, 3 corners (float32 x 3 each), uint16 attribute

std::string read_whole_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError(fmt::format("{}: is a directory, not an STL file", path));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot open the STL file (missing or unreadable)", path));
  std::string data{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw InputError(fmt::format("{}: read error in the STL file", path));
  return data;
}

std::uint32_t u32_at(std::string_view data, std::size_t at) {
  std::uint32_t value = 0;
  for (std::size_t b = 0; b < 4; ++b)
    value |= static_cast<std::uint32_t>(static_cast<unsigned char>(data[at + b])) << (8 * b);
  return value;
}

float f32_at(std::string_view data, std::size_t at) { return std::bit_cast<float>(u32_at(data, at)); }

bool starts_with_solid(std::string_view data) {
  std::size_t i = 0;
  while (i < data.size() && std::isspace(static_cast<unsigned char>(data[i]))) ++i;
  if (data.size() - i < 5) return false;
  for (std::size_t k = 0; k < 5; ++k)
    if (std::tolower(static_cast<unsigned char>(data[i + k])) != "solid"[k]) return false;
  return true;
}

void throw_if_empty(const TriangleMeshBuilder& builder, const std::string& path) {
  if (builder.triangle_count() > 0) return;
  if (builder.dropped_degenerate_triangles() > 0)
    throw InputError(fmt::format("{}: empty mesh: all {} triangles are degenerate (zero area) and were dropped", path,
                                 builder.dropped_degenerate_triangles()));
  throw InputError(fmt::format("{}: empty mesh: the file holds no triangles", path));
}

// ---------------------------------------------------------------------------------
TriangleMesh read_binary(std::string_view data, const std::string& path) {
  const std::uint32_t count = u32_at(data, 80);
  TriangleMeshBuilder builder;
  for (std::uint32_t t = 0; t < count; ++t) {
    const std::size_t base = header_bytes + triangle_bytes * t + 12;  // skip the normal
    Vec3 corners[3];
    for (std::size_t k = 0; k < 3; ++k) {
      const std::size_t at = base + 12 * k;
      const double x = f32_at(data, at), y = f32_at(data, at + 4), z = f32_at(data, at + 8);
      if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
        throw InputError(fmt::format("{}: triangle {} (counting from 0), corner {}: vertex is not finite ({}, {}, {})",
                                     path, t, k, x, y, z));
      corners[k] = {x, y, z};
    }
    builder.add_triangle(corners[0], corners[1], corners[2]);
  }
  throw_if_empty(builder, path);
  return std::move(builder).finish(path);
}

// ---------------------------------------------------------------------------------

std::string lower(std::string_view word) {
  std::string out(word);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

/// Parses the whole word as a double; false if it is not a number.

TriangleMesh read_ascii(std::string_view data, const std::string& path) {
  enum class State { outside, in_solid, in_facet };
  State state = State::outside;
  TriangleMeshBuilder builder;
  Vec3 corners[3];
  std::size_t corner_count = 0;
  std::size_t facet_line = 0;
  std::size_t line_number = 0;
  std::size_t pos = 0;
  while (pos < data.size()) {
    std::size_t eol = data.find('\n', pos);
    if (eol == std::string_view::npos) eol = data.size();
    const std::string_view line = data.substr(pos, eol - pos);
    pos = eol + 1;
    ++line_number;
    const std::vector<std::string_view> words = split_words(line);
    if (words.empty()) continue;
    const std::string keyword = lower(words[0]);
    auto fail = [&](const std::string& problem) {
      return InputError(fmt::format("{}:{}: {}", path, line_number, problem));
    };
    if (keyword == "solid") {
      if (state != State::outside) throw fail("'solid' before the previous solid's 'endsolid'");
      state = State::in_solid;
    } else if (keyword == "endsolid") {
      if (state == State::in_facet)
        throw fail(fmt::format("'endsolid' inside the facet begun on line {} (missing 'endfacet')", facet_line));
      if (state == State::outside) throw fail("'endsolid' without 'solid'");
      state = State::outside;
    } else if (keyword == "facet") {
      if (state == State::in_facet)
        throw fail(fmt::format("'facet' inside the facet begun on line {} (missing 'endfacet')", facet_line));
      if (state == State::outside) throw fail("'facet' outside a 'solid'");
      state = State::in_facet;
      corner_count = 0;
      facet_line = line_number;
    } else if (keyword == "outer" || keyword == "endloop") {
      if (state != State::in_facet) throw fail(fmt::format("'{}' outside a facet", words[0]));
    } else if (keyword == "vertex") {
      if (state != State::in_facet) throw fail("'vertex' outside a facet");
      if (words.size() != 4)
        throw fail(fmt::format("malformed vertex line: expected 'vertex x y z', found {} numbers", words.size() - 1));
      double xyz[3];
      for (std::size_t k = 0; k < 3; ++k) {
        if (!parse_double(words[k + 1], xyz[k]))
          throw fail(fmt::format("malformed vertex line: '{}' is not a number", words[k + 1]));
        if (!std::isfinite(xyz[k]))
          throw fail(fmt::format("vertex is not finite: coordinate '{}'", words[k + 1]));
      }
      if (corner_count == 3)
        throw fail(fmt::format("the facet begun on line {} has more than 3 vertices; an STL facet has 3", facet_line));
      corners[corner_count++] = {xyz[0], xyz[1], xyz[2]};
    } else if (keyword == "endfacet") {
      if (state != State::in_facet) throw fail("'endfacet' without 'facet'");
      if (corner_count != 3)
        throw fail(fmt::format("the facet begun on line {} has {} vertices; an STL facet has 3", facet_line,
                               corner_count));
      builder.add_triangle(corners[0], corners[1], corners[2]);
      state = State::in_solid;
    } else {
      throw fail(fmt::format("unexpected '{}' in an ASCII STL file (expected solid, facet, outer loop, vertex, "
                             "endloop, endfacet or endsolid)",
                             words[0]));
    }
  }
  if (state == State::in_facet)
    throw InputError(fmt::format("{}:{}: the file ends inside the facet begun on line {} (truncated?)", path,
                                 line_number, facet_line));
  if (state == State::in_solid)
    throw InputError(fmt::format("{}:{}: the file ends before 'endsolid' (truncated?)", path, line_number));
  throw_if_empty(builder, path);
  return std::move(builder).finish(path);
}

}  // namespace

// ---------------------------------------------------------------------------------
TriangleMesh read_stl(const std::string& path) {
  const std::string data = read_whole_file(path);
  const std::string_view view(data);
  const std::size_t size = data.size();
  std::uint64_t claimed = 0;
  std::uint64_t expected = 0;
  if (size >= header_bytes) {
    claimed = u32_at(view, 80);
    expected = header_bytes + triangle_bytes * claimed;
    if (size == expected) return read_binary(view, path);
  }
  if (starts_with_solid(view) && view.find('\0') == std::string_view::npos) return read_ascii(view, path);
  if (size < header_bytes)
    throw InputError(fmt::format("{}: not an STL file: {} bytes, shorter than a binary STL header (84 bytes), and "
                                 "not ASCII (which starts with 'solid')",
                                 path, size));
  if ((size - header_bytes) % triangle_bytes == 0)
    throw InputError(fmt::format("{}: wrong triangle count in the binary STL header: it says {} triangles "
                                 "(84 + 50 n = {} bytes) but the file has {} bytes, room for {} triangles",
                                 path, claimed, expected, size, (size - header_bytes) / triangle_bytes));
  throw InputError(fmt::format("{}: truncated or corrupted binary STL: its size, {} bytes, is not 84 + 50 n for a "
                               "whole number n of triangles (the header says {} triangles, {} bytes)",
                               path, size, claimed, expected));
}

}  // namespace regodem
