// The geometric beds of `regodem estimate` (sim/geometric_packing.hpp): the bulk solid
// fraction they reach, that every sphere lies inside its region, that overlaps stay at
// the lattice's small stated fraction, and that they fill from the bottom.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "core/particle_store.hpp"
#include "measure/solid_fraction.hpp"
#include "sim/geometric_packing.hpp"

namespace regodem {
namespace {

constexpr double kRadius = 0.3e-3;
constexpr double kOverlapFraction = 0.002;
// The bulk fraction, measured in a probe two diameters clear of the region's boundary:
// the lattice is regular, so a finite probe sees it within about this much.
constexpr double kFractionTolerance = 0.02;

ParticleStore store_of(const Packing& packing) {
  ParticleStore store;
  for (const PackedSphere& s : packing.spheres) {
    NewParticle p;
    p.position_m = s.centre_m;
    p.radius_m = s.radius_m;
    p.density_kg_per_m3 = 1000.0;
    store.add(p);
  }
  return store;
}

/// Largest overlap of any two spheres, as a fraction of the pair's smaller diameter.
double max_overlap_fraction(const Packing& packing) {
  double worst = 0.0;
  const auto& s = packing.spheres;
  for (std::size_t i = 0; i < s.size(); ++i)
    for (std::size_t j = i + 1; j < s.size(); ++j) {
      const double overlap = s[i].radius_m + s[j].radius_m - norm(s[i].centre_m - s[j].centre_m);
      worst = std::max(worst, overlap / (2.0 * std::min(s[i].radius_m, s[j].radius_m)));
    }
  return worst;
}

/// Mean number of neighbours each sphere touches (overlap > 0).
double coordination(const Packing& packing) {
  std::size_t touches = 0;
  const auto& s = packing.spheres;
  for (std::size_t i = 0; i < s.size(); ++i)
    for (std::size_t j = i + 1; j < s.size(); ++j)
      if (norm(s[i].centre_m - s[j].centre_m) < s[i].radius_m + s[j].radius_m) touches += 2;
  return static_cast<double>(touches) / static_cast<double>(s.size());
}

std::vector<SizeClass> one_size() { return {{kRadius, 1.0}}; }

TEST(GeometricPacking, BoxFilledAtTheTargetFractionInsideWithSmallOverlaps) {
  InsertionRegion box;
  box.shape = InsertionShape::box;
  box.min_m = {0.0, 0.0, 0.0};
  box.max_m = {8e-3, 8e-3, 8e-3};
  PackingOptions options;
  options.solid_fraction = 0.6;
  options.overlap_fraction = kOverlapFraction;
  const Packing packing = pack_region(box, one_size(), 1000000, options);
  ASSERT_GT(packing.spheres.size(), 1000u);
  // Spread layers: no in-plane contacts, each sphere on three below and under three above.
  EXPECT_GT(packing.in_plane_spacing_m, 2.0 * kRadius);
  for (const PackedSphere& s : packing.spheres) ASSERT_TRUE(box.contains_sphere(s.centre_m, s.radius_m * (1.0 - 1e-9)));
  EXPECT_LE(max_overlap_fraction(packing), kOverlapFraction * (1.0 + 1e-6));
  EXPECT_GT(coordination(packing), 4.5);  // 6 inside, fewer at the boundary: contacts cost as in a bed

  const ProbeCylinder probe{{4e-3, 4e-3, 1.2e-3}, {0, 0, 1}, 2.6e-3, 5.6e-3};
  EXPECT_NEAR(solid_fraction(store_of(packing), probe, 0.04e-3), 0.6, kFractionTolerance);
}

TEST(GeometricPacking, CylinderFilledAtADenserTarget) {
  InsertionRegion cylinder;
  cylinder.shape = InsertionShape::cylinder;
  cylinder.base_m = {1e-3, -2e-3, 0.5e-3};
  cylinder.axis = {0, 0, 1};
  cylinder.radius_m = 4.5e-3;
  cylinder.length_m = 7e-3;
  PackingOptions options;
  options.solid_fraction = 0.68;
  const Packing packing = pack_region(cylinder, one_size(), 1000000, options);
  ASSERT_GT(packing.spheres.size(), 1000u);
  EXPECT_LT(packing.in_plane_spacing_m, 2.0 * kRadius * 1.1);  // close to face-centred cubic (0.740)
  for (const PackedSphere& s : packing.spheres)
    ASSERT_TRUE(cylinder.contains_sphere(s.centre_m, s.radius_m * (1.0 - 1e-9)));
  EXPECT_LE(max_overlap_fraction(packing), options.overlap_fraction * (1.0 + 1e-6));

  const ProbeCylinder probe{{1e-3, -2e-3, 1.7e-3}, {0, 0, 1}, 3.2e-3, 4.6e-3};
  EXPECT_NEAR(solid_fraction(store_of(packing), probe, 0.04e-3), 0.68, kFractionTolerance);
}

TEST(GeometricPacking, FillsFromTheBottomUpToTheCountAndRespectsTheVeto) {
  InsertionRegion box;
  box.shape = InsertionShape::box;
  box.min_m = {0.0, 0.0, 0.0};
  box.max_m = {6e-3, 6e-3, 20e-3};
  const Packing packing = pack_region(box, one_size(), 150, PackingOptions{});
  ASSERT_EQ(packing.spheres.size(), 150u);
  double top = 0.0;
  for (const PackedSphere& s : packing.spheres) top = std::max(top, s.centre_m.z);
  // 150 spheres at about 70 a layer: three layers.
  EXPECT_LT(top, kRadius + 2.0 * packing.layer_spacing_m + 1e-9);

  // A veto (a wall or particles below z = 3 mm): everything lands above it.
  const Packing above = pack_region(box, one_size(), 150, PackingOptions{},
                                    [](const Vec3& x, double r) { return x.z - r >= 3e-3; });
  ASSERT_EQ(above.spheres.size(), 150u);
  for (const PackedSphere& s : above.spheres) EXPECT_GE(s.centre_m.z - s.radius_m, 3e-3);
}

TEST(GeometricPacking, MixturesFollowTheirNumberFractions) {
  InsertionRegion box;
  box.shape = InsertionShape::box;
  box.min_m = {0.0, 0.0, 0.0};
  box.max_m = {10e-3, 10e-3, 10e-3};
  const std::vector<SizeClass> sizes{{kRadius, 0.25}, {0.5 * kRadius, 0.75}};
  const Packing packing = pack_region(box, sizes, 400, PackingOptions{});
  ASSERT_EQ(packing.spheres.size(), 400u);
  const auto small = std::count_if(packing.spheres.begin(), packing.spheres.end(),
                                   [](const PackedSphere& s) { return s.size_class == 1; });
  EXPECT_EQ(small, 300);
  EXPECT_LE(max_overlap_fraction(packing), PackingOptions{}.overlap_fraction * (1.0 + 1e-6));
}

}  // namespace
}  // namespace regodem
