#pragma once
// Small builders for the physics verification tests: one material, a few walls.
#include <cmath>
#include <numbers>

#include "sim/simulation.hpp"
#include "sim/time_step.hpp"

namespace regodem::testing {

struct SphereMaterial {
  double density = 2500.0;
  double shear_modulus = 1.0e8;
  double poisson = 0.25;
  double restitution = 0.5;
  double sliding_friction = 0.0;
  double rolling_friction = 0.0;
};

/// E* of two bodies of this material: E / (2 (1 - nu^2)), E = 2G(1 + nu).
inline double effective_youngs_modulus(const SphereMaterial& m) {
  const double youngs = 2.0 * m.shear_modulus * (1.0 + m.poisson);
  return youngs / (2.0 * (1.0 - m.poisson * m.poisson));
}

inline double sphere_mass(const SphereMaterial& m, double radius) {
  return m.density * 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
}

inline MaterialTable one_material(const SphereMaterial& m) {
  MaterialTable table;
  table.add({"grain", m.density, m.shear_modulus, m.poisson});
  PairProperties pair;
  pair.restitution = m.restitution;
  pair.sliding_friction = m.sliding_friction;
  pair.rolling_friction = m.rolling_friction;
  table.set_pair(0, 0, pair);
  return table;
}

inline double rayleigh_time_for(const SphereMaterial& m, double radius) {
  return rayleigh_time_s(radius, m.density, m.shear_modulus, m.poisson);
}

inline SimulationSettings settings_for(double radius, double dt, Vec3 gravity = {}, double half_box = 0.1,
                                       int threads = 1) {
  SimulationSettings s;
  s.domain = {{-half_box, -half_box, -half_box}, {half_box, half_box, half_box}};
  s.gravity_m_per_s2 = gravity;
  s.time_step_s = dt;
  s.neighbor_skin_m = 0.2 * radius;
  s.min_particle_radius_m = radius;
  s.threads = threads;
  return s;
}

inline NewParticle sphere(const Vec3& x, const Vec3& v, double radius, double density) {
  NewParticle p;
  p.position_m = x;
  p.velocity_m_per_s = v;
  p.radius_m = radius;
  p.density_kg_per_m3 = density;
  return p;
}

}  // namespace regodem::testing
