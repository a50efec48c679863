#include "measure/measure_region.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace regodem {

bool MeasureRegion::contains(const Vec3& x_m) const {
  if (shape == MeasureShape::box)
    return x_m.x >= min_m.x && x_m.y >= min_m.y && x_m.z >= min_m.z && x_m.x <= max_m.x && x_m.y <= max_m.y &&
           x_m.z <= max_m.z;
  const Vec3 d = x_m - base_m;
  const double along = dot(d, axis);
  const double across2 = std::max(0.0, norm2(d) - along * along);  // squared distance from the axis
  switch (shape) {
    case MeasureShape::box: break;
    case MeasureShape::cylinder:
      return along >= 0.0 && along <= length_m && across2 <= radius_m * radius_m;
    case MeasureShape::annulus:
      return along >= 0.0 && along <= length_m && across2 <= radius_m * radius_m &&
             across2 >= inner_radius_m * inner_radius_m;
    case MeasureShape::plane_band:
      // Half-open at the surface so that a centre exactly on it counts on one side only.
      return (near_m < 0.0 ? along >= near_m && along < 0.0 : along >= near_m && along <= far_m) &&
             across2 <= lateral_radius_m * lateral_radius_m;
    case MeasureShape::cylinder_band: {
      if (along < 0.0 || along > length_m) return false;
      const double from_surface = std::sqrt(across2) - radius_m;
      return near_m < 0.0 ? from_surface >= near_m && from_surface < 0.0
                          : from_surface >= near_m && from_surface <= far_m;
    }
  }
  return false;
}

MeasureRegion plane_band(const Vec3& point_m, const Vec3& unit_normal, double width_m, bool front,
                         double lateral_radius_m) {
  MeasureRegion r;
  r.shape = MeasureShape::plane_band;
  r.base_m = point_m;
  r.axis = unit_normal;
  r.near_m = front ? 0.0 : -width_m;
  r.far_m = front ? width_m : 0.0;
  r.lateral_radius_m = lateral_radius_m;
  return r;
}

MeasureRegion cylinder_band(const Vec3& base_m, const Vec3& unit_axis, double radius_m, double length_m,
                            double width_m, bool outside) {
  MeasureRegion r;
  r.shape = MeasureShape::cylinder_band;
  r.base_m = base_m;
  r.axis = unit_axis;
  r.radius_m = radius_m;
  r.length_m = length_m;
  r.near_m = outside ? 0.0 : -width_m;
  r.far_m = outside ? width_m : 0.0;
  return r;
}

void TemperatureAccumulator::merge(const TemperatureAccumulator& other) {
  if (other.count_ == 0) return;
  min_K_ = count_ == 0 ? other.min_K_ : std::min(min_K_, other.min_K_);
  max_K_ = count_ == 0 ? other.max_K_ : std::max(max_K_, other.max_K_);
  count_ += other.count_;
  crossed_ += other.crossed_;
  sum_K_.merge(other.sum_K_);
}

TemperatureStatistics TemperatureAccumulator::result() const {
  TemperatureStatistics s;
  s.count = count_;
  s.crossed = crossed_;
  if (count_ > 0) {
    s.mean_K = sum_K_.value() / static_cast<double>(count_);
    s.min_K = min_K_;
    s.max_K = max_K_;
  }
  return s;
}

void TemperatureAccumulator::append_to(std::vector<double>& out) const {
  // Counts below 2^53 are exact as doubles.
  out.insert(out.end(), {static_cast<double>(count_), static_cast<double>(crossed_), min_K_, max_K_});
  sum_K_.append_to(out);
}

TemperatureAccumulator TemperatureAccumulator::read_from(std::span<const double> in, std::size_t& at) {
  if (at + 4 > in.size())
    throw std::invalid_argument("a temperature accumulator's record at " + std::to_string(at) + " is cut short");
  TemperatureAccumulator a;
  a.count_ = static_cast<std::size_t>(in[at]);
  a.crossed_ = static_cast<std::size_t>(in[at + 1]);
  a.min_K_ = in[at + 2];
  a.max_K_ = in[at + 3];
  at += 4;
  a.sum_K_ = ExactSum::read_from(in, at);
  return a;
}

TemperatureAccumulator region_sums(const ParticleStore& particles, const MeasureRegion& region, const Vec3& offset_m,
                                   std::optional<double> threshold_K, LeftOut left_out) {
  TemperatureAccumulator sum;
  const std::size_t n = particles.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (!left_out.empty() && left_out[i]) continue;
    if (!region.contains(particles.position_m[i] - offset_m)) continue;
    sum.add(particles.temperature_K[i], threshold_K && particles.peak_temperature_K[i] > *threshold_K);
  }
  return sum;
}

TemperatureStatistics region_statistics(const ParticleStore& particles, const MeasureRegion& region,
                                        const Vec3& offset_m, std::optional<double> threshold_K) {
  return region_sums(particles, region, offset_m, threshold_K).result();
}

BandSums band_sums(const ParticleStore& particles, const MeasureRegion& in_band, const MeasureRegion& out_band,
                   const Vec3& offset_m, LeftOut left_out) {
  BandSums sums;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    if (!left_out.empty() && left_out[i]) continue;
    const Vec3 x = particles.position_m[i] - offset_m;
    if (in_band.contains(x)) sums.in.add(particles.temperature_K[i], false);
    if (out_band.contains(x)) sums.out.add(particles.temperature_K[i], false);
  }
  return sums;
}

BandTemperatures band_temperatures(const ParticleStore& particles, const MeasureRegion& in_band,
                                   const MeasureRegion& out_band, const Vec3& offset_m) {
  const BandSums sums = band_sums(particles, in_band, out_band, offset_m);
  return {sums.in.result(), sums.out.result()};
}

}  // namespace regodem
