#include "scenario/wall_speed_check.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "sim/time_step.hpp"

namespace regodem {

WallSpeedReport wall_speed_report(WallSet& walls, const MaterialTable& materials,
                                  const std::vector<double>& smallest_radius_m, double time_step_s,
                                  double rayleigh_fraction) {
  WallSpeedReport report;
  double smallest_of_all_m = std::numeric_limits<double>::infinity();
  for (const double r : smallest_radius_m) smallest_of_all_m = std::min(smallest_of_all_m, r);
  for (std::uint32_t b = 0; b < walls.bodies.size(); ++b) {
    const double speed = walls.fastest_surface_speed_m_per_s(b);
    if (!(speed > 0.0)) continue;
    std::vector<char> body_material(materials.size(), 0);
    for (const WallPrimitive& p : walls.primitives)
      if (p.body == b) body_material[p.material] = 1;
    for (const MeshWall& m : walls.meshes)
      if (m.body == b) body_material[m.material] = 1;
    // The shortest contact among the pairs this body can strike.
    double shortest_s = std::numeric_limits<double>::infinity();
    std::string grain;
    for (std::size_t a = 0; a < materials.size(); ++a) {
      const double r = smallest_radius_m[a];
      if (!std::isfinite(r)) continue;
      const Material& particle = materials[static_cast<MaterialIndex>(a)];
      const double mass = 4.0 / 3.0 * std::numbers::pi * r * r * r * particle.density_kg_per_m3;
      for (std::size_t w = 0; w < materials.size(); ++w) {
        if (!body_material[w]) continue;
        const double e_star = effective_youngs_modulus_Pa(particle, materials[static_cast<MaterialIndex>(w)]);
        const double t = hertz_contact_time_s(mass, r, e_star, speed);  // a wall: m* = m, R* = r
        if (t < shortest_s) {
          shortest_s = t;
          grain = fmt::format("a '{}' grain of radius {:.4g} m", particle.name, r);
        }
      }
    }
    if (!std::isfinite(shortest_s)) continue;
    const double per_step_m = speed * time_step_s;
    const double steps = shortest_s / time_step_s;
    const std::string& name = walls.bodies[b].name;
    report.impacts.push_back({b, speed, shortest_s, steps});
    report.lines.push_back(fmt::format("wall '{}': its fastest point moves {:.3g} m/s, {:.3g} m a step ({:.2g} of the "
                                       "smallest radius); {} struck at that speed is in contact {:.3g} s (Hertz), "
                                       "{:.1f} steps",
                                       name, speed, per_step_m, per_step_m / smallest_of_all_m, grain, shortest_s,
                                       steps));
    if (steps >= kMinimumStepsPerImpact) continue;
    const double step_needed_s = shortest_s / kMinimumStepsPerImpact;
    report.warnings.push_back(fmt::format(
        "wall '{}' strikes grains faster than the step resolves: {} struck at its fastest point's {:.3g} m/s is in "
        "contact {:.1f} steps (Hertz), fewer than {:.0f}. The losses of such contacts (and their heat with "
        "`dissipation_heating`) then depend on the step: use a step of at most {:.3g} s{}, or check the result "
        "against a smaller one",
        name, grain, speed, steps, kMinimumStepsPerImpact, step_needed_s,
        rayleigh_fraction > 0.0
            ? fmt::format(" (rayleigh_fraction {:.2g})", rayleigh_fraction * step_needed_s / time_step_s)
            : std::string()));
  }
  return report;
}

}  // namespace regodem
