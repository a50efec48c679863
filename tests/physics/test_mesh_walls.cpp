// Triangle-mesh walls in the contact pass (issue 4): a mesh plane acts as the analytic
// plane it approximates (force, resting overlap, a loaded friction spring carried
// across the shared diagonal, heat), a sphere rebounds from a mesh box with the
// restitution coefficient, a turning mesh cylinder drags a sphere with the Coulomb
// force, and a translating mesh plate pushes a sphere at its speed and stops at its
// travel. Time step 0.05 of the Rayleigh time throughout.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "physics_fixtures.hpp"

namespace regodem::testing {
namespace {

constexpr double kRadius = 1.0e-3;
constexpr double kG = 9.81;

/// The square [-h, h]^2 at z = 0, normal +z, cut into cells x cells squares of two
/// triangles each (diagonals from (-,-) to (+,+)): one cell gives the two-triangle
/// plane, two cells put a vertex shared by six triangles at the origin.
TriangleMesh square_mesh(double half_side_m, int cells) {
  TriangleMeshBuilder builder;
  const double step = 2.0 * half_side_m / cells;
  const auto at = [&](int i, int j) { return Vec3{-half_side_m + i * step, -half_side_m + j * step, 0.0}; };
  for (int i = 0; i < cells; ++i)
    for (int j = 0; j < cells; ++j) {
      builder.add_triangle(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      builder.add_triangle(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  return std::move(builder).finish("square");
}


/// A closed cylinder about the z axis from z0 to z1, `sides` facets, wound outwards.
TriangleMesh cylinder_mesh(double radius_m, double z0, double z1, int sides) {
  TriangleMeshBuilder builder;
  const auto rim = [&](int k, double z) {
    const double a = 2.0 * std::numbers::pi * (k % sides) / sides;
    return Vec3{radius_m * std::cos(a), radius_m * std::sin(a), z};
  };
  for (int k = 0; k < sides; ++k) {
    builder.add_triangle(rim(k, z0), rim(k + 1, z0), rim(k + 1, z1));
    builder.add_triangle(rim(k, z0), rim(k + 1, z1), rim(k, z1));
    builder.add_triangle(Vec3{0, 0, z1}, rim(k, z1), rim(k + 1, z1));
    builder.add_triangle(Vec3{0, 0, z0}, rim(k + 1, z0), rim(k, z0));
  }
  return std::move(builder).finish("cylinder");
}

enum class Floor { plane, mesh };

/// A sphere under gravity on a floor at z = 0: an analytic plane or the given mesh.
Simulation sphere_on(Floor floor, const TriangleMesh& mesh, const SphereMaterial& m, const Vec3& start,
                     const Vec3& gravity, const WallMotion& motion = {}, ThermalWall thermal = {}) {
  WallSet walls;
  const std::uint32_t body = walls.add_body("floor", motion);
  if (floor == Floor::plane)
    walls.add_plane(body, {0, 0, 0}, {0, 0, 1}, 0);
  else
    walls.add_mesh(body, mesh, 0);
  const double dt = 0.05 * rayleigh_time_for(m, kRadius);
  SimulationSettings settings = settings_for(kRadius, dt, gravity, 0.2);
  settings.heat.enabled = thermal.mode != WallThermalMode::adiabatic;
  Simulation sim(one_material(m), walls, settings, {thermal});
  sim.add_particle(sphere(start, motion.velocity_m_per_s, kRadius, m.density, 200.0));
  return sim;
}

// A sphere settling on the two-triangle plane across its diagonal, and on the
// four-cell plane over the vertex six triangles share, ends where it does on the
// analytic plane: the floor carries its weight within 0.1 % (the bound) and
// the overlap is Hertz's, (3 m g / (4 E* sqrt(R)))^(2/3), within 0.1 %; the mesh and
// plane runs agree to 1e-9 of the overlap (round-off in the closest point only).
TEST(MeshWalls, SphereRestingAcrossDiagonalOrOnVertexFeelsThePlaneForce) {
  SphereMaterial m;
  m.restitution = 0.3;
  const double h = 10.0 * kRadius;
  struct Case {
    const char* what;
    int cells;
    Vec3 start;
  };
  for (const Case& c : {Case{"across the diagonal", 1, {0.0, 0.0, 1.001 * kRadius}},
                        Case{"across the diagonal, off centre", 1, {0.3 * h, 0.3 * h, 1.001 * kRadius}},
                        Case{"on a vertex of six triangles", 2, {0.0, 0.0, 1.001 * kRadius}}}) {
    SCOPED_TRACE(c.what);
    const TriangleMesh mesh = square_mesh(h, c.cells);
    Simulation on_mesh = sphere_on(Floor::mesh, mesh, m, c.start, {0, 0, -kG});
    Simulation on_plane = sphere_on(Floor::plane, mesh, m, c.start, {0, 0, -kG});
    const std::uint64_t steps = static_cast<std::uint64_t>(0.05 / on_mesh.time_step_s());
    on_mesh.advance(steps);
    on_plane.advance(steps);
    const double weight = on_mesh.particles.mass_kg[0] * kG;
    EXPECT_NEAR(on_mesh.walls.bodies[0].force_N.z, -weight, 1e-3 * weight);
    EXPECT_EQ(on_mesh.contact_statistics().wall_contacts, 1u);
    const double overlap = kRadius - on_mesh.particles.position_m[0].z;
    // The wall is of the sphere's material: E* = E / (2 (1 - nu^2)), R* = R.
    const double hertz = hertz_overlap(weight, effective_youngs_modulus(m), kRadius);
    EXPECT_NEAR(overlap, hertz, 1e-3 * hertz);
    EXPECT_NEAR(on_mesh.particles.position_m[0].z, on_plane.particles.position_m[0].z, 1e-9 * hertz);
    EXPECT_NEAR(on_mesh.walls.bodies[0].force_N.z, on_plane.walls.bodies[0].force_N.z, 1e-9 * weight);
  }
}

// A sphere rolling without slip down a 10-degree incline (tilted gravity, friction
// 0.5) over the two-triangle plane: static friction, 2/7 m g sin(theta), loads its
// tangential spring, and the contact crosses the plane's diagonal. The spring must
// follow the contact from one triangle to the next: the sphere's position then equals
// the analytic plane run's within 1 % of the spring's stretch F_t / k_t. A spring reset
// at the diagonal makes the sphere slip by about that stretch (checked by disabling the
// carry: the difference is then 0.29 stretch).
TEST(MeshWalls, LoadedFrictionSpringIsCarriedAcrossTheDiagonal) {
  SphereMaterial m;
  m.restitution = 0.3;
  m.sliding_friction = 0.5;
  const double h = 10.0 * kRadius;
  const TriangleMesh mesh = square_mesh(h, 1);
  const double tilt = 10.0 * std::numbers::pi / 180.0;
  const Vec3 gravity{kG * std::sin(tilt), 0.0, -kG * std::cos(tilt)};
  // Starts over the triangle y > x and rolls along +x across the diagonal y = x at x = 0:
  // 3 mm at (5/7) g sin(theta) = 1.2 m/s^2 takes 0.07 s.
  const Vec3 start{-0.3 * h, 0.0, kRadius * 0.9999};
  Simulation on_mesh = sphere_on(Floor::mesh, mesh, m, start, gravity);
  Simulation on_plane = sphere_on(Floor::plane, mesh, m, start, gravity);
  const std::uint64_t steps = static_cast<std::uint64_t>(0.09 / on_mesh.time_step_s());
  on_mesh.advance(steps);
  on_plane.advance(steps);
  const Vec3 x = on_mesh.particles.position_m[0];
  ASSERT_GT(x.x, 0.05 * h);  // crossed
  // Spring stretch: F_t / k_t with k_t = 8 G* a, a = sqrt(R delta) (DESIGN.md section 2).
  const double weight = on_mesh.particles.mass_kg[0] * kG;
  const double overlap = hertz_overlap(weight * std::cos(tilt), effective_youngs_modulus(m), kRadius);
  const double shear_star = m.shear_modulus / (2.0 * (2.0 - m.poisson));
  const double stretch = 2.0 / 7.0 * weight * std::sin(tilt) / (8.0 * shear_star * std::sqrt(kRadius * overlap));
  EXPECT_NEAR(x.x, on_plane.particles.position_m[0].x, 0.01 * stretch);
}

// A sphere dropped at 0.1 m/s on the top face of a mesh box, at its centre (on the
// shared diagonal) and near a corner of the face, rebounds with speed ratio e within
// 1 % (the analytic wall's bound, test_collision_restitution).
TEST(MeshWalls, SphereReboundsFromMeshBoxWithRestitution) {
  for (const double e : {0.3, 0.8}) {
    for (const Vec3 at : {Vec3{0.0, 0.0, 0.0}, Vec3{3.0 * kRadius, -3.5 * kRadius, 0.0}}) {
      SphereMaterial m;
      m.restitution = e;
      WallSet walls;
      walls.add_mesh(walls.add_body("box", {}), box_mesh({-5e-3, -5e-3, -5e-3}, {5e-3, 5e-3, 0.0}), 0);
      const double dt = 0.05 * rayleigh_time_for(m, kRadius);
      Simulation sim(one_material(m), walls, settings_for(kRadius, dt));
      sim.add_particle(sphere({at.x, at.y, 1.01 * kRadius}, {0, 0, -0.1}, kRadius, m.density));
      bool touched = false;
      for (int s = 0; s < 1'000'000; ++s) {
        sim.step();
        const bool touching = sim.contact_statistics().wall_contacts > 0;
        touched = touched || touching;
        if (touched && !touching) break;
      }
      ASSERT_TRUE(touched);
      EXPECT_NEAR(sim.particles.velocity_m_per_s[0].z / 0.1, e, 0.01 * e);
      EXPECT_NEAR(sim.particles.velocity_m_per_s[0].x, 0.0, 1e-9);
    }
  }
}

// A mesh cylinder (r = 5 mm, 64 facets) turning at 20 rad/s about its axis (z) drags
// a sphere resting on its top face 3 mm off the axis (rotation locked, so it keeps
// sliding, and crosses the fan's edges): the tangential force equals mu m g within
// 1 %, along the surface's motion, and the cylinder feels the opposite, with torque
// -mu m g r about its axis within 1 %.
TEST(MeshWalls, TurningMeshCylinderDragsSphereWithCoulombForce) {
  SphereMaterial m;
  m.restitution = 0.3;
  m.sliding_friction = 0.4;
  WallMotion spin;
  spin.angular_velocity_rad_per_s = {0, 0, 20.0};
  spin.start_s = 0.01;  // settle first
  WallSet walls;
  walls.add_mesh(walls.add_body("cylinder", spin), cylinder_mesh(5e-3, -5e-3, 0.0, 64), 0);
  const double dt = 0.05 * rayleigh_time_for(m, kRadius);
  Simulation sim(one_material(m), walls, settings_for(kRadius, dt, {0, 0, -kG}, 0.05));
  sim.add_particle(sphere({3e-3, 0, 0.9999 * kRadius}, {}, kRadius, m.density));
  sim.particles.inv_inertia[0] = 0.0;
  sim.advance(static_cast<std::uint64_t>(0.01 / dt));
  const double friction = m.sliding_friction * sim.particles.mass_kg[0] * kG;
  EXPECT_NEAR(std::hypot(sim.walls.bodies[0].force_N.x, sim.walls.bodies[0].force_N.y), 0.0, 1e-9 * friction);
  // 10 ms of sliding: the cylinder turns 11 degrees (fan edges every 5.6 degrees) and
  // the sphere gains mu g t = 0.04 m/s, still short of the surface's 0.06 m/s.
  sim.advance(static_cast<std::uint64_t>(0.01 / dt));
  const Vec3 x = sim.particles.position_m[0];
  const double r = std::hypot(x.x, x.y);
  const Vec3 tangent = normalized(cross(Vec3{0, 0, 1}, Vec3{x.x, x.y, 0.0}));  // surface motion there
  const Vec3 on_wall = sim.walls.bodies[0].force_N;
  EXPECT_NEAR(dot(-on_wall, tangent), friction, 0.01 * friction);
  EXPECT_NEAR(sim.walls.bodies[0].torque_N_m.z, -friction * r, 0.01 * friction * r);
}

// A mesh plate (a thin box) moving at 20 mm/s pushes a sphere sliding on an analytic
// floor (friction 0.5) at its own speed within 1 %, and stops when it has travelled
// 10 mm, exactly there; the sphere then slides on by v^2 / (2 mu g) and stops.
TEST(MeshWalls, TranslatingMeshPlatePushesAtItsSpeedAndStopsAtItsTravel) {
  SphereMaterial m;
  m.sliding_friction = 0.5;
  const double dt = 0.05 * rayleigh_time_for(m, kRadius);
  const double speed = 0.02, travel = 0.01;
  WallMotion push;
  push.velocity_m_per_s = {speed, 0, 0};
  push.max_travel_m = travel;
  WallSet walls;
  walls.add_plane(walls.add_body("floor", {}), {0, 0, 0}, {0, 0, 1}, 0);
  walls.add_mesh(walls.add_body("plate", push), box_mesh({-2e-3, -4e-3, 0.0}, {-1e-3, 4e-3, 4e-3}), 0);
  Simulation sim(one_material(m), walls, settings_for(kRadius, dt, {0, 0, -kG}, 0.05));
  sim.add_particle(sphere({0.2e-3, 0, kRadius}, {}, kRadius, m.density));  // 0.2 mm from the plate
  sim.particles.inv_inertia[0] = 0.0;
  sim.advance(static_cast<std::uint64_t>(0.2 / dt));
  const double x0 = sim.particles.position_m[0].x, t0 = sim.time_s();
  sim.advance(static_cast<std::uint64_t>(0.1 / dt));
  const double mean_speed = (sim.particles.position_m[0].x - x0) / (sim.time_s() - t0);
  EXPECT_NEAR(mean_speed, speed, 0.01 * speed);
  sim.advance(static_cast<std::uint64_t>(0.3 / dt));
  EXPECT_DOUBLE_EQ(sim.walls.bodies[1].travel_m, travel);
  EXPECT_NEAR(sim.walls.bodies[1].displacement_m.x, travel, 1e-15);
  EXPECT_EQ(sim.walls.bodies[1].motion.velocity_m_per_s, Vec3{});
  EXPECT_NEAR(sim.particles.velocity_m_per_s[0].x, 0.0, 1e-6);
  // Plate face + radius + the slide, within 5 % of the slide (the contact lets go over
  // a few steps, and the overlap is about 1e-3 of the slide).
  const double slide = speed * speed / (2.0 * m.sliding_friction * kG);
  EXPECT_NEAR(sim.particles.position_m[0].x, -1e-3 + travel + kRadius + slide, 0.05 * slide);
}

// A sphere resting on a fixed-temperature mesh plane warms exactly as on the analytic
// plane (same conductance law, R* = R): temperatures agree to 1e-9 K after 0.05 s.
TEST(MeshWalls, HeatThroughAMeshWallMatchesTheAnalyticWall) {
  SphereMaterial m;
  m.restitution = 0.3;
  ThermalWall hot;
  hot.mode = WallThermalMode::fixed;
  hot.prescribed_temperature_K = TimeTable(400.0);
  const TriangleMesh mesh = square_mesh(10.0 * kRadius, 2);
  const Vec3 start{1e-4, 2e-4, 0.9999 * kRadius};
  Simulation on_mesh = sphere_on(Floor::mesh, mesh, m, start, {0, 0, -kG}, {}, hot);
  Simulation on_plane = sphere_on(Floor::plane, mesh, m, start, {0, 0, -kG}, {}, hot);
  const std::uint64_t steps = static_cast<std::uint64_t>(0.05 / on_mesh.time_step_s());
  on_mesh.advance(steps);
  on_plane.advance(steps);
  EXPECT_GT(on_mesh.particles.temperature_K[0], 200.001);
  EXPECT_NEAR(on_mesh.particles.temperature_K[0], on_plane.particles.temperature_K[0], 1e-9);
  EXPECT_NEAR(on_mesh.energy_imbalance_J(), 0.0, 1e-12 * on_mesh.thermal_energy_J());
}

}  // namespace
}  // namespace regodem::testing
