#pragma once
// A bed built by geometry instead of by pouring: spheres on a lattice inside an
// insertion region, filled layer by layer from the bottom, at a target solid fraction.
// `regodem estimate` times a stage's steps on such a bed where the run would only have
// it after a pour (docs/estimate.md).
//
// The lattice keeps every sphere in contact, so that contacts and conduction cost what
// a settled bed's do, and stable under gravity: triangular layers, each resting in the
// hollows of the one below (A, B, C stacking), each sphere on three below and under
// three above. Spreading the layers (in-plane spacing from 2R to 2.83R) lets each sink
// deeper and sets the solid fraction, from 0.740 (face-centred cubic) down to 0.524;
// below that, sites are left empty, evenly spread. The contact distance is
// 2R(1 - overlap_fraction): each contact overlaps by that small fraction of the
// diameter, enough to exist, too little to throw the bed apart.
#include <cstddef>
#include <functional>
#include <vector>

#include "core/vec3.hpp"
#include "sim/insertion.hpp"
#include "sim/insertion_region.hpp"

namespace regodem {

struct PackingOptions {
  double solid_fraction = 0.6;      // target, in the bulk (away from the region's boundary)
  double overlap_fraction = 1e-5;   // of the largest diameter, at every lattice contact
  Vec3 up{0.0, 0.0, 1.0};           // layers fill from the lowest along -up (unit)
};

struct PackedSphere {
  Vec3 centre_m;
  double radius_m = 0.0;
  std::size_t size_class = 0;  // index into the insertion's sizes
};

struct Packing {
  std::vector<PackedSphere> spheres;
  double lattice_solid_fraction = 0.0;  // of the full lattice, before sites are left empty
  double kept_share = 1.0;              // share of the lattice sites filled
  double in_plane_spacing_m = 0.0;      // of a layer's triangular lattice
  double layer_spacing_m = 0.0;         // between layers, along up
};

/// The caller's veto on a site (an existing particle or a wall there): true if free.
using SiteIsFree = std::function<bool(const Vec3& centre_m, double radius_m)>;

/// Up to `count` spheres of the given size classes (numbers in their fractions,
/// stratified as the insertion does) on the lattice inside `region`, lowest layers
/// first; fewer when the region is full. Mixtures sit on the largest size's lattice,
/// so the smaller spheres touch fewer neighbours.
Packing pack_region(const InsertionRegion& region, const std::vector<SizeClass>& sizes, std::size_t count,
                    const PackingOptions& options, const SiteIsFree& site_is_free = {});

/// Lowers the whole packing along -up, rigidly, onto what will carry it (a floor, a
/// bed below): an insertion region usually hangs above the bed the pour would make,
/// and a lattice in free fall has no load on its contacts, which then drift open. Stops
/// where `site_is_free` first refuses a sphere (to within a thousandth of the smallest
/// radius), or after max_drop_m. Returns the distance lowered.
double drop_onto_support(std::vector<PackedSphere>& spheres, const Vec3& up, double max_drop_m,
                         const SiteIsFree& site_is_free);

}  // namespace regodem
