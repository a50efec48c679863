#include "io/obj_reader.hpp"

#include <fmt/format.h>

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string_view>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "io/text_words.hpp"

namespace regodem {
namespace {



bool parse_integer(std::string_view word, long long& value) {
  if (word.size() > 1 && word[0] == '+') word.remove_prefix(1);
  const char* end = word.data() + word.size();
  const auto [ptr, ec] = std::from_chars(word.data(), end, value);
  return !word.empty() && ec == std::errc() && ptr == end;
}

struct Face {
  std::size_t line = 0;
  std::vector<long long> corners;  // 0-based vertex indices; forward references checked at the end
};

}  // namespace

TriangleMesh read_obj(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError(fmt::format("{}: is a directory, not an OBJ file", path));
  std::ifstream in(path);
  if (!in) throw InputError(fmt::format("{}: cannot open the OBJ file (missing or unreadable)", path));

  std::vector<Vec3> positions;
  std::vector<Face> faces;
  std::string line;
  std::size_t line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    std::string_view text(line);
    if (const std::size_t hash = text.find('#'); hash != std::string_view::npos) text = text.substr(0, hash);
    const std::vector<std::string_view> words = split_words(text);
    if (words.empty()) continue;
    auto fail = [&](const std::string& problem) {
      return InputError(fmt::format("{}:{}: {}", path, line_number, problem));
    };
    if (words[0] == "v") {
      if (words.size() < 4)
        throw fail(fmt::format("malformed vertex line: expected 'v x y z', found {} numbers", words.size() - 1));
      double xyz[3];
      for (std::size_t k = 0; k < 3; ++k) {
        if (!parse_double(words[k + 1], xyz[k]))
          throw fail(fmt::format("malformed vertex line: '{}' is not a number", words[k + 1]));
        if (!std::isfinite(xyz[k])) throw fail(fmt::format("vertex is not finite: coordinate '{}'", words[k + 1]));
      }
      positions.push_back({xyz[0], xyz[1], xyz[2]});
    } else if (words[0] == "f") {
      if (words.size() < 4)
        throw fail(fmt::format("a face needs at least 3 corners, this one has {}", words.size() - 1));
      Face face;
      face.line = line_number;
      for (std::size_t k = 1; k < words.size(); ++k) {
        const std::string_view corner = words[k];
        // v, v/vt, v//vn or v/vt/vn: only v is used, the others must be integers or empty.
        std::vector<std::string_view> parts;
        std::size_t start = 0;
        while (true) {
          const std::size_t slash = corner.find('/', start);
          const std::size_t length = slash == std::string_view::npos ? std::string_view::npos : slash - start;
          parts.push_back(corner.substr(start, length));
          if (slash == std::string_view::npos) break;
          start = slash + 1;
        }
        long long index = 0;
        bool ok = parts.size() <= 3 && parse_integer(parts[0], index);
        for (std::size_t p = 1; ok && p < parts.size(); ++p) {
          long long ignored = 0;
          ok = parts[p].empty() || parse_integer(parts[p], ignored);
        }
        if (!ok)
          throw fail(fmt::format("malformed face corner '{}' (expected v, v/vt, v//vn or v/vt/vn with integer indices)",
                                 corner));
        if (index == 0) throw fail(fmt::format("face corner '{}': OBJ indices start at 1, 0 is not valid", corner));
        if (index < 0) {
          // Relative: -1 is the last vertex defined so far.
          const long long resolved = static_cast<long long>(positions.size()) + index;
          if (resolved < 0)
            throw fail(fmt::format("face corner '{}': relative index {} reaches before the first vertex (only {} "
                                   "defined so far)",
                                   corner, index, positions.size()));
          face.corners.push_back(resolved);
        } else {
          face.corners.push_back(index - 1);
        }
      }
      faces.push_back(std::move(face));
    }
    // Everything else (vt, vn, vp, o, g, s, usemtl, mtllib, l, p, ...) carries no geometry we use.
  }
  if (in.bad()) throw InputError(fmt::format("{}: read error in the OBJ file", path));

  TriangleMeshBuilder builder;
  for (const Face& face : faces) {
    for (long long index : face.corners)
      if (index >= static_cast<long long>(positions.size()))
        throw InputError(fmt::format("{}:{}: face refers to vertex {}, but the file defines only {} vertices", path,
                                     face.line, index + 1, positions.size()));
    const Vec3& first = positions[static_cast<std::size_t>(face.corners[0])];
    for (std::size_t k = 1; k + 1 < face.corners.size(); ++k)
      builder.add_triangle(first, positions[static_cast<std::size_t>(face.corners[k])],
                           positions[static_cast<std::size_t>(face.corners[k + 1])]);
  }
  if (builder.triangle_count() == 0) {
    if (builder.dropped_degenerate_triangles() > 0)
      throw InputError(fmt::format("{}: empty mesh: all {} triangles are degenerate (zero area) and were dropped",
                                   path, builder.dropped_degenerate_triangles()));
    throw InputError(fmt::format("{}: empty mesh: the file holds no faces ('f' lines)", path));
  }
  return std::move(builder).finish(path);
}

}  // namespace regodem
