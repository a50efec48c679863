#pragma once
// Temperature profiles: particles binned by their signed distance from a plane (the
// paper's Fig. 3, temperature against the distance from the heat source) or by their
// distance from an axis within a slab along it (Fig. 13a, the radial profile at 25 mm
// depth). A particle falls in a bin by its centre.
#include <cstddef>
#include <vector>

#include "measure/measure_region.hpp"

namespace regodem {

enum class ProfileCoordinate { plane_distance, radius };

struct ProfileGeometry {
  ProfileCoordinate coordinate = ProfileCoordinate::plane_distance;
  Vec3 origin_m;               // a point of the plane, or of the axis
  Vec3 direction{0.0, 0.0, 1.0};  // unit: the plane's normal, or the axis
  // radius: only particles whose coordinate along the axis, (x - origin) . direction,
  // lies in [slab_min_m, slab_max_m].
  double slab_min_m = 0.0, slab_max_m = 0.0;
  // Bins of width bin_m from min_m; the last one ends at max_m (narrower when the range
  // is not a whole number of bins). Particles outside [min_m, max_m] are left out.
  double min_m = 0.0, max_m = 0.0, bin_m = 0.0;

  std::size_t bin_count() const;
  /// Centre of bin k.
  double bin_centre_m(std::size_t k) const;
};

/// The statistics of each bin (bin_count() of them), of the particles moved back by
/// the profile's offset_m (a profile that moves with a wall).
std::vector<TemperatureStatistics> temperature_profile(const ParticleStore& particles,
                                                       const ProfileGeometry& profile, const Vec3& offset_m = {});
/// The same as sums, which several ranks' merge, leaving out the flagged particles.
std::vector<TemperatureAccumulator> temperature_profile_sums(const ParticleStore& particles,
                                                             const ProfileGeometry& profile, const Vec3& offset_m = {},
                                                             LeftOut left_out = {});

}  // namespace regodem
