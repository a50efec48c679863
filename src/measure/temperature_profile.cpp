#include "measure/temperature_profile.hpp"

#include <algorithm>
#include <cmath>

namespace regodem {

std::size_t ProfileGeometry::bin_count() const {
  if (!(bin_m > 0.0) || !(max_m > min_m)) return 0;
  // A range of a whole number of bins, up to round-off, gets exactly that many.
  return static_cast<std::size_t>(std::ceil((max_m - min_m) / bin_m - 1e-9));
}

double ProfileGeometry::bin_centre_m(std::size_t k) const {
  const double lo = min_m + static_cast<double>(k) * bin_m;
  return 0.5 * (lo + std::min(lo + bin_m, max_m));
}

std::vector<TemperatureAccumulator> temperature_profile_sums(const ParticleStore& particles,
                                                             const ProfileGeometry& profile, const Vec3& offset_m,
                                                             LeftOut left_out) {
  const std::size_t bins = profile.bin_count();
  if (bins == 0) return {};
  std::vector<TemperatureAccumulator> sums(bins);
  for (std::size_t i = 0; i < particles.size(); ++i) {
    if (!left_out.empty() && left_out[i]) continue;
    const Vec3 d = particles.position_m[i] - offset_m - profile.origin_m;
    const double along = dot(d, profile.direction);
    double coordinate = along;
    if (profile.coordinate == ProfileCoordinate::radius) {
      if (along < profile.slab_min_m || along > profile.slab_max_m) continue;
      coordinate = std::sqrt(std::max(0.0, norm2(d) - along * along));
    }
    if (coordinate < profile.min_m || coordinate > profile.max_m) continue;
    const auto k = std::min(bins - 1, static_cast<std::size_t>((coordinate - profile.min_m) / profile.bin_m));
    sums[k].add(particles.temperature_K[i], false);
  }
  return sums;
}

std::vector<TemperatureStatistics> temperature_profile(const ParticleStore& particles,
                                                       const ProfileGeometry& profile, const Vec3& offset_m) {
  const std::vector<TemperatureAccumulator> sums = temperature_profile_sums(particles, profile, offset_m);
  const std::size_t bins = sums.size();
  std::vector<TemperatureStatistics> result(bins);
  for (std::size_t k = 0; k < bins; ++k) result[k] = sums[k].result();
  return result;
}

}  // namespace regodem
