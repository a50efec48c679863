// Sphere–mesh contact geometry: the closest point on a triangle by feature, the
// counting of shared edges and vertices once (against an analytic plane, 1e-12), box
// faces, edges and corners from outside and inside, and the grid against brute force.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <tuple>
#include <vector>

#include "geometry/mesh_contact.hpp"
#include "geometry/mesh_grid.hpp"
#include "geometry/triangle_mesh.hpp"
#include "geometry/wall_primitive.hpp"

namespace regodem {
namespace {

constexpr double kTol = 1e-12;

TriangleMesh build(const std::vector<std::array<Vec3, 3>>& triangles) {
  TriangleMeshBuilder builder;
  for (const auto& t : triangles) EXPECT_TRUE(builder.add_triangle(t[0], t[1], t[2]));
  return std::move(builder).finish("test");
}

// The unit square in z = 0 as two triangles sharing the diagonal (0,0,0)-(1,1,0).
TriangleMesh square() {
  return build({{Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{1, 1, 0}}, {Vec3{0, 0, 0}, Vec3{1, 1, 0}, Vec3{0, 1, 0}}});
}

// Six triangles around the origin in z = 0.
TriangleMesh fan() {
  std::vector<std::array<Vec3, 3>> tris;
  for (int k = 0; k < 6; ++k) {
    const double a0 = k * std::numbers::pi / 3.0;
    const double a1 = (k + 1) * std::numbers::pi / 3.0;
    tris.push_back({Vec3{0, 0, 0}, Vec3{std::cos(a0), std::sin(a0), 0}, Vec3{std::cos(a1), std::sin(a1), 0}});
  }
  return build(tris);
}

// [0,1]^3 as 12 triangles; outward winding unless `inward`.
TriangleMesh cube(bool inward = false) {
  const auto v = [](int i) { return Vec3{double(i & 1), double((i >> 1) & 1), double((i >> 2) & 1)}; };
  // Faces as corner quads (counter-clockwise seen from outside).
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  std::vector<std::array<Vec3, 3>> tris;
  for (const auto& q : quads) {
    if (inward) {
      tris.push_back({v(q[0]), v(q[2]), v(q[1])});
      tris.push_back({v(q[0]), v(q[3]), v(q[2])});
    } else {
      tris.push_back({v(q[0]), v(q[1]), v(q[2])});
      tris.push_back({v(q[0]), v(q[2]), v(q[3])});
    }
  }
  return build(tris);
}

TriangleMesh icosphere(int levels) {
  const double g = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3> p = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                         {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  for (Vec3& x : p) x = normalized(x);
  std::vector<std::array<Vec3, 3>> tris;
  const int f[20][3] = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                        {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                        {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  for (const auto& t : f) tris.push_back({p[t[0]], p[t[1]], p[t[2]]});
  for (int l = 0; l < levels; ++l) {
    std::vector<std::array<Vec3, 3>> finer;
    for (const auto& t : tris) {
      // a + b == b + a exactly, so both triangles of an edge make the same midpoint.
      const Vec3 ab = normalized(t[0] + t[1]), bc = normalized(t[1] + t[2]), ca = normalized(t[2] + t[0]);
      finer.push_back({t[0], ab, ca});
      finer.push_back({t[1], bc, ab});
      finer.push_back({t[2], ca, bc});
      finer.push_back({ab, bc, ca});
    }
    tris = std::move(finer);
  }
  return build(tris);
}

// A wavy sheet over [0,2]^2 of n x n quads, each split in two.
TriangleMesh wavy_sheet(int n) {
  const auto z = [](double x, double y) { return 0.05 * std::sin(3.0 * x) * std::cos(2.0 * y); };
  const auto at = [&](int i, int j) {
    const double x = 2.0 * i / n, y = 2.0 * j / n;
    return Vec3{x, y, z(x, y)};
  };
  std::vector<std::array<Vec3, 3>> tris;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      tris.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      tris.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return build(tris);
}

std::vector<MeshContact> contacts_of(const TriangleMesh& mesh, const Vec3& centre, double radius) {
  const MeshGrid grid(mesh);
  std::vector<MeshContact> out;
  mesh_contacts(mesh, grid, centre, radius, out);
  return out;
}

void expect_vec_near(const Vec3& a, const Vec3& b, double tol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

// ---------------------------------------------------------------------------------
TEST(MeshClosestPoint, EachRegionOfATriangle) {
  const Vec3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  struct Case {
    Vec3 p, q;
    MeshFeature feature;
    int local;
  };
  const Case cases[] = {
      {{-1, -1, 1}, {0, 0, 0}, MeshFeature::vertex, 0},    {{2, -0.5, 0}, {1, 0, 0}, MeshFeature::vertex, 1},
      {{-0.5, 3, -1}, {0, 1, 0}, MeshFeature::vertex, 2},  {{0.5, -1, 0.3}, {0.5, 0, 0}, MeshFeature::edge, 0},
      {{1, 1, -2}, {0.5, 0.5, 0}, MeshFeature::edge, 1},   {{-1, 0.25, 0}, {0, 0.25, 0}, MeshFeature::edge, 2},
      {{0.2, 0.3, 5}, {0.2, 0.3, 0}, MeshFeature::face, 0}, {{0.5, 0, 1}, {0.5, 0, 0}, MeshFeature::edge, 0},
  };
  for (const Case& k : cases) {
    const TriangleClosestPoint r = closest_point_on_triangle(k.p, a, b, c);
    expect_vec_near(r.point_m, k.q, kTol);
    EXPECT_EQ(r.feature, k.feature);
    EXPECT_EQ(r.local, k.local);
  }
}

TEST(MeshClosestPoint, NoSampledTrianglePointIsCloser) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 a{u(rng), u(rng), u(rng)}, b{u(rng), u(rng), u(rng)}, c{u(rng), u(rng), u(rng)};
    const Vec3 p{u(rng), u(rng), u(rng)};
    const TriangleClosestPoint r = closest_point_on_triangle(p, a, b, c);
    const double d = norm(r.point_m - p);
    for (int i = 0; i <= 20; ++i)
      for (int j = 0; i + j <= 20; ++j) {
        const Vec3 s = a + (i / 20.0) * (b - a) + (j / 20.0) * (c - a);
        ASSERT_LE(d, norm(s - p) + 1e-12);
      }
  }
}

// ---------------------------------------------------------------------------------
// Two triangles sharing a diagonal must act as one plane: distance and normal within 1e-12.
TEST(MeshContact, SquareAcrossTheDiagonalIsOnePlaneContact) {
  const TriangleMesh mesh = square();
  WallPrimitive plane;
  plane.axis = {0, 0, 1};
  for (int i = 0; i <= 100; ++i) {
    for (const double offset : {0.0, 1e-15, -1e-15, 1e-12, 1e-10, -1e-9, 1e-7, 1e-4}) {
      const double t = 0.05 + 0.9 * i / 100.0;
      const Vec3 centre{t + offset, t, 0.3};
      const std::vector<MeshContact> cs = contacts_of(mesh, centre, 0.4);
      ASSERT_EQ(cs.size(), 1u) << "t = " << t << " offset " << offset;
      const WallProximity ref = closest_wall_point(plane, centre);
      EXPECT_NEAR(cs[0].distance_m, ref.distance_m, kTol);
      expect_vec_near(cs[0].normal, ref.normal, kTol);
      expect_vec_near(cs[0].contact_point_m, ref.contact_point_m, kTol);
    }
  }
  // Exactly over the diagonal both triangles see the same edge point: one edge contact.
  const std::vector<MeshContact> cs = contacts_of(mesh, {0.5, 0.5, 0.3}, 0.4);
  ASSERT_EQ(cs.size(), 1u);
  EXPECT_EQ(cs[0].feature, MeshFeature::edge);
}

TEST(MeshContact, PlacedSquareAcrossTheDiagonalIsOnePlaneContact) {
  // Tilted and moved, so no coordinate is exact and the two triangles round differently.
  const MeshTransform place = MeshTransform::from_axis_angle(2e-3, {0.4, 0.1, -0.9}, 1.3, {0.31, -0.17, 1.9});
  TriangleMesh mesh = square();
  mesh.apply(place);
  const Vec3 origin = place.apply({0, 0, 0});
  const Vec3 up = place.rotate({0, 0, 1});
  const double h = 0.3 * place.scale;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.05, 0.95), tiny(-1e-9, 1e-9);
  for (int trial = 0; trial < 500; ++trial) {
    const double t = u(rng);
    const double off = trial % 2 == 0 ? tiny(rng) : 0.0;
    const Vec3 centre = place.apply({t + off, t, 0.3});
    const std::vector<MeshContact> cs = contacts_of(mesh, centre, 0.4 * place.scale);
    ASSERT_EQ(cs.size(), 1u) << "t = " << t;
    EXPECT_NEAR(cs[0].distance_m, h, kTol * place.scale);
    expect_vec_near(cs[0].normal, -up, kTol);
    EXPECT_NEAR(dot(cs[0].contact_point_m - origin, up), 0.0, kTol * place.scale);
  }
}

TEST(MeshContact, SquareOnASharedCornerVertex) {
  const TriangleMesh mesh = square();
  WallPrimitive plane;
  plane.axis = {0, 0, 1};
  for (const Vec3 centre : {Vec3{0, 0, 0.3}, Vec3{1, 1, 0.3}, Vec3{1e-15, 0, 0.3}, Vec3{1, 1 - 1e-15, 0.3}}) {
    const std::vector<MeshContact> cs = contacts_of(mesh, centre, 0.4);
    ASSERT_EQ(cs.size(), 1u);
    const WallProximity ref = closest_wall_point(plane, centre);
    EXPECT_NEAR(cs[0].distance_m, ref.distance_m, kTol);
    expect_vec_near(cs[0].normal, ref.normal, kTol);
  }
  // Beyond the corner: the vertex alone, at the 3-D distance.
  const std::vector<MeshContact> cs = contacts_of(mesh, {-0.1, -0.1, 0.2}, 0.4);
  ASSERT_EQ(cs.size(), 1u);
  EXPECT_EQ(cs[0].feature, MeshFeature::vertex);
  EXPECT_NEAR(cs[0].distance_m, std::sqrt(0.06), kTol);
  expect_vec_near(cs[0].normal, Vec3{0.1, 0.1, -0.2} / std::sqrt(0.06), kTol);
  EXPECT_EQ(cs[0].vertices[0], cs[0].vertices[1]);
  // Out of reach: nothing.
  EXPECT_TRUE(contacts_of(mesh, {0.5, 0.2, 0.5}, 0.4).empty());
  EXPECT_TRUE(contacts_of(mesh, {50, 20, 0.1}, 0.4).empty());
}

TEST(MeshContact, FanVertexSharedBySixTrianglesIsOnePlaneContact) {
  // Also placed and tilted, so coordinates are not exact and the six triangles round differently.
  const MeshTransform placements[] = {
      MeshTransform{},
      MeshTransform::from_axis_angle(1.0, {0.3, -0.7, 0.2}, 0.83, {0.12, -0.4, 2.5}),
      MeshTransform::from_axis_angle(1e-3, {1, 1, 1}, 2.1, {3.0, 1.0, -2.0}),
  };
  for (const MeshTransform& place : placements) {
    TriangleMesh mesh = fan();
    mesh.apply(place);
    const Vec3 vertex = place.apply({0, 0, 0});
    const Vec3 up = place.rotate({0, 0, 1});
    const double h = 0.3 * place.scale;
    for (const Vec3 slip : {Vec3{}, Vec3{1e-15, 0, 0}, Vec3{0, -3e-16, 0}, Vec3{2e-14, 1e-14, 0}}) {
      const Vec3 centre = vertex + h * up + place.rotate(slip) * place.scale;
      const std::vector<MeshContact> cs = contacts_of(mesh, centre, 0.4 * place.scale);
      ASSERT_EQ(cs.size(), 1u);
      // The plane through the vertex with normal `up`.
      EXPECT_NEAR(cs[0].distance_m, dot(centre - vertex, up), kTol * place.scale);
      expect_vec_near(cs[0].normal, -up, kTol);
    }
  }
}

// ---------------------------------------------------------------------------------
TEST(MeshContact, CubeFaceConvexEdgeAndConvexCorner) {
  const TriangleMesh mesh = cube();
  ASSERT_EQ(mesh.triangle_count(), 12u);
  ASSERT_EQ(mesh.vertices.size(), 8u);
  for (const Vec3 centre : {Vec3{0.5, 0.5, 1.2}, Vec3{0.3, 0.6, 1.2}, Vec3{0.9, 0.2, 1.2}}) {
    const std::vector<MeshContact> face = contacts_of(mesh, centre, 0.25);
    ASSERT_EQ(face.size(), 1u);
    EXPECT_NEAR(face[0].distance_m, 0.2, kTol);
    expect_vec_near(face[0].normal, {0, 0, -1}, kTol);
  }

  const std::vector<MeshContact> edge = contacts_of(mesh, {1.1, 0.37, 1.1}, 0.2);
  ASSERT_EQ(edge.size(), 1u);
  EXPECT_EQ(edge[0].feature, MeshFeature::edge);
  EXPECT_NEAR(edge[0].distance_m, 0.1 * std::sqrt(2.0), kTol);
  expect_vec_near(edge[0].normal, Vec3{-1, 0, -1} / std::sqrt(2.0), kTol);
  expect_vec_near(edge[0].contact_point_m, {1, 0.37, 1}, kTol);
  // The edge from (1,0,1) to (1,1,1): vertices 5 and 7 in the cube's corner numbering,
  // whatever indices the builder gave them.
  const Vec3 e0 = mesh.vertices[edge[0].vertices[0]], e1 = mesh.vertices[edge[0].vertices[1]];
  EXPECT_EQ(e0.x, 1.0);
  EXPECT_EQ(e0.z, 1.0);
  EXPECT_EQ(e1.x, 1.0);
  EXPECT_EQ(e1.z, 1.0);

  const std::vector<MeshContact> corner = contacts_of(mesh, {1.1, 1.1, 1.1}, 0.2);
  ASSERT_EQ(corner.size(), 1u);
  EXPECT_EQ(corner[0].feature, MeshFeature::vertex);
  EXPECT_NEAR(corner[0].distance_m, 0.1 * std::sqrt(3.0), kTol);
  expect_vec_near(corner[0].normal, Vec3{-1, -1, -1} / std::sqrt(3.0), kTol);
  // A sphere big enough to reach the far diagonal of the face z = 0, at the corner
  // (1,0,0) which that diagonal misses: the diagonal's edge point of the triangle
  // (0,0,0)-(0,1,0)-(1,1,0), 0.85 away, is beaten by the corner triangle; one contact.
  const std::vector<MeshContact> big = contacts_of(mesh, {1.1, -0.1, -0.1}, 0.9);
  ASSERT_EQ(big.size(), 1u);
  EXPECT_EQ(big[0].feature, MeshFeature::vertex);
  EXPECT_NEAR(big[0].distance_m, 0.1 * std::sqrt(3.0), kTol);
  expect_vec_near(big[0].contact_point_m, {1, 0, 0}, 0.0);
}

TEST(MeshContact, InsideABoxCornerThreeFacesAndInsideEdgeTwo) {
  for (const bool inward : {true, false}) {  // winding does not enter the geometry
    const TriangleMesh mesh = cube(inward);
    const std::vector<MeshContact> corner = contacts_of(mesh, {0.1, 0.1, 0.1}, 0.15);
    ASSERT_EQ(corner.size(), 3u);
    std::vector<Vec3> normals;
    for (const MeshContact& c : corner) {
      EXPECT_NEAR(c.distance_m, 0.1, kTol);
      normals.push_back(c.normal);
    }
    // One contact on each of the faces x = 0, y = 0, z = 0.
    for (int axis = 0; axis < 3; ++axis)
      EXPECT_EQ(std::count_if(normals.begin(), normals.end(), [&](const Vec3& n) { return std::abs(n[axis] + 1.0) < kTol; }), 1);
    // Output order: by triangle.
    EXPECT_TRUE(std::is_sorted(corner.begin(), corner.end(),
                               [](const MeshContact& a, const MeshContact& b) { return a.triangle < b.triangle; }));

    const std::vector<MeshContact> edge = contacts_of(mesh, {0.1, 0.12, 0.5}, 0.15);
    ASSERT_EQ(edge.size(), 2u);
    EXPECT_NEAR(edge[0].distance_m + edge[1].distance_m, 0.22, kTol);
  }
}

// ---------------------------------------------------------------------------------
using ContactKey = std::tuple<std::uint32_t, MeshFeature, double>;

std::vector<ContactKey> keys(const std::vector<MeshContact>& cs) {
  std::vector<ContactKey> k;
  for (const MeshContact& c : cs) k.emplace_back(c.triangle, c.feature, c.distance_m);
  return k;
}

void check_grid_against_brute_force(const TriangleMesh& mesh, double cell_size, std::size_t max_cells,
                                    std::uint64_t seed, double max_radius) {
  const MeshGrid grid(mesh, cell_size, max_cells);
  ASSERT_LE(grid.cell_count(), max_cells);
  std::vector<std::uint32_t> all(mesh.triangle_count());
  for (std::uint32_t t = 0; t < all.size(); ++t) all[t] = t;

  const Aabb box = mesh.bounding_box();
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<std::uint32_t> candidates;
  std::vector<MeshContact> via_grid, brute, scratch;
  MeshContactScratch work;
  std::size_t touching = 0;
  for (int trial = 0; trial < 700; ++trial) {
    const double radius = max_radius * (0.02 + 0.98 * unit(rng));
    Vec3 centre;
    for (int a = 0; a < 3; ++a) {
      const double lo = box.lo_m[a] - radius, hi = box.hi_m[a] + radius;
      (a == 0 ? centre.x : a == 1 ? centre.y : centre.z) = lo + (hi - lo) * unit(rng);
    }
    grid.candidates(centre, radius, candidates);
    ASSERT_TRUE(std::is_sorted(candidates.begin(), candidates.end()));
    ASSERT_EQ(std::adjacent_find(candidates.begin(), candidates.end()), candidates.end());
    // Every triangle within the radius is a candidate (the grid may return more).
    for (std::uint32_t t = 0; t < mesh.triangle_count(); ++t) {
      const TriangleClosestPoint q =
          closest_point_on_triangle(centre, mesh.corner(t, 0), mesh.corner(t, 1), mesh.corner(t, 2));
      if (norm(q.point_m - centre) < radius) {
        ASSERT_TRUE(std::binary_search(candidates.begin(), candidates.end(), t)) << "triangle " << t << " lost";
      }
    }
    mesh_contacts(mesh, grid, centre, radius, via_grid, work);
    mesh_contacts_among(mesh, all, centre, radius, brute, scratch);
    ASSERT_EQ(keys(via_grid), keys(brute));
    touching += brute.empty() ? 0 : 1;
  }
  EXPECT_GT(touching, 50u);  // the random spheres did exercise contacts
}

TEST(MeshGrid, SameContactsAsBruteForceOnAFineWavySheet) {
  const TriangleMesh mesh = wavy_sheet(40);  // 3200 triangles
  check_grid_against_brute_force(mesh, 0.0, MeshGrid::kDefaultMaxCells, 11, 0.1);
  check_grid_against_brute_force(mesh, 0.07, MeshGrid::kDefaultMaxCells, 12, 0.1);
  check_grid_against_brute_force(mesh, 0.01, 64, 13, 0.1);  // cap forces bigger cells
}

TEST(MeshGrid, SameContactsAsBruteForceOnAnIcosphere) {
  TriangleMesh mesh = icosphere(3);  // 1280 triangles
  ASSERT_EQ(mesh.triangle_count(), 1280u);
  ASSERT_EQ(mesh.vertices.size(), 642u);  // shared midpoints merged
  check_grid_against_brute_force(mesh, 0.0, MeshGrid::kDefaultMaxCells, 21, 0.3);
  mesh.apply(MeshTransform::from_axis_angle(2e-3, {1, 2, 3}, 0.7, {0.5, -0.2, 0.1}));
  check_grid_against_brute_force(mesh, 1e-3, MeshGrid::kDefaultMaxCells, 22, 6e-4);
}

TEST(MeshGrid, SphereResolvedOnTheIcosphereSurfaceOncePerTouch) {
  // A small sphere pressed on the outside of a fine convex mesh touches it in exactly one place.
  const TriangleMesh mesh = icosphere(3);
  const MeshGrid grid(mesh);
  std::mt19937_64 rng(5);
  std::normal_distribution<double> gauss;
  std::vector<MeshContact> cs;
  for (int trial = 0; trial < 500; ++trial) {
    const Vec3 dir = normalized(Vec3{gauss(rng), gauss(rng), gauss(rng)});
    mesh_contacts(mesh, grid, 1.02 * dir, 0.05, cs);
    ASSERT_EQ(cs.size(), 1u) << "trial " << trial;
    EXPECT_LT(dot(cs[0].normal, dir), 0.0);
  }
}

TEST(MeshGrid, CellCountCapAndEmptyQueries) {
  const TriangleMesh mesh = wavy_sheet(10);
  const MeshGrid tiny(mesh, 1e-6, 1000);
  EXPECT_LE(tiny.cell_count(), 1000u);
  EXPECT_GT(tiny.cell_size_m(), 1e-6);
  std::vector<std::uint32_t> out{1, 2, 3};
  tiny.candidates({100, 100, 100}, 0.1, out);
  EXPECT_TRUE(out.empty());
  tiny.candidates({1, 1, 0}, -1.0, out);
  EXPECT_TRUE(out.empty());
  tiny.candidates({1, 1, std::nan("")}, 0.1, out);
  EXPECT_TRUE(out.empty());
  const MeshGrid empty(TriangleMesh{});
  empty.candidates({0, 0, 0}, 1.0, out);
  EXPECT_TRUE(out.empty());
}

}  // namespace
}  // namespace regodem
