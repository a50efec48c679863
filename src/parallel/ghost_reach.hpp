#pragma once
// Which particles a rank's brick wants from the other ranks as ghosts (issue 19). A pair is
// listed within R_i + R_j + h_i + h_j (NeighborSkin: each half h at most its largest), so
// particle g can be a partner of an own particle o of brick r only if |x_g - x_o| <=
// R_g + R_o + 2 h_max. Each brick describes its own particles by bands of radii: for each
// band the largest radius in it and the box that holds the band's centres; g is wanted
// where it lies within R_g + R_band + 2 h_max of some band's box (o lies in its band's box,
// R_o <= R_band, so no partner is missed). In a multi-level bed (0.6 / 2.4 mm grains) a brick
// that holds both sizes then takes ghosts by the coarse reach only near its coarse grains,
// and a fine grain reaches a fine brick by two fine radii and the skin. A brick without
// particles needs no ghosts.
#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "core/vec3.hpp"
#include "parallel/recursive_bisection.hpp"

namespace regodem {

/// A brick's own particles whose radii lie in one band: the largest radius among them
/// (0: the band is empty) and the box of their centres.
struct RadiusBand {
  double largest_radius_m = 0.0;
  Brick centres{};
};

struct GhostReach {
  /// A brick's bands, by its own largest radius R: radii above R/2, above R/4, the rest.
  static constexpr std::size_t kBandsPerBrick = 3;
  /// A band's numbers as sent between ranks: the radius, then the box's low and high corners.
  static constexpr std::size_t kValuesPerBand = 7;

  double skin_m = 0.0;            // 2 h_max: the most a pair's two halves of the skin add
  std::vector<RadiusBand> bands;  // kBandsPerBrick per brick, by brick

  std::size_t bricks() const { return bands.size() / kBandsPerBrick; }
  /// Whether a particle of `radius_m` at x is wanted as a ghost by brick `rank`.
  bool wanted(int rank, const Vec3& x, double radius_m) const {
    const std::size_t first = static_cast<std::size_t>(rank) * kBandsPerBrick;
    for (std::size_t b = first; b < first + kBandsPerBrick; ++b)
      if (bands[b].largest_radius_m > 0.0 &&
          bands[b].centres.distance_m(x) <= radius_m + bands[b].largest_radius_m + skin_m)
        return true;
    return false;
  }
  /// The bricks, but `except`, that may want some particle of radius at most
  /// `largest_radius_m` centred in `box`: every brick for which wanted() is true for such a
  /// particle is among them (a band's box is no nearer to a point of `box` than to `box`).
  /// A rank then asks wanted() of its neighbours only, not of every rank.
  std::vector<int> bricks_near(const Brick& box, double largest_radius_m, int except) const;
};

/// The box of the centres `positions` (an empty box at the origin for none) and their
/// largest radius.
struct CentresBox {
  Brick box{};
  double largest_radius_m = 0.0;
};
CentresBox centres_box(std::span<const Vec3> positions, std::span<const double> radii_m);

/// One brick's bands from its own particles.
std::array<RadiusBand, GhostReach::kBandsPerBrick> radius_bands(std::span<const Vec3> positions,
                                                                std::span<const double> radii_m);
/// Every brick's bands, by brick, when every particle is at hand (one process, the model).
std::vector<RadiusBand> radius_bands_by_brick(const RecursiveBisection& bricks, std::span<const Vec3> positions,
                                              std::span<const double> radii_m);
/// Bands as numbers (kValuesPerBand each) and back, to send them between ranks.
std::vector<double> band_values(std::span<const RadiusBand> bands);
std::vector<RadiusBand> bands_of_values(std::span<const double> values);

}  // namespace regodem
