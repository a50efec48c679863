#pragma once
// Bulk solid fraction of a packing inside a probe cylinder, measured by sampling a
// regular lattice of points and counting those inside a particle (partial spheres at
// the probe's boundary count exactly as much as lies inside it).
#include "core/particle_store.hpp"

namespace regodem {

struct ProbeCylinder {
  Vec3 base_m;              // centre of the bottom end
  Vec3 axis{0.0, 0.0, 1.0}; // unit
  double radius_m = 0.0;
  double length_m = 0.0;
};

/// Fraction of the probe volume occupied by particles, sampled on a cubic lattice of
/// the given spacing (error ~ spacing / radius of the particles, times the surface).
double solid_fraction(const ParticleStore& particles, const ProbeCylinder& probe, double spacing_m);

}  // namespace regodem
