#pragma once
// Regions that measurements average over: a box, a solid cylinder, an annulus, or a
// band (the particles within a distance on one side of a plane or of a cylindrical
// surface, the paper's "2 mm on the inner side of the sieve", Eq. 4-5). A particle
// belongs to a region when its centre does. A region may move with a wall: the caller
// passes the wall's translation since the start as `offset_m` (the region is given
// where it is at the start).
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <vector>

#include "core/exact_sum.hpp"
#include "core/particle_store.hpp"

namespace regodem {

enum class MeasureShape {
  box,            // min_m .. max_m
  cylinder,       // base_m, axis, radius_m, length_m
  annulus,        // as cylinder, plus inner_radius_m
  plane_band,     // signed distance (x - base_m) . axis in [near_m, far_m], within lateral_radius_m of the axis
  cylinder_band,  // r - radius_m in [near_m, far_m], r the distance from the axis; axial 0 .. length_m
};

struct MeasureRegion {
  MeasureShape shape = MeasureShape::box;
  Vec3 min_m, max_m;           // box
  Vec3 base_m;                 // cylinder, annulus: centre of the bottom end; plane band: a point of the plane
  Vec3 axis{0.0, 0.0, 1.0};    // unit: cylinder axis, or the plane's normal (its front side)
  double length_m = std::numeric_limits<double>::infinity();  // along axis from base_m (cylinder shapes)
  double radius_m = 0.0;       // cylinder, annulus: outer radius; cylinder band: the surface's radius
  double inner_radius_m = 0.0; // annulus
  // Bands: the signed distance from the surface (along the normal; outwards for a
  // cylinder) lies in [near_m, far_m]: [0, w] on the front (outside), [-w, 0) behind (inside).
  double near_m = 0.0, far_m = 0.0;
  double lateral_radius_m = std::numeric_limits<double>::infinity();  // plane band: a disk's radius

  /// Whether the point x (already moved back by the region's offset) lies inside.
  bool contains(const Vec3& x_m) const;
};

/// A band of the given width on one side of a plane (front: the side the normal points
/// to) or of a cylindrical surface (front: outside).
MeasureRegion plane_band(const Vec3& point_m, const Vec3& unit_normal, double width_m, bool front,
                         double lateral_radius_m = std::numeric_limits<double>::infinity());
MeasureRegion cylinder_band(const Vec3& base_m, const Vec3& unit_axis, double radius_m, double length_m,
                            double width_m, bool outside);

/// Temperatures of a set of particles. Without particles the count is 0 and the
/// temperatures are NaN.
struct TemperatureStatistics {
  std::size_t count = 0;
  double mean_K = std::numeric_limits<double>::quiet_NaN();
  double min_K = std::numeric_limits<double>::quiet_NaN();
  double max_K = std::numeric_limits<double>::quiet_NaN();
  std::size_t crossed = 0;  // of them, those whose peak temperature went above the threshold
  double crossed_fraction() const {
    return count > 0 ? static_cast<double>(crossed) / static_cast<double>(count)
                     : std::numeric_limits<double>::quiet_NaN();
  }
};

/// Sums temperatures one particle at a time. The sum is exact (core/exact_sum.hpp), so
/// the mean of the same particles is the same bits in any order, and the partial sums of
/// several MPI ranks merge into the sum of all.
class TemperatureAccumulator {
 public:
  void add(double temperature_K, bool crossed) {
    ++count_;
    sum_K_.add(temperature_K);
    min_K_ = count_ == 1 ? temperature_K : (temperature_K < min_K_ ? temperature_K : min_K_);
    max_K_ = count_ == 1 ? temperature_K : (temperature_K > max_K_ ? temperature_K : max_K_);
    crossed_ += crossed ? 1 : 0;
  }
  /// Adds another accumulator's particles.
  void merge(const TemperatureAccumulator& other);
  TemperatureStatistics result() const;
  /// For a message between ranks (as ExactSum's).
  void append_to(std::vector<double>& out) const;
  static TemperatureAccumulator read_from(std::span<const double> in, std::size_t& at);

 private:
  std::size_t count_ = 0, crossed_ = 0;
  ExactSum sum_K_;
  double min_K_ = 0.0, max_K_ = 0.0;
};

/// Particles a measurement leaves out, one flag per particle: in a run over MPI ranks the
/// ghosts, which their own ranks count. Empty: none.
using LeftOut = std::span<const std::uint8_t>;

/// Mean, min, max temperature and count of the particles whose centre lies in the
/// region moved by offset_m; with a threshold, how many of them have a peak
/// temperature above it (ParticleStore::peak_temperature_K). One pass over the particles.
TemperatureAccumulator region_sums(const ParticleStore& particles, const MeasureRegion& region,
                                   const Vec3& offset_m = {}, std::optional<double> threshold_K = std::nullopt,
                                   LeftOut left_out = {});
TemperatureStatistics region_statistics(const ParticleStore& particles, const MeasureRegion& region,
                                        const Vec3& offset_m = {},
                                        std::optional<double> threshold_K = std::nullopt);

/// The paper's T_in, T_out and T_d = T_in - T_out (Eq. 3-5): mean temperatures of the
/// particles within a distance on the inner and on the outer side of a wall.
struct BandTemperatures {
  TemperatureStatistics in, out;
  double difference_K() const { return in.mean_K - out.mean_K; }
};
struct BandSums {
  TemperatureAccumulator in, out;
};
BandSums band_sums(const ParticleStore& particles, const MeasureRegion& in_band, const MeasureRegion& out_band,
                   const Vec3& offset_m = {}, LeftOut left_out = {});
BandTemperatures band_temperatures(const ParticleStore& particles, const MeasureRegion& in_band,
                                   const MeasureRegion& out_band, const Vec3& offset_m = {});

}  // namespace regodem
