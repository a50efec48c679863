#pragma once
// Where particles are inserted: a box, a cylinder or an annulus (a cylinder with a
// core removed), with uniform random sampling of sphere centres that keep the whole
// sphere inside.
#include "core/rng.hpp"
#include "core/vec3.hpp"

namespace regodem {

enum class InsertionShape { box, cylinder, annulus };

struct InsertionRegion {
  InsertionShape shape = InsertionShape::box;
  Vec3 min_m, max_m;        // box
  Vec3 base_m;              // cylinder, annulus: centre of the bottom end
  Vec3 axis{0.0, 0.0, 1.0}; // unit
  double length_m = 0.0;
  double radius_m = 0.0;
  double inner_radius_m = 0.0;  // annulus

  double volume_m3() const;
  /// Axis-aligned bounding box of the region.
  void bounds(Vec3& lo, Vec3& hi) const;
  /// A uniformly random centre for a sphere of radius r lying wholly inside; false if
  /// the sphere does not fit at all.
  bool sample_centre(Rng& rng, double radius_m, Vec3& centre_m) const;
  /// Whether a sphere of radius r at centre_m lies wholly inside.
  bool contains_sphere(const Vec3& centre_m, double radius_m) const;
};

}  // namespace regodem
