#pragma once
// Small builders for the physics verification tests: one or two materials, a few walls.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "core/rng.hpp"
#include "geometry/triangle_mesh.hpp"
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
  double conductivity = 10.0;     // W/(m K)
  double specific_heat = 800.0;   // J/(kg K)
  double real_shear_modulus = 0.0;
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
  Material grain;
  grain.name = "grain";
  grain.density_kg_per_m3 = m.density;
  grain.shear_modulus_Pa = m.shear_modulus;
  grain.poisson_ratio = m.poisson;
  grain.conductivity_W_per_mK = TemperatureCurve(m.conductivity);
  grain.specific_heat_J_per_kgK = TemperatureCurve(m.specific_heat);
  grain.real_shear_modulus_Pa = m.real_shear_modulus;
  table.add(grain);
  PairProperties pair;
  pair.restitution = m.restitution;
  pair.sliding_friction = m.sliding_friction;
  pair.rolling_friction = m.rolling_friction;
  table.set_pair(0, 0, pair);
  return table;
}

/// Two materials, a (index 0) and b (index 1), each with its own pair properties, and
/// `between` for an a-b contact (a wall names its material like a particle).
inline MaterialTable two_materials(const SphereMaterial& a, const SphereMaterial& b, const PairProperties& between) {
  MaterialTable table;
  for (const SphereMaterial* m : {&a, &b}) {
    Material material;
    material.name = m == &a ? "a" : "b";
    material.density_kg_per_m3 = m->density;
    material.shear_modulus_Pa = m->shear_modulus;
    material.poisson_ratio = m->poisson;
    material.conductivity_W_per_mK = TemperatureCurve(m->conductivity);
    material.specific_heat_J_per_kgK = TemperatureCurve(m->specific_heat);
    material.real_shear_modulus_Pa = m->real_shear_modulus;
    table.add(material);
  }
  for (const MaterialIndex i : {MaterialIndex{0}, MaterialIndex{1}}) {
    const SphereMaterial& m = i == 0 ? a : b;
    PairProperties own;
    own.restitution = m.restitution;
    own.sliding_friction = m.sliding_friction;
    own.rolling_friction = m.rolling_friction;
    table.set_pair(i, i, own);
  }
  table.set_pair(0, 1, between);
  return table;
}

/// The mixing of docs/physics.md ("Mixing"), written out here independently of the
/// contact code: E = 2G(1 + nu), 1/E* = (1 - nu_a^2)/E_a + (1 - nu_b^2)/E_b.
inline double mixed_youngs_modulus(double shear_a_Pa, double poisson_a, double shear_b_Pa, double poisson_b) {
  const double youngs_a = 2.0 * shear_a_Pa * (1.0 + poisson_a), youngs_b = 2.0 * shear_b_Pa * (1.0 + poisson_b);
  return 1.0 / ((1.0 - poisson_a * poisson_a) / youngs_a + (1.0 - poisson_b * poisson_b) / youngs_b);
}

/// E* of a contact between materials a and b at their simulated moduli.
inline double effective_youngs_modulus(const SphereMaterial& a, const SphereMaterial& b) {
  return mixed_youngs_modulus(a.shear_modulus, a.poisson, b.shear_modulus, b.poisson);
}

/// E*_real: each body's real modulus where it gives one, its simulated one otherwise.
inline double effective_real_youngs_modulus(const SphereMaterial& a, const SphereMaterial& b) {
  const auto real = [](const SphereMaterial& m) {
    return m.real_shear_modulus > 0.0 ? m.real_shear_modulus : m.shear_modulus;
  };
  return mixed_youngs_modulus(real(a), a.poisson, real(b), b.poisson);
}

/// 1/G* = (2 - nu_a)/G_a + (2 - nu_b)/G_b.
inline double effective_shear_modulus(const SphereMaterial& a, const SphereMaterial& b) {
  return 1.0 / ((2.0 - a.poisson) / a.shear_modulus + (2.0 - b.poisson) / b.shear_modulus);
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

/// Hertz overlap under a normal force F: delta = (3 F / (4 E* sqrt(R*)))^(2/3).
inline double hertz_overlap(double force_N, double effective_youngs_Pa, double effective_radius_m) {
  return std::pow(3.0 * force_N / (4.0 * effective_youngs_Pa * std::sqrt(effective_radius_m)), 2.0 / 3.0);
}

inline NewParticle sphere(const Vec3& x, const Vec3& v, double radius, double density, double temperature_K = 0.0) {
  NewParticle p;
  p.temperature_K = temperature_K;
  p.position_m = x;
  p.velocity_m_per_s = v;
  p.radius_m = radius;
  p.density_kg_per_m3 = density;
  return p;
}

/// An 8 x 8 x 10 lattice of grains 1 mm apart above z = -9.4 mm, each with a random
/// velocity (mean_velocity plus up to +-velocity_spread per component), spin (+-10 rad/s),
/// radius (radius times uniform(smallest_fraction, 1)) and temperature (100-300 K).
inline void add_grain_lattice(Simulation& sim, Rng& rng, double radius, double density, const Vec3& mean_velocity,
                              double velocity_spread, double smallest_fraction) {
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j)
      for (int k = 0; k < 10; ++k) {
        const Vec3 x{(i - 3.5) * 1.0e-3, (j - 3.5) * 1.0e-3, -0.0094 + k * 1.0e-3};
        const Vec3 v = mean_velocity + Vec3{rng.uniform(-velocity_spread, velocity_spread),
                                            rng.uniform(-velocity_spread, velocity_spread),
                                            rng.uniform(-velocity_spread, velocity_spread)};
        const double r = radius * rng.uniform(smallest_fraction, 1.0);  // the draws in a fixed order
        const double temperature_K = rng.uniform(100.0, 300.0);
        NewParticle p = sphere(x, v, r, density, temperature_K);
        p.angular_velocity_rad_per_s = {rng.uniform(-10, 10), rng.uniform(-10, 10), rng.uniform(-10, 10)};
        sim.add_particle(p);
      }
}

/// The store index of the particle with this id (neighbour rebuilds re-sort the store).
inline std::size_t index_of(const Simulation& sim, ParticleId id) {
  for (std::size_t i = 0; i < sim.particles.size(); ++i)
    if (sim.particles.id[i] == id) return i;
  ADD_FAILURE() << "no particle " << id;
  return 0;
}

/// A closed box, wound outwards (12 triangles).
inline TriangleMesh box_mesh(const Vec3& lo, const Vec3& hi, const std::string& name = "box") {
  TriangleMeshBuilder builder;
  const auto corner = [&](int k) { return Vec3{k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z}; };
  // Each face as four corners counter-clockwise seen from outside.
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    builder.add_triangle(corner(f[0]), corner(f[1]), corner(f[2]));
    builder.add_triangle(corner(f[0]), corner(f[2]), corner(f[3]));
  }
  return std::move(builder).finish(name);
}

}  // namespace regodem::testing
