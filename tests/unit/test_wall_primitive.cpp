// The closest-point query of each analytic wall shape, against hand-worked geometry.
#include <gtest/gtest.h>

#include "geometry/wall_set.hpp"

namespace regodem {
namespace {

constexpr double kTol = 1e-12;

TEST(WallPrimitive, PlaneIsOneSidedSignedDistance) {
  WallSet walls;
  walls.add_plane(walls.add_body("floor", {}), {0, 0, 1}, {0, 0, 2}, 0);  // normal normalised
  const WallProximity above = closest_wall_point(walls.primitives[0], {3, 4, 1.5});
  EXPECT_NEAR(above.distance_m, 0.5, kTol);
  EXPECT_NEAR(above.normal.z, -1.0, kTol);
  EXPECT_NEAR(above.contact_point_m.z, 1.0, kTol);
  EXPECT_NEAR(closest_wall_point(walls.primitives[0], {0, 0, 0.8}).distance_m, -0.2, kTol);
}

TEST(WallPrimitive, DiskFaceFromBothSidesAndItsRim) {
  WallSet walls;
  walls.add_disk(walls.add_body("sieve", {}), {0, 0, 0}, {0, 0, 1}, 1.0, 0);
  const WallPrimitive& disk = walls.primitives[0];
  EXPECT_NEAR(closest_wall_point(disk, {0.5, 0, 0.3}).distance_m, 0.3, kTol);
  EXPECT_NEAR(closest_wall_point(disk, {0.5, 0, -0.3}).normal.z, 1.0, kTol);
  const WallProximity rim = closest_wall_point(disk, {1.3, 0, 0.4});
  EXPECT_NEAR(rim.distance_m, 0.5, kTol);  // 3-4-5 triangle to the rim point (1, 0, 0)
  EXPECT_NEAR(rim.contact_point_m.x, 1.0, kTol);
}

TEST(WallPrimitive, CylinderSidesAndEnds) {
  WallSet walls;
  const auto body = walls.add_body("barrel", {});
  walls.add_cylinder(body, {0, 0, 0}, {0, 0, 1}, 1.0, 2.0, /*inside*/ true, /*outside*/ false,
                     /*cap_bottom*/ true, /*cap_top*/ false, 0);
  ASSERT_EQ(walls.primitives.size(), 2u);  // the shell and its bottom disk
  const WallPrimitive& shell = walls.primitives[0];
  const WallProximity inside = closest_wall_point(shell, {0.7, 0, 1});
  EXPECT_TRUE(inside.candidate);
  EXPECT_NEAR(inside.distance_m, 0.3, kTol);
  EXPECT_NEAR(inside.normal.x, 1.0, kTol);
  EXPECT_FALSE(closest_wall_point(shell, {1.2, 0, 1}).candidate);  // outside: not felt
  // Open top: its rim edge is felt beyond the end.
  const WallProximity rim = closest_wall_point(shell, {0.6, 0, 2.3});
  EXPECT_TRUE(rim.candidate);
  EXPECT_NEAR(rim.distance_m, 0.5, kTol);
  // Capped bottom: the disk, not the shell, handles the edge there.
  EXPECT_FALSE(closest_wall_point(shell, {0.6, 0, -0.3}).candidate);
  EXPECT_NEAR(closest_wall_point(walls.primitives[1], {0.6, 0, 0.2}).distance_m, 0.2, kTol);
}

TEST(WallPrimitive, CylinderFeltFromBothSides) {
  WallSet walls;
  walls.add_cylinder(walls.add_body("sieve", {}), {0, 0, 0}, {0, 0, 1}, 1.0, 2.0, true, true, false, false, 0);
  const WallProximity outside = closest_wall_point(walls.primitives[0], {0, 1.25, 1});
  EXPECT_TRUE(outside.candidate);
  EXPECT_NEAR(outside.distance_m, 0.25, kTol);
  EXPECT_NEAR(outside.normal.y, -1.0, kTol);
}

TEST(WallSet, TranslationMovesPrimitivesOnlyWhileActive) {
  WallSet walls;
  WallMotion motion;
  motion.velocity_m_per_s = {0, 0, -0.5};
  motion.start_s = 1.0;
  motion.stop_s = 2.0;
  walls.add_plane(walls.add_body("piston", motion), {0, 0, 1}, {0, 0, -1}, 0);
  for (int s = 0; s < 300; ++s) walls.advance(0.01 * s, 0.01);  // t = 0 .. 3 s
  EXPECT_NEAR(walls.primitives[0].point_m.z, 0.5, 1e-9);
  EXPECT_NEAR(walls.bodies[0].displacement_m.z, -0.5, 1e-9);
}

}  // namespace
}  // namespace regodem
