// STL writer: a mesh written as binary or ASCII STL reads back (io/stl_reader) to the
// same vertices and triangles, in the same order (binary: coordinates rounded to
// float, bit for bit; ASCII: exactly); the binary layout and the facet normals; bad
// meshes and unwritable paths refused.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include "core/error.hpp"
#include "geometry/triangle_mesh.hpp"
#include "io/stl_reader.hpp"
#include "io/stl_writer.hpp"

namespace regodem {
namespace {

namespace fs = std::filesystem;

/// The unit cube, wound outwards, then turned and moved so that its coordinates are
/// not representable in float (the binary round trip must round them).
TriangleMesh turned_cube() {
  const std::array<Vec3, 8> v = {Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{1, 1, 0}, Vec3{0, 1, 0},
                                 Vec3{0, 0, 1}, Vec3{1, 0, 1}, Vec3{1, 1, 1}, Vec3{0, 1, 1}};
  const std::array<std::array<int, 4>, 6> quads = {
      {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 4, 7, 3}, {1, 2, 6, 5}}};
  TriangleMeshBuilder builder;
  for (const auto& q : quads) {
    builder.add_triangle(v[q[0]], v[q[1]], v[q[2]]);
    builder.add_triangle(v[q[0]], v[q[2]], v[q[3]]);
  }
  TriangleMesh mesh = std::move(builder).finish("cube");
  mesh.apply(MeshTransform::from_axis_angle(0.0123, Vec3{1, 2, 3}, 0.7, Vec3{0.1, -0.2, 0.3}));
  return mesh;
}

/// x rounded to float. Through a volatile: GCC 12.2's SLP vectorizer turns
/// {(float)p.x, (float)p.y} widened back to double into a plain copy (wrong code at -O2).
double float_rounded(double x) {
  volatile float f = static_cast<float>(x);
  return f;
}
Vec3 to_float(const Vec3& p) { return {float_rounded(p.x), float_rounded(p.y), float_rounded(p.z)}; }

class StlWriter : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = (fs::temp_directory_path() / "regodem-stlw-XXXXXX").string();
    ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
    directory_ = pattern;
  }
  void TearDown() override { fs::remove_all(directory_); }
  fs::path directory_;
};

#define EXPECT_CONTAINS(text, part) EXPECT_NE(std::string(text).find(part), std::string::npos) << (text)

// ---------------------------------------------------------------------------------
TEST_F(StlWriter, BinaryRoundTripGivesTheSameTrianglesBitExactAfterFloatRounding) {
  const TriangleMesh mesh = turned_cube();
  const fs::path path = directory_ / "cube.stl";
  write_stl(path, mesh);  // binary is the default
  const TriangleMesh back = read_stl(path.string());
  ASSERT_EQ(back.triangles, mesh.triangles);  // same order, same sharing
  ASSERT_EQ(back.vertices.size(), mesh.vertices.size());
  bool some_rounded = false;
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    EXPECT_EQ(back.vertices[i], to_float(mesh.vertices[i])) << "vertex " << i;
    some_rounded = some_rounded || back.vertices[i] != mesh.vertices[i];
  }
  EXPECT_TRUE(some_rounded);  // the test would prove nothing on float-exact input
  EXPECT_EQ(back.dropped_degenerate_triangles, 0U);
}

TEST_F(StlWriter, AsciiRoundTripGivesExactlyTheSameMesh) {
  const TriangleMesh mesh = turned_cube();
  const fs::path path = directory_ / "cube_ascii.stl";
  write_stl(path, mesh, StlFormat::ascii, "turned cube");
  const TriangleMesh back = read_stl(path.string());
  // Stronger than float precision: the shortest round-trip decimal gives the doubles back.
  EXPECT_EQ(back.vertices, mesh.vertices);
  EXPECT_EQ(back.triangles, mesh.triangles);
}

TEST_F(StlWriter, BinaryLayoutHeaderCountAndWindingNormals) {
  const TriangleMesh mesh = turned_cube();
  const std::string bytes = stl_bytes(mesh, StlFormat::binary, "my part");
  ASSERT_EQ(bytes.size(), 84U + 50U * mesh.triangle_count());
  EXPECT_NE(bytes.rfind("solid", 0), 0U);  // an ASCII sniffer must not take it for text
  EXPECT_CONTAINS(bytes.substr(0, 80), "my_part");
  std::uint32_t count = 0;
  for (int b = 0; b < 4; ++b)
    count |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[80 + static_cast<std::size_t>(b)])) << (8 * b);
  EXPECT_EQ(count, mesh.triangle_count());
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    std::array<float, 3> n{};
    std::memcpy(n.data(), bytes.data() + 84 + 50 * t, 12);  // little-endian host assumed here
    const Vec3 expected = to_float(mesh.normal(t));
    EXPECT_EQ((Vec3{n[0], n[1], n[2]}), expected) << "triangle " << t;
    EXPECT_EQ(bytes[84 + 50 * t + 48], '\0');
    EXPECT_EQ(bytes[84 + 50 * t + 49], '\0');
  }
}

TEST_F(StlWriter, AsciiFacetNormalsAreTheWindingNormals) {
  const TriangleMesh mesh = turned_cube();
  std::istringstream text(stl_bytes(mesh, StlFormat::ascii, "cube"));
  std::string line;
  std::getline(text, line);
  EXPECT_EQ(line, "solid cube");
  std::size_t t = 0;
  std::string last;
  while (std::getline(text, line)) {
    last = line;
    std::istringstream words(line);
    std::string first, second;
    words >> first >> second;
    if (first != "facet") continue;
    ASSERT_EQ(second, "normal");
    Vec3 n;
    words >> n.x >> n.y >> n.z;
    ASSERT_LT(t, mesh.triangle_count());
    EXPECT_EQ(n, mesh.normal(t)) << "triangle " << t;
    ++t;
  }
  EXPECT_EQ(t, mesh.triangle_count());
  EXPECT_EQ(last, "endsolid cube");
}

TEST_F(StlWriter, NonFiniteVertexOrFloatOverflowIsRefused) {
  TriangleMesh mesh = turned_cube();
  mesh.vertices[3].y = std::numeric_limits<double>::quiet_NaN();
  for (StlFormat format : {StlFormat::binary, StlFormat::ascii}) {
    try {
      (void)stl_bytes(mesh, format);
      ADD_FAILURE() << "no InputError";
    } catch (const InputError& e) {
      EXPECT_CONTAINS(e.what(), "vertex 3");
      EXPECT_CONTAINS(e.what(), "not finite");
    }
  }
  mesh = turned_cube();
  mesh.vertices[0].x = 1e39;  // a double, but beyond float's 3.4e38
  EXPECT_NO_THROW((void)stl_bytes(mesh, StlFormat::ascii));
  try {
    (void)stl_bytes(mesh, StlFormat::binary);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_CONTAINS(e.what(), "32-bit float");
  }
}

TEST_F(StlWriter, UnwritablePathThrowsSystemErrorAndLeavesNoFile) {
  const fs::path path = directory_ / "no_such_dir" / "cube.stl";
  EXPECT_THROW(write_stl(path, turned_cube()), std::system_error);
  EXPECT_FALSE(fs::exists(path));
}

}  // namespace
}  // namespace regodem
