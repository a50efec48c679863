// Triangle meshes read from STL (binary and ASCII) and OBJ: the same cube loads to the
// same shared-vertex triangles whatever the format; a placement moves it exactly; a
// bad file is refused with its name (and line, or triangle) and the problem.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "geometry/triangle_mesh.hpp"
#include "io/obj_reader.hpp"
#include "io/stl_reader.hpp"

namespace regodem {
namespace {

namespace fs = std::filesystem;

using Triangle = std::array<Vec3, 3>;

const std::string mesh_data_dir = std::string(REGODEM_SOURCE_DIR) + "/tests/data/meshes/";

/// The unit cube [0,1]^3 as 12 triangles wound outwards: the quads of
/// tests/data/meshes/cube_quads.obj fanned from their first corner, in the same order.
std::vector<Triangle> unit_cube_triangles() {
  const std::array<Vec3, 8> v = {Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{1, 1, 0}, Vec3{0, 1, 0},
                                 Vec3{0, 0, 1}, Vec3{1, 0, 1}, Vec3{1, 1, 1}, Vec3{0, 1, 1}};
  const std::array<std::array<int, 4>, 6> quads = {
      {{1, 4, 3, 2}, {5, 6, 7, 8}, {1, 2, 6, 5}, {3, 4, 8, 7}, {1, 5, 8, 4}, {2, 3, 7, 6}}};
  std::vector<Triangle> out;
  for (const auto& q : quads) {
    out.push_back({v[q[0] - 1], v[q[1] - 1], v[q[2] - 1]});
    out.push_back({v[q[0] - 1], v[q[2] - 1], v[q[3] - 1]});
  }
  return out;
}

std::string ascii_stl(const std::vector<Triangle>& triangles) {
  std::string text = "solid cube\n";
  for (const Triangle& t : triangles) {
    text += "  facet normal 0 0 0\n    outer loop\n";
    for (const Vec3& p : t) text += "      vertex " + std::to_string(p.x) + " " + std::to_string(p.y) + " " +
                                    std::to_string(p.z) + "\n";
    text += "    endloop\n  endfacet\n";
  }
  return text + "endsolid cube\n";
}

void put_u32(std::string& out, std::uint32_t value) {
  for (int b = 0; b < 4; ++b) out.push_back(static_cast<char>((value >> (8 * b)) & 0xffU));
}
void put_f32(std::string& out, float value) { put_u32(out, std::bit_cast<std::uint32_t>(value)); }

std::string binary_stl(const std::vector<Triangle>& triangles, const std::string& header_text = "binary cube",
                       std::int64_t claimed_count = -1) {
  std::string out = header_text;
  out.resize(80, ' ');
  put_u32(out, static_cast<std::uint32_t>(claimed_count < 0 ? static_cast<std::int64_t>(triangles.size())
                                                            : claimed_count));
  for (const Triangle& t : triangles) {
    for (int k = 0; k < 3; ++k) put_f32(out, 0.0f);  // normal, ignored by the reader
    for (const Vec3& p : t) {
      put_f32(out, static_cast<float>(p.x));
      put_f32(out, static_cast<float>(p.y));
      put_f32(out, static_cast<float>(p.z));
    }
    out.push_back('\0');
    out.push_back('\0');
  }
  return out;
}

class MeshFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = (fs::temp_directory_path() / "regodem-mesh-XXXXXX").string();
    ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
    directory_ = pattern;
  }
  void TearDown() override { fs::remove_all(directory_); }

  std::string write(const std::string& name, const std::string& content) const {
    const fs::path path = directory_ / name;
    std::ofstream out(path, std::ios::binary);
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    return path.string();
  }

  /// The message of the InputError that reading throws; fails the test if none.
  template <class Reader>
  static std::string error_of(Reader read, const std::string& path) {
    try {
      read(path);
    } catch (const InputError& e) {
      return e.what();
    }
    ADD_FAILURE() << "no InputError for " << path;
    return "";
  }
  static std::string stl_error(const std::string& path) { return error_of(read_stl, path); }
  static std::string obj_error(const std::string& path) { return error_of(read_obj, path); }

  fs::path directory_;
};

#define EXPECT_CONTAINS(text, part) EXPECT_NE((text).find(part), std::string::npos) << (text)

void expect_unit_cube(const TriangleMesh& mesh) {
  ASSERT_EQ(mesh.triangle_count(), 12U);
  EXPECT_EQ(mesh.vertices.size(), 8U);
  EXPECT_EQ(mesh.dropped_degenerate_triangles, 0U);
  EXPECT_NEAR(mesh.area(), 6.0, 1e-12);
  const Aabb box = mesh.bounding_box();
  EXPECT_EQ(box.lo_m, (Vec3{0, 0, 0}));
  EXPECT_EQ(box.hi_m, (Vec3{1, 1, 1}));
  // The winding of the file is kept: every normal points out of the cube.
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const Vec3 centroid = (mesh.corner(t, 0) + mesh.corner(t, 1) + mesh.corner(t, 2)) / 3.0;
    EXPECT_GT(dot(mesh.normal(t), centroid - Vec3{0.5, 0.5, 0.5}), 0.0) << "triangle " << t;
  }
}

void expect_same_mesh(const TriangleMesh& a, const TriangleMesh& b) {
  EXPECT_EQ(a.vertices, b.vertices);
  EXPECT_EQ(a.triangles, b.triangles);
}

// ---------------------------------------------------------------------------------
TEST_F(MeshFiles, StlAsciiAndBinaryCubeLoadToTheSameTwelveTrianglesAndEightVertices) {
  const std::vector<Triangle> cube = unit_cube_triangles();
  const TriangleMesh ascii = read_stl(write("cube_ascii.stl", ascii_stl(cube)));
  const TriangleMesh binary = read_stl(write("cube_binary.stl", binary_stl(cube)));
  expect_unit_cube(ascii);
  expect_unit_cube(binary);
  expect_same_mesh(ascii, binary);
  EXPECT_EQ(ascii.merged_duplicate_vertices, 36U - 8U);
  EXPECT_CONTAINS(binary.source, "cube_binary.stl");
}

TEST_F(MeshFiles, StlBinaryWhoseHeaderStartsWithSolidIsReadAsBinary) {
  const std::string path = write("solid_header.stl", binary_stl(unit_cube_triangles(), "solid cube exported by CAD"));
  expect_unit_cube(read_stl(path));
}

TEST_F(MeshFiles, StlAsciiToleratesUppercaseCrLfAndSignedExponents) {
  const std::string text =
      "SOLID part\r\nFACET NORMAL 0 0 1\r\nOUTER LOOP\r\nVERTEX 0 0 0\r\nVERTEX +1.0e+00 0 0\r\n"
      "VERTEX 0 1E0 0\r\nENDLOOP\r\nENDFACET\r\nENDSOLID part\r\n";
  const TriangleMesh mesh = read_stl(write("upper.stl", text));
  ASSERT_EQ(mesh.triangle_count(), 1U);
  EXPECT_EQ(mesh.corner(0, 1), (Vec3{1, 0, 0}));
  EXPECT_EQ(mesh.corner(0, 2), (Vec3{0, 1, 0}));
  EXPECT_NEAR(mesh.area(), 0.5, 1e-15);
}

TEST_F(MeshFiles, StlDegenerateTrianglesAreDroppedAndCounted) {
  std::vector<Triangle> triangles = unit_cube_triangles();
  triangles.push_back({Vec3{0, 0, 0}, Vec3{1, 1, 1}, Vec3{2, 2, 2}});  // collinear
  triangles.push_back({Vec3{1, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1, 0}});  // repeated corner
  for (const std::string& path :
       {write("degenerate.stl", binary_stl(triangles)), write("degenerate_ascii.stl", ascii_stl(triangles))}) {
    const TriangleMesh mesh = read_stl(path);
    EXPECT_EQ(mesh.triangle_count(), 12U) << path;
    EXPECT_EQ(mesh.dropped_degenerate_triangles, 2U) << path;
    EXPECT_EQ(mesh.vertices.size(), 8U) << path;  // the dropped triangles add no vertices
  }
}

TEST_F(MeshFiles, StlNegativeZeroMergesWithZero) {
  std::vector<Triangle> triangles = {{Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1, 0}},
                                     {Vec3{-0.0, -0.0, -0.0}, Vec3{0, 1, 0}, Vec3{-1, 0, 0}}};
  const TriangleMesh mesh = read_stl(write("negzero.stl", binary_stl(triangles)));
  EXPECT_EQ(mesh.vertices.size(), 4U);
  EXPECT_FALSE(std::signbit(mesh.vertices[0].x));
}

// ---------------------------------------------------------------------------------
TEST_F(MeshFiles, StlTruncatedBinaryIsRefused) {
  std::string data = binary_stl(unit_cube_triangles());
  data.resize(data.size() - 20);
  const std::string message = stl_error(write("truncated.stl", data));
  EXPECT_CONTAINS(message, "truncated.stl");
  EXPECT_CONTAINS(message, "truncated");
  EXPECT_CONTAINS(message, "84 + 50 n");
}

TEST_F(MeshFiles, StlWrongTriangleCountInHeaderIsRefused) {
  const std::string message = stl_error(write("count.stl", binary_stl(unit_cube_triangles(), "cube", 13)));
  EXPECT_CONTAINS(message, "count.stl");
  EXPECT_CONTAINS(message, "wrong triangle count");
  EXPECT_CONTAINS(message, "says 13 triangles");
  EXPECT_CONTAINS(message, "room for 12");
}

TEST_F(MeshFiles, StlBinaryNanOrInfVertexIsRefusedWithTriangleIndex) {
  std::vector<Triangle> triangles = unit_cube_triangles();
  triangles[5][1].y = std::numeric_limits<double>::quiet_NaN();
  std::string message = stl_error(write("nan.stl", binary_stl(triangles)));
  EXPECT_CONTAINS(message, "nan.stl");
  EXPECT_CONTAINS(message, "triangle 5");
  EXPECT_CONTAINS(message, "not finite");

  triangles = unit_cube_triangles();
  triangles[11][2].z = std::numeric_limits<double>::infinity();
  message = stl_error(write("inf.stl", binary_stl(triangles)));
  EXPECT_CONTAINS(message, "triangle 11");
  EXPECT_CONTAINS(message, "not finite");
}

TEST_F(MeshFiles, StlAsciiNanVertexIsRefusedWithLine) {
  std::string text = ascii_stl(unit_cube_triangles());
  text.replace(text.find("vertex 1.000000"), 15, "vertex nan");  // first such vertex: line 6
  const std::string message = stl_error(write("nan_ascii.stl", text));
  EXPECT_CONTAINS(message, "nan_ascii.stl:6:");
  EXPECT_CONTAINS(message, "not finite");
}

TEST_F(MeshFiles, StlAsciiMalformedVertexLineIsRefusedWithLine) {
  const std::string head = "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n";
  const std::string tail = "vertex 0 1 0\nendloop\nendfacet\nendsolid s\n";
  std::string message = stl_error(write("short_vertex.stl", head + "vertex 1 0\n" + tail));
  EXPECT_CONTAINS(message, "short_vertex.stl:5:");
  EXPECT_CONTAINS(message, "malformed vertex line");
  message = stl_error(write("word_vertex.stl", head + "vertex 1 zero 0\n" + tail));
  EXPECT_CONTAINS(message, "word_vertex.stl:5:");
  EXPECT_CONTAINS(message, "'zero' is not a number");
  message = stl_error(write("long_vertex.stl", head + "vertex 1 0 0 7\n" + tail));
  EXPECT_CONTAINS(message, "long_vertex.stl:5:");
  EXPECT_CONTAINS(message, "malformed vertex line");
}

TEST_F(MeshFiles, StlAsciiFacetWithoutThreeVerticesIsRefused) {
  std::string message = stl_error(write(
      "two.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid\n"));
  EXPECT_CONTAINS(message, "two.stl:7:");
  EXPECT_CONTAINS(message, "facet begun on line 2 has 2 vertices");
  message = stl_error(write("four.stl",
                            "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                            "vertex 1 1 0\nendloop\nendfacet\nendsolid\n"));
  EXPECT_CONTAINS(message, "four.stl:7:");
  EXPECT_CONTAINS(message, "more than 3 vertices");
}

TEST_F(MeshFiles, StlAsciiTruncatedOrStrayKeywordIsRefused) {
  std::string text = ascii_stl(unit_cube_triangles());
  text.resize(text.find("endloop"));
  std::string message = stl_error(write("cut.stl", text));
  EXPECT_CONTAINS(message, "cut.stl:");
  EXPECT_CONTAINS(message, "ends inside the facet begun on line 2");
  message = stl_error(write("stray.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertx 0 0 0\n"));
  EXPECT_CONTAINS(message, "stray.stl:4:");
  EXPECT_CONTAINS(message, "unexpected 'vertx'");
}

TEST_F(MeshFiles, StlEmptyMeshIsRefused) {
  std::string message = stl_error(write("empty_ascii.stl", "solid nothing\nendsolid nothing\n"));
  EXPECT_CONTAINS(message, "empty_ascii.stl");
  EXPECT_CONTAINS(message, "empty mesh");
  message = stl_error(write("empty_binary.stl", binary_stl({})));
  EXPECT_CONTAINS(message, "empty_binary.stl");
  EXPECT_CONTAINS(message, "empty mesh");
  message = stl_error(
      write("all_degenerate.stl", binary_stl({{Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{2, 0, 0}}})));
  EXPECT_CONTAINS(message, "empty mesh");
  EXPECT_CONTAINS(message, "1 triangles are degenerate");
  message = stl_error(write("zero_bytes.stl", ""));
  EXPECT_CONTAINS(message, "zero_bytes.stl");
  EXPECT_CONTAINS(message, "not an STL file");
}

TEST_F(MeshFiles, StlMissingFileIsRefused) {
  const std::string path = (directory_ / "no_such_mesh.stl").string();
  const std::string message = stl_error(path);
  EXPECT_CONTAINS(message, "no_such_mesh.stl");
  EXPECT_CONTAINS(message, "cannot open");
  EXPECT_CONTAINS(stl_error(directory_.string()), "is a directory");
}

// ---------------------------------------------------------------------------------
TEST(ObjReader, CubeWithQuadsInEveryCornerFormLoadsToTwelveTriangles) {
  const TriangleMesh mesh = read_obj(mesh_data_dir + "cube_quads.obj");
  expect_unit_cube(mesh);
}

TEST_F(MeshFiles, ObjCubeMatchesTheStlCube) {
  const TriangleMesh obj = read_obj(mesh_data_dir + "cube_quads.obj");
  const TriangleMesh stl = read_stl(write("cube.stl", binary_stl(unit_cube_triangles())));
  expect_same_mesh(obj, stl);
}

TEST(ObjReader, NegativeIndicesCountBackFromTheLastVertexDefined) {
  const TriangleMesh relative = read_obj(mesh_data_dir + "cube_negative_indices.obj");
  expect_unit_cube(relative);
  expect_same_mesh(relative, read_obj(mesh_data_dir + "cube_quads.obj"));
}

TEST_F(MeshFiles, ObjPolygonIsFanTriangulatedAndForwardReferencesResolve) {
  // A regular hexagon of unit circumradius (area 3 sqrt(3) / 2), face before its vertices.
  std::string text = "f 1 2 3 4 5 6\n";
  for (int k = 0; k < 6; ++k) {
    const double angle = k * std::numbers::pi / 3.0;
    text += "v " + std::to_string(std::cos(angle)) + " " + std::to_string(std::sin(angle)) + " 0\n";
  }
  const TriangleMesh mesh = read_obj(write("hexagon.obj", text));
  EXPECT_EQ(mesh.triangle_count(), 4U);
  EXPECT_NEAR(mesh.area(), 1.5 * std::sqrt(3.0), 1e-5);  // coordinates written to 6 decimals
}

TEST_F(MeshFiles, ObjBadFilesAreRefusedWithLine) {
  const std::string square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
  std::string message = obj_error(write("range.obj", square + "f 1 2 5\n"));
  EXPECT_CONTAINS(message, "range.obj:5:");
  EXPECT_CONTAINS(message, "vertex 5");
  message = obj_error(write("before.obj", square + "f -1 -2 -5\n"));
  EXPECT_CONTAINS(message, "before.obj:5:");
  EXPECT_CONTAINS(message, "before the first vertex");
  message = obj_error(write("zero.obj", square + "f 0 1 2\n"));
  EXPECT_CONTAINS(message, "zero.obj:5:");
  EXPECT_CONTAINS(message, "start at 1");
  message = obj_error(write("two.obj", square + "f 1 2\n"));
  EXPECT_CONTAINS(message, "two.obj:5:");
  EXPECT_CONTAINS(message, "at least 3 corners");
  message = obj_error(write("corner.obj", square + "f 1/a 2 3\n"));
  EXPECT_CONTAINS(message, "corner.obj:5:");
  EXPECT_CONTAINS(message, "malformed face corner '1/a'");
  message = obj_error(write("vertex.obj", "v 0 0 0\nv 1 0\n"));
  EXPECT_CONTAINS(message, "vertex.obj:2:");
  EXPECT_CONTAINS(message, "malformed vertex line");
  message = obj_error(write("nan.obj", "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n"));
  EXPECT_CONTAINS(message, "nan.obj:3:");
  EXPECT_CONTAINS(message, "not finite");
  message = obj_error(write("faceless.obj", square));
  EXPECT_CONTAINS(message, "faceless.obj");
  EXPECT_CONTAINS(message, "empty mesh");
  message = obj_error((directory_ / "missing.obj").string());
  EXPECT_CONTAINS(message, "missing.obj");
  EXPECT_CONTAINS(message, "cannot open");
}

// ---------------------------------------------------------------------------------
TEST(MeshTransform, ScaleRotationAndTranslationMoveAKnownVertexExactly) {
  TriangleMesh mesh = read_obj(mesh_data_dir + "cube_quads.obj");  // file "in mm"
  const Vec3 t{0.1, 0.2, 0.3};
  mesh.apply(MeshTransform::from_axis_angle(1e-3, {0, 0, 2}, std::numbers::pi / 2.0, t));
  // Vertex 6 of the file, (1, 0, 1) mm -> (1e-3, 0, 1e-3) m -> rotated to (0, 1e-3, 1e-3) -> + t.
  // Vertices are numbered in first-use order: file vertices 1 4 3 2 5 6 ..., so file vertex 6 is index 5.
  EXPECT_NEAR(mesh.vertices[5].x, 0.1, 1e-15);
  EXPECT_NEAR(mesh.vertices[5].y, 0.2 + 1e-3, 1e-15);
  EXPECT_NEAR(mesh.vertices[5].z, 0.3 + 1e-3, 1e-15);
  EXPECT_NEAR(mesh.area(), 6e-6, 1e-18);
  const Aabb box = mesh.bounding_box();
  EXPECT_NEAR(box.lo_m.x, 0.1 - 1e-3, 1e-15);
  EXPECT_NEAR(box.hi_m.x, 0.1, 1e-15);
  EXPECT_NEAR(box.lo_m.y, 0.2, 1e-15);
  EXPECT_NEAR(box.hi_m.z, 0.3 + 1e-3, 1e-15);
}

TEST(MeshTransform, MatrixRotationMatchesAxisAngleAndBadInputsAreRefused) {
  const Matrix3 quarter_turn_z = {{{0, -1, 0}, {1, 0, 0}, {0, 0, 1}}};
  const MeshTransform by_matrix = MeshTransform::from_matrix(2.0, quarter_turn_z, {1, 1, 1});
  EXPECT_EQ(by_matrix.apply({1, 2, 3}), (Vec3{1 - 4, 1 + 2, 1 + 6}));
  const MeshTransform by_angle = MeshTransform::from_axis_angle(2.0, {0, 0, 1}, std::numbers::pi / 2.0, {1, 1, 1});
  const Vec3 a = by_angle.apply({1, 2, 3});
  EXPECT_NEAR(a.x, -3.0, 1e-15);
  EXPECT_NEAR(a.y, 3.0, 1e-15);
  EXPECT_NEAR(a.z, 7.0, 1e-15);

  const Matrix3 mirror = {{{-1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  EXPECT_THROW(MeshTransform::from_matrix(1.0, mirror, {}), InputError);
  const Matrix3 shear = {{{1, 0.1, 0}, {0, 1, 0}, {0, 0, 1}}};
  EXPECT_THROW(MeshTransform::from_matrix(1.0, shear, {}), InputError);
  EXPECT_THROW(MeshTransform::from_axis_angle(1.0, {0, 0, 0}, 1.0, {}), InputError);
  EXPECT_THROW(MeshTransform::from_axis_angle(0.0, {0, 0, 1}, 1.0, {}), InputError);
  EXPECT_THROW(MeshTransform::from_axis_angle(-1e-3, {0, 0, 1}, 1.0, {}), InputError);
}

}  // namespace
}  // namespace regodem
