#include "sim/geometric_packing.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace regodem {
namespace {

/// e1, e2 complete `up` to an orthonormal frame, built from the coordinate axis least
/// aligned with it: for up = z they are x and y, so the rows line up with a box's faces.
void layer_frame(const Vec3& up, Vec3& e1, Vec3& e2) {
  const double ax = std::abs(up.x), ay = std::abs(up.y), az = std::abs(up.z);
  const Vec3 helper = ax <= ay && ax <= az ? Vec3{1, 0, 0} : ay <= az ? Vec3{0, 1, 0} : Vec3{0, 0, 1};
  e1 = normalized(helper - up * dot(helper, up));
  e2 = cross(up, e1);
}

struct Range {
  double lo = 1e300, hi = -1e300;
  void take(double v) { lo = std::min(lo, v), hi = std::max(hi, v); }
};

/// The class whose count lags its share the most, so counts follow the fractions exactly.
std::size_t lagging_class(const std::vector<double>& share, const std::vector<std::size_t>& placed, std::size_t total) {
  std::size_t pick = 0;
  double worst = -1e300;
  for (std::size_t c = 0; c < share.size(); ++c) {
    const double lag = share[c] * static_cast<double>(total + 1) - static_cast<double>(placed[c]);
    if (lag > worst) worst = lag, pick = c;
  }
  return pick;
}

}  // namespace

Packing pack_region(const InsertionRegion& region, const std::vector<SizeClass>& sizes, std::size_t count,
                    const PackingOptions& options, const SiteIsFree& site_is_free) {
  Packing packing;
  if (sizes.empty() || count == 0) return packing;
  double max_radius = 0.0, share_sum = 0.0;
  for (const SizeClass& c : sizes) max_radius = std::max(max_radius, c.radius_m), share_sum += c.number_fraction;
  if (!(max_radius > 0.0) || !(share_sum > 0.0)) return packing;
  std::vector<double> share;
  double mean_volume_m3 = 0.0;
  for (const SizeClass& c : sizes) {
    share.push_back(c.number_fraction / share_sum);
    mean_volume_m3 += share.back() * 4.0 / 3.0 * std::numbers::pi * c.radius_m * c.radius_m * c.radius_m;
  }

  // Triangular layers of in-plane spacing a, each in the hollows of the one below
  // (A, B, C stacking) at the height h = sqrt(d^2 - a^2 / 3) where it rests on three
  // spheres at the contact distance d. A site takes (sqrt 3 / 2) a^2 h; a = d is the
  // face-centred cubic packing (0.740), a = sqrt 2 d the loosest of the family (0.524).
  const double d = 2.0 * max_radius * (1.0 - options.overlap_fraction);
  auto site_volume = [d](double a) { return std::sqrt(3.0) / 2.0 * a * a * std::sqrt(d * d - a * a / 3.0); };
  const double wanted_m3 = mean_volume_m3 / std::min(options.solid_fraction, mean_volume_m3 / site_volume(d));
  double a = std::sqrt(2.0) * d;  // site_volume rises with a up to here
  if (wanted_m3 < site_volume(a)) {
    double tight = d, loose = a;
    for (int i = 0; i < 60; ++i) {
      const double mid = 0.5 * (tight + loose);
      (site_volume(mid) < wanted_m3 ? tight : loose) = mid;
    }
    a = 0.5 * (tight + loose);
  }
  packing.in_plane_spacing_m = a;
  packing.layer_spacing_m = std::sqrt(d * d - a * a / 3.0);
  packing.lattice_solid_fraction = mean_volume_m3 / site_volume(a);
  packing.kept_share = std::min(1.0, options.solid_fraction / packing.lattice_solid_fraction);
  const double row_m = a * std::sqrt(3.0) / 2.0, layer_m = packing.layer_spacing_m;

  const Vec3 up = normalized(options.up);
  Vec3 e1, e2;
  layer_frame(up, e1, e2);
  Vec3 lo, hi;
  region.bounds(lo, hi);
  Range x, y, z;
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 p{corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y, corner & 4 ? hi.z : lo.z};
    x.take(dot(p, e1)), y.take(dot(p, e2)), z.take(dot(p, up));
  }

  std::vector<std::size_t> placed(sizes.size(), 0);
  std::size_t valid_sites = 0;
  const double tiny = 1e-9 * a;
  for (long k = 0; packing.spheres.size() < count; ++k) {
    const double height = z.lo + max_radius + static_cast<double>(k) * layer_m;
    if (height > z.hi - max_radius + tiny) break;
    const auto shift = static_cast<double>(k % 3);  // A, B, C: the hollows of the layer below
    const double layer_x = shift * a / 2.0, layer_y = shift * a / (2.0 * std::sqrt(3.0));
    for (long j = -1; packing.spheres.size() < count; ++j) {
      const double across = y.lo + max_radius + static_cast<double>(j) * row_m + layer_y;
      if (across > y.hi + tiny) break;
      const double row_x = (j % 2 != 0 ? a / 2.0 : 0.0) + layer_x;
      for (long i = -1; packing.spheres.size() < count; ++i) {
        const double along = x.lo + max_radius + static_cast<double>(i) * a + row_x;
        if (along > x.hi + tiny) break;
        const Vec3 site = e1 * along + e2 * across + up * height;
        if (!region.contains_sphere(site, max_radius * (1.0 - 1e-9))) continue;
        // Empty sites evenly spread: keep site s when floor(s * kept) steps up.
        const std::size_t s = valid_sites++;
        if (std::floor(static_cast<double>(s + 1) * packing.kept_share) ==
            std::floor(static_cast<double>(s) * packing.kept_share))
          continue;
        const std::size_t c = lagging_class(share, placed, packing.spheres.size());
        const double r = sizes[c].radius_m;
        if (site_is_free && !site_is_free(site, r)) continue;
        packing.spheres.push_back({site, r, c});
        ++placed[c];
      }
    }
  }
  return packing;
}

double drop_onto_support(std::vector<PackedSphere>& spheres, const Vec3& up, double max_drop_m,
                         const SiteIsFree& site_is_free) {
  if (spheres.empty() || !(max_drop_m > 0.0)) return 0.0;
  double lowest = 1e300, max_radius = 0.0, min_radius = 1e300;
  for (const PackedSphere& s : spheres) {
    lowest = std::min(lowest, dot(s.centre_m, up));
    max_radius = std::max(max_radius, s.radius_m), min_radius = std::min(min_radius, s.radius_m);
  }
  // The lowest layer meets a support first; every sphere is checked at the end.
  std::vector<std::size_t> bottom, all;
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    all.push_back(i);
    if (dot(spheres[i].centre_m, up) < lowest + max_radius) bottom.push_back(i);
  }
  auto fits = [&](double drop_m, const std::vector<std::size_t>& which) {
    for (std::size_t i : which)
      if (!site_is_free(spheres[i].centre_m - up * drop_m, spheres[i].radius_m)) return false;
    return true;
  };
  // Steps of half the smallest radius cannot jump across a wall; then bisect.
  auto lowest_fit = [&](double from_m, double to_m, const std::vector<std::size_t>& which) {
    const double step_m = 0.5 * min_radius;
    double fit = from_m, miss = -1.0;
    for (double d = from_m + step_m;; d += step_m) {
      const double at = std::min(d, to_m);
      if (!fits(at, which)) {
        miss = at;
        break;
      }
      fit = at;
      if (at >= to_m) break;
    }
    while (miss > 0.0 && miss - fit > 1e-3 * min_radius) {
      const double mid = 0.5 * (fit + miss);
      (fits(mid, which) ? fit : miss) = mid;
    }
    return fit;
  };
  double drop_m = lowest_fit(0.0, max_drop_m, bottom);
  if (!fits(drop_m, all)) drop_m = lowest_fit(0.0, drop_m, all);  // a ledge above the lowest layer
  for (PackedSphere& s : spheres) s.centre_m -= up * drop_m;
  return drop_m;
}

}  // namespace regodem
