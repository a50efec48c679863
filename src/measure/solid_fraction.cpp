#include "measure/solid_fraction.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <vector>

namespace regodem {

double solid_fraction(const ParticleStore& particles, const ProbeCylinder& probe, double spacing_m) {
  // Bin the particles on a grid of cells as wide as the largest diameter.
  double max_radius = 0.0;
  for (double r : particles.radius_m) max_radius = std::max(max_radius, r);
  if (max_radius == 0.0) return 0.0;
  const double cell = 2.0 * max_radius;
  auto key = [cell](const Vec3& x) {
    const auto ix = static_cast<std::int64_t>(std::floor(x.x / cell));
    const auto iy = static_cast<std::int64_t>(std::floor(x.y / cell));
    const auto iz = static_cast<std::int64_t>(std::floor(x.z / cell));
    return (ix * 73856093) ^ (iy * 19349663) ^ (iz * 83492791);
  };
  std::unordered_multimap<std::int64_t, std::uint32_t> bins;
  for (std::uint32_t i = 0; i < particles.size(); ++i) bins.emplace(key(particles.position_m[i]), i);

  const Vec3 helper = std::abs(probe.axis.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  const Vec3 e1 = normalized(cross(probe.axis, helper));
  const Vec3 e2 = cross(probe.axis, e1);
  const int n_radial = static_cast<int>(std::ceil(probe.radius_m / spacing_m));
  const int n_axial = static_cast<int>(std::floor(probe.length_m / spacing_m));
  std::size_t inside_probe = 0, inside_solid = 0;
  for (int k = 0; k < n_axial; ++k)
    for (int a = -n_radial; a <= n_radial; ++a)
      for (int b = -n_radial; b <= n_radial; ++b) {
        const double u = (a + 0.5) * spacing_m, v = (b + 0.5) * spacing_m;
        if (u * u + v * v > probe.radius_m * probe.radius_m) continue;
        const Vec3 x = probe.base_m + probe.axis * ((k + 0.5) * spacing_m) + e1 * u + e2 * v;
        ++inside_probe;
        bool solid = false;
        for (int dz = -1; dz <= 1 && !solid; ++dz)
          for (int dy = -1; dy <= 1 && !solid; ++dy)
            for (int dx = -1; dx <= 1 && !solid; ++dx) {
              const Vec3 neighbour_cell = x + Vec3{dx * cell, dy * cell, dz * cell};
              auto [first, last] = bins.equal_range(key(neighbour_cell));
              for (auto it = first; it != last && !solid; ++it) {
                const std::uint32_t i = it->second;
                const double r = particles.radius_m[i];
                if (norm2(particles.position_m[i] - x) <= r * r) solid = true;
              }
            }
        if (solid) ++inside_solid;
      }
  return inside_probe ? static_cast<double>(inside_solid) / static_cast<double>(inside_probe) : 0.0;
}

}  // namespace regodem
