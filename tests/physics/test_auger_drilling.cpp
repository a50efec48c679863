// An auger turning and feeding into a small bed (issue 4): the mesh keeps every
// particle centre out of its solid volume (winding number < 1/2 in the auger's own
// frame), pushes the particles aside, and feels thrust and torque against its feed and
// turn. Sped up (soft grains, fast feed and spin) so that it runs in seconds.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/rng.hpp"
#include "geometry/auger_generator.hpp"
#include "geometry/mesh_inside.hpp"
#include "physics_fixtures.hpp"

namespace regodem::testing {
namespace {

TEST(AugerDrilling, TurningAugerKeepsParticlesOutOfItsSolid) {
  SphereMaterial m;
  m.shear_modulus = 5e6;
  m.restitution = 0.3;
  m.sliding_friction = 0.5;
  const double radius = 1e-3, barrel_r = 12e-3;
  const double dt = 0.2 * rayleigh_time_for(m, radius);

  AugerSpec auger;
  auger.outer_diameter_m = 10e-3;
  auger.core_diameter_m = 4e-3;
  auger.pitch_m = 8e-3;
  auger.flutes = 2;
  auger.flute_thickness_m = 1.5e-3;
  auger.length_m = 40e-3;
  auger.tip = AugerTip::cone;
  auger.segments_per_turn = 32;
  TriangleMesh drill = make_auger(auger);
  const double tip_z = 24e-3;
  drill.apply(MeshTransform::from_axis_angle(1.0, {0, 0, 1}, 0.0, {0, 0, tip_z}));
  const TriangleMesh reference = drill;  // the mesh wall's reference frame is its start

  WallMotion feed;
  feed.velocity_m_per_s = {0, 0, -0.2};
  feed.angular_velocity_rad_per_s = {0, 0, 60.0};
  feed.axis_point_m = {0, 0, tip_z};
  feed.start_s = 0.05;  // after the bed settles
  feed.max_travel_m = 14e-3;
  WallSet walls;
  walls.add_cylinder(walls.add_body("barrel", {}), {0, 0, 0}, {0, 0, 1}, barrel_r, 70e-3, true, false, true, false, 0);
  const std::uint32_t drill_body = walls.add_body("drill", feed);
  walls.add_mesh(drill_body, std::move(drill), 0);

  SimulationSettings settings = settings_for(radius, dt, {0, 0, -9.81}, 0.08);
  settings.domain = {{-0.02, -0.02, -0.01}, {0.02, 0.02, 0.08}};
  Simulation sim(one_material(m), walls, settings);
  // A loose lattice in the barrel below the tip, jittered so it collapses into a bed.
  Rng rng(3);
  const double spacing = 2.1 * radius;
  for (double z = 1.1 * radius; z < tip_z - 2.0 * radius; z += spacing)
    for (double x = -barrel_r; x <= barrel_r; x += spacing)
      for (double y = -barrel_r; y <= barrel_r; y += spacing)
        if (std::hypot(x, y) < barrel_r - 1.1 * radius)
          sim.add_particle(sphere({x + 0.02 * radius * rng.uniform(), y + 0.02 * radius * rng.uniform(), z}, {},
                                  radius, m.density));
  ASSERT_GT(sim.particles.size(), 600u);

  // No particle centre within the auger's solid: checked in the auger's frame (the
  // pose maps it back), only for centres within its outer radius of the axis.
  const auto centres_inside_drill = [&] {
    int inside = 0;
    const RigidPose& pose = sim.walls.bodies[drill_body].pose;
    for (const Vec3& x : sim.particles.position_m) {
      const Vec3 local = pose.to_reference(x);
      if (std::hypot(local.x, local.y) < 0.5 * auger.outer_diameter_m && point_inside(reference, local)) ++inside;
    }
    return inside;
  };
  double largest_thrust = 0.0, largest_torque = 0.0;
  const std::uint64_t steps = static_cast<std::uint64_t>(0.13 / dt);
  for (std::uint64_t s = 0; s < steps; ++s) {
    sim.step();
    if (s % 250 == 0) {
      ASSERT_EQ(centres_inside_drill(), 0) << "at t = " << sim.time_s();
    }
    const WallBody& body = sim.walls.bodies[drill_body];
    largest_thrust = std::max(largest_thrust, body.force_N.z);            // the bed pushes up
    largest_torque = std::max(largest_torque, -body.torque_N_m.z);        // and resists the turn
  }
  EXPECT_EQ(centres_inside_drill(), 0);
  const WallBody& body = sim.walls.bodies[drill_body];
  EXPECT_NEAR(body.travel_m, 14e-3, 1e-12);  // fed its whole travel
  // It cut into the bed: the bed's weight scale is ~ m g per particle; the drill met
  // more than one particle's weight of resistance, and a resisting torque.
  const double particle_weight = sim.particles.mass_kg[0] * 9.81;
  EXPECT_GT(largest_thrust, particle_weight);
  EXPECT_GT(largest_torque, 0.0);
}

}  // namespace
}  // namespace regodem::testing
