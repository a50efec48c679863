// Rigid wall poses: many small turns compose to the exact rotation and stay
// orthonormal; a wall's feed ends exactly at its travel.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "geometry/rigid_pose.hpp"
#include "geometry/wall_set.hpp"
#include "geometry/wall_tessellation.hpp"

namespace regodem {
namespace {

// 100,000 turns of 2 pi / 100,000 about an axis through (1, 2, 0) along (0, 0, 1)
// bring every point back where it started within 5e-11 m (round-off: 1e5 steps at
// 2.2e-16 each, times the 2.3 m lever), and R^T R = I within 1e-14.
TEST(RigidPose, ManySmallTurnsComposeToTheExactRotation) {
  RigidPose pose;
  const Vec3 pivot{1.0, 2.0, 0.0};
  const int steps = 100'000;
  const Vec3 turn = Vec3{0.0, 0.0, 1.0} * (2.0 * std::numbers::pi / steps);
  const Vec3 p{0.3, -0.4, 0.5};
  for (int s = 0; s < steps / 4; ++s) pose.turn_and_shift(turn, pivot, {});
  // A quarter turn about z through the pivot: (x, y) -> pivot + (-(y - py), x - px).
  const Vec3 quarter = pose.to_world(p);
  EXPECT_NEAR(quarter.x, 1.0 - (-0.4 - 2.0), 5e-11);
  EXPECT_NEAR(quarter.y, 2.0 + (0.3 - 1.0), 5e-11);
  EXPECT_NEAR(quarter.z, 0.5, 5e-11);
  for (int s = steps / 4; s < steps; ++s) pose.turn_and_shift(turn, pivot, {});
  const Vec3 back = pose.to_world(p);
  EXPECT_NEAR(norm(back - p), 0.0, 5e-11);
  const Matrix3& r = pose.rotation;
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j) {
      const double rtr = r[0][i] * r[0][j] + r[1][i] * r[1][j] + r[2][i] * r[2][j];
      EXPECT_NEAR(rtr, i == j ? 1.0 : 0.0, 1e-14);
    }
}

// to_reference undoes to_world (1e-15 m).
TEST(RigidPose, ReferenceFrameIsTheInverse) {
  RigidPose pose;
  pose.turn_and_shift({0.3, -0.2, 0.9}, {0.1, 0.0, -0.3}, {0.05, 0.02, -0.01});
  const Vec3 p{0.7, -0.1, 0.25};
  EXPECT_NEAR(norm(pose.to_reference(pose.to_world(p)) - p), 0.0, 1e-15);
}

// A feed of 1 mm/s with max_travel 0.35 mm, stepped at 0.1 ms: travel stops at 0.35 mm
// exactly and the velocity is zero from then on; a turning mesh body counts the
// swept arc in its displacement since the neighbour build.
TEST(WallSetMotion, FeedStopsExactlyAtItsTravel) {
  WallSet walls;
  WallMotion feed;
  feed.velocity_m_per_s = {0.0, 0.0, -1e-3};
  feed.max_travel_m = 0.35e-3;
  walls.add_body("drill", feed);
  for (int s = 0; s < 10'000; ++s) walls.advance(s * 1e-4, 1e-4);
  EXPECT_DOUBLE_EQ(walls.bodies[0].travel_m, 0.35e-3);
  EXPECT_NEAR(walls.bodies[0].displacement_m.z, -0.35e-3, 1e-18);
  EXPECT_EQ(walls.bodies[0].motion.velocity_m_per_s, Vec3{});
  EXPECT_DOUBLE_EQ(walls.bodies[0].depth_m(), 0.35e-3);
}

TEST(WallSetMotion, TurningMeshCountsItsSweptArc) {
  WallSet walls;
  WallMotion spin;
  spin.angular_velocity_rad_per_s = {0.0, 0.0, 10.0};
  const std::uint32_t body = walls.add_body("paddle", spin);
  TriangleMeshBuilder builder;
  builder.add_triangle({0.0, 0.0, 0.0}, {0.02, 0.0, 0.0}, {0.0, 0.01, 0.0});
  walls.add_mesh(body, std::move(builder).finish("paddle"), 0);
  walls.advance(0.0, 1e-3);
  // The farthest vertex from the z axis is (0.02, 0, 0): an arc of 0.01 rad x 0.02 m.
  EXPECT_NEAR(walls.max_displacement_since_build_m(), 0.01 * 0.02, 1e-15);
  walls.advance(1e-3, 1e-3);
  EXPECT_NEAR(walls.max_displacement_since_build_m(), 2 * 0.01 * 0.02, 1e-15);
  walls.mark_neighbor_build();
  EXPECT_EQ(walls.max_displacement_since_build_m(), 0.0);
}

// A mesh wall's triangles are drawn at its current pose: after a quarter turn about z,
// the vertex (0.02, 0, 0) is at (0, 0.02, 0) (1e-15 m), tagged with its body.
TEST(WallTessellation, MeshWallIsDrawnAtItsPose) {
  WallSet walls;
  WallMotion spin;
  spin.angular_velocity_rad_per_s = {0.0, 0.0, std::numbers::pi / 2.0};
  walls.add_body("floor", {});
  const std::uint32_t body = walls.add_body("paddle", spin);
  TriangleMeshBuilder builder;
  builder.add_triangle({0.0, 0.0, 0.0}, {0.02, 0.0, 0.0}, {0.0, 0.01, 0.0});
  walls.add_mesh(body, std::move(builder).finish("paddle"), 0);
  walls.advance(0.0, 1.0);
  const WallSurface surface = tessellate_walls(walls, {-1, -1, -1}, {1, 1, 1});
  ASSERT_EQ(surface.triangles.size(), 1u);
  EXPECT_EQ(surface.body[0], body);
  EXPECT_EQ(surface.primitive[0], kNoPrimitive);
  const Vec3 corner = surface.points_m[surface.triangles[0][1]];
  EXPECT_NEAR(corner.x, 0.0, 1e-15);
  EXPECT_NEAR(corner.y, 0.02, 1e-15);
}

}  // namespace
}  // namespace regodem
