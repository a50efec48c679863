#pragma once
// The small drilling bed several physics tests share: ~250 grains in a lumped cup on a
// fixed-temperature floor, a mesh paddle that feeds and turns (a fixed-temperature
// "drill"), heat, bonds formed later by the test that are weak enough to break.
#include "core/rng.hpp"
#include "geometry/mesh_axial_segments.hpp"
#include "physics_fixtures.hpp"

namespace regodem::testing {

struct DrillingBedOptions {
  int threads = 1;
  // Heat from the contacts: the sliding power (default) or every loss.
  bool dissipation_heating = false;
  HeatPartitionModel partition = HeatPartitionModel::fixed;
  double bond_damping_ratio = 0.0;
  RollingModel rolling_model = RollingModel::relative_spin;
  double rolling_friction = 0.1;
  double rayleigh_fraction = 0.1;  // the step
  bool energy_audit = true;
  // The paddle a lumped rod of 4 axial segments (issue 21: the drill as a thermal body):
  // steel's k along its section, radiating to 100 K, its top held at 150 K.
  bool rod_drill = false;
};

inline Simulation make_drilling_bed(const DrillingBedOptions& options = {}) {
  constexpr double kRadius = 0.5e-3;
  SphereMaterial m;
  m.shear_modulus = 1e7;
  m.restitution = 0.3;
  m.sliding_friction = 0.5;
  m.rolling_friction = options.rolling_friction;
  const double dt = options.rayleigh_fraction * rayleigh_time_for(m, kRadius);
  WallSet walls;
  walls.add_cylinder(walls.add_body("cup", {}), {0, 0, -0.004}, {0, 0, 1}, 0.0045, 0.012, true, false, false, false, 0);
  walls.add_plane(walls.add_body("floor", {}), {0, 0, -0.004}, {0, 0, 1}, 0);
  WallMotion drill;
  drill.velocity_m_per_s = {0, 0, -0.05};
  drill.angular_velocity_rad_per_s = {0, 0, 30.0};
  drill.axis_point_m = {0, 0, 0};
  drill.max_travel_m = 0.004;
  const std::uint32_t paddle = walls.add_body("paddle", drill);
  walls.add_mesh(paddle, box_mesh({-0.0025, -0.0006, 0.0}, {0.0025, 0.0006, 0.004}, "paddle"), 0);
  SimulationSettings settings = settings_for(kRadius, dt, {0, 0, -9.81}, 0.02, options.threads);
  settings.min_particles_per_thread = 50;  // up to 4 threads work on this small bed
  settings.energy_audit = options.energy_audit;  // its books too must not depend on threads or a restart
  settings.heat.enabled = true;
  settings.heat.time_scale_factor = 1e3;
  settings.heat.friction_heating = !options.dissipation_heating;
  settings.heat.dissipation_heating = options.dissipation_heating;
  settings.heat.partition = options.partition;
  ThermalWall cup, floor, paddle_heat;
  cup.mode = WallThermalMode::lumped;
  cup.initial_temperature_K = 300.0;
  cup.heat_capacity_J_per_K = 0.05;
  floor.mode = WallThermalMode::fixed;
  floor.prescribed_temperature_K = TimeTable({0.0, 0.05}, {400.0, 500.0});
  paddle_heat.mode = WallThermalMode::fixed;
  paddle_heat.prescribed_temperature_K = TimeTable(150.0);
  if (options.rod_drill) {
    MeshWall& mesh = walls.meshes.back();
    const MeshAxialSegments cut = split_mesh_along_axis(mesh.mesh, {0, 0, 1}, 4);
    mesh.triangle_segment = cut.triangle_segment;
    paddle_heat = ThermalWall{};
    paddle_heat.mode = WallThermalMode::lumped;
    paddle_heat.initial_temperature_K = 150.0;
    paddle_heat.heat_capacity_J_per_K = 0.087;  // 5 x 1.2 x 4 mm of steel, c = 460 J/(kg K)
    for (double a : cut.area_m2) {
      paddle_heat.rod.segment_heat_capacity_J_per_K.push_back(0.087 * a / mesh.mesh.area());
      paddle_heat.rod.segment_area_m2.push_back(a);
    }
    paddle_heat.rod.link_conductance_W_per_K = 45.0 * 5e-3 * 1.2e-3 / (cut.length_m / 4);
    paddle_heat.rod.held_end_K = 150.0;
    paddle_heat.rod.held_end_conductance_W_per_K = 2.0 * paddle_heat.rod.link_conductance_W_per_K;
    paddle_heat.rod.emissivity = 0.8;
    paddle_heat.rod.surroundings_K = 100.0;
  }
  MaterialTable materials = one_material(m);
  PairProperties pair = materials.pair(0, 0);
  pair.rolling_model = options.rolling_model;
  materials.set_pair(0, 0, pair);
  Simulation sim(std::move(materials), walls, settings, {cup, floor, paddle_heat});
  BondParameters bond;
  bond.normal_stiffness_Pa_per_m = 1e10;
  bond.shear_stiffness_Pa_per_m = 4e9;
  bond.tensile_strength_Pa = 2e4;  // weak: the paddle breaks some
  bond.shear_strength_Pa = 2e4;
  bond.damping_ratio = options.bond_damping_ratio;
  sim.configure_bonds({bond}, {0});
  Rng rng(5);
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j)
      for (int k = 0; k < 5; ++k) {
        const Vec3 x{(i - 3.5) * 1.02e-3, (j - 3.5) * 1.02e-3, -0.0035 + k * 1.0e-3};
        if (norm2(Vec3{x.x, x.y, 0}) > 0.004 * 0.004) continue;
        NewParticle p = sphere(x, {rng.uniform(-0.02, 0.02), rng.uniform(-0.02, 0.02), 0.0},
                               kRadius * rng.uniform(0.95, 1.0), m.density, rng.uniform(200.0, 300.0));
        sim.add_particle(p);
      }
  return sim;
}

}  // namespace regodem::testing
