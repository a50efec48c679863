#include "geometry/auger_generator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "core/error.hpp"

namespace regodem {
namespace {

constexpr double two_pi = 2.0 * std::numbers::pi;
constexpr int min_segments_per_turn = 16;  // cos(pi/16) = 0.981 > kBladeRootFraction: blade root inside the N-gon
constexpr int max_segments_per_turn = 4096;
constexpr double max_triangles = 2e7;

void check_length(double value, const char* name) {
  if (!std::isfinite(value)) throw InputError(fmt::format("auger: {} must be a finite number, not {}", name, value));
  if (value <= 0.0) throw InputError(fmt::format("auger: {} must be positive, not {}", name, value));
}

/// Axial extent of the blade's bottom face: from the top of the tip to length - thickness.
double blade_bottom_start_m(const AugerSpec& s) { return s.tip_height_m(); }
double blade_bottom_end_m(const AugerSpec& s) { return s.length_m - s.flute_thickness_m; }

/// Segments along one blade: at least segments_per_turn per turn (rounded up).
double blade_segments(const AugerSpec& s) {
  const double turns = (blade_bottom_end_m(s) - blade_bottom_start_m(s)) / s.pitch_m;
  return std::max(1.0, std::ceil(turns * s.segments_per_turn));
}

/// Adds triangles to one shell; a dropped (degenerate) triangle would open the shell.
class ShellBuilder {
 public:
  explicit ShellBuilder(bool flip) : flip_(flip) {}
  void triangle(const Vec3& a, const Vec3& b, const Vec3& c) {
    const bool kept = flip_ ? builder_.add_triangle(a, c, b) : builder_.add_triangle(a, b, c);
    if (!kept)
      throw InputError("auger: a facet came out degenerate (zero area); the proportions are too extreme "
                       "for the mesh (check the lengths' units and segments_per_turn)");
  }
  /// Quad a-b-c-d (counterclockwise seen from outside), split along a-c.
  void quad(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    triangle(a, b, c);
    triangle(a, c, d);
  }
  TriangleMesh finish(std::string source) && { return std::move(builder_).finish(std::move(source)); }

 private:
  bool flip_;
  TriangleMeshBuilder builder_;
};

// ---------------------------------------------------------------------------------
TriangleMesh make_core(const AugerSpec& s) {
  const int n = s.segments_per_turn;
  const double r = 0.5 * s.core_diameter_m;
  const double h = s.tip_height_m();
  // Each ring vertex computed once, so neighbouring facets share it bit for bit.
  std::vector<Vec3> bottom(static_cast<std::size_t>(n)), top(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const double angle = two_pi * i / n;
    const double x = r * std::cos(angle), y = r * std::sin(angle);
    bottom[static_cast<std::size_t>(i)] = {x, y, h};
    top[static_cast<std::size_t>(i)] = {x, y, s.length_m};
  }
  const Vec3 apex{0.0, 0.0, 0.0};  // the cone's apex, or the flat bottom's centre (h = 0)
  const Vec3 top_centre{0.0, 0.0, s.length_m};
  ShellBuilder shell(false);
  for (std::size_t i = 0; i < bottom.size(); ++i) {
    const std::size_t j = (i + 1) % bottom.size();
    shell.triangle(apex, bottom[j], bottom[i]);             // normal down (and out, on a cone)
    shell.quad(bottom[i], bottom[j], top[j], top[i]);       // normal out
    shell.triangle(top_centre, top[i], top[j]);             // normal up
  }
  return std::move(shell).finish("auger core");
}

// Ring j of a blade: its cross-section corners (inner/outer, bottom/top).
struct Ring {
  Vec3 inner_bottom, outer_bottom, outer_top, inner_top;
};

TriangleMesh make_blade(const AugerSpec& s, int flute) {
  const double r_in = kBladeRootFraction * 0.5 * s.core_diameter_m;
  const double r_out = 0.5 * s.outer_diameter_m;
  const double z0 = blade_bottom_start_m(s);
  const double z1 = blade_bottom_end_m(s);
  const auto n = static_cast<std::int64_t>(blade_segments(s));
  const double start_angle = two_pi * flute / s.flutes;
  const double hand = s.hand == FluteHand::right ? 1.0 : -1.0;
  auto ring = [&](std::int64_t j) {
    // The helix: angle = start + hand * 2 pi (z - z0) / pitch. The last ring is pinned
    // to the ends exactly, so the blade's top reaches z = length without rounding.
    const double zb = j == n ? z1 : z0 + (z1 - z0) * static_cast<double>(j) / static_cast<double>(n);
    const double zt = j == n ? s.length_m : zb + s.flute_thickness_m;
    const double angle = start_angle + hand * two_pi * (zb - z0) / s.pitch_m;
    const double c = std::cos(angle), sn = std::sin(angle);
    return Ring{{r_in * c, r_in * sn, zb}, {r_out * c, r_out * sn, zb}, {r_out * c, r_out * sn, zt},
                {r_in * c, r_in * sn, zt}};
  };
  // The windings below are outward for a right-hand blade (angle rising with z); a
  // left-hand blade is its mirror image, which reverses orientation, so flip.
  ShellBuilder shell(s.hand == FluteHand::left);
  Ring a = ring(0);
  shell.quad(a.inner_bottom, a.outer_bottom, a.outer_top, a.inner_top);  // start face, normal -e_phi
  for (std::int64_t j = 0; j < n; ++j) {
    const Ring b = ring(j + 1);
    shell.quad(a.outer_bottom, b.outer_bottom, b.outer_top, a.outer_top);  // +e_r
    shell.quad(a.inner_bottom, a.inner_top, b.inner_top, b.inner_bottom);  // -e_r
    shell.quad(a.inner_bottom, b.inner_bottom, b.outer_bottom, a.outer_bottom);  // down
    shell.quad(a.inner_top, a.outer_top, b.outer_top, b.inner_top);        // up
    a = b;
  }
  shell.quad(a.inner_bottom, a.inner_top, a.outer_top, a.outer_bottom);  // end face, normal +e_phi
  return std::move(shell).finish(fmt::format("auger flute {}", flute));
}

}  // namespace

// ---------------------------------------------------------------------------------
double AugerSpec::tip_height_m() const {
  return tip == AugerTip::cone ? 0.5 * core_diameter_m / std::tan(0.5 * tip_angle_rad) : 0.0;
}

void AugerSpec::validate() const {
  check_length(outer_diameter_m, "outer_diameter_m");
  check_length(core_diameter_m, "core_diameter_m");
  check_length(pitch_m, "pitch_m");
  check_length(flute_thickness_m, "flute_thickness_m");
  check_length(length_m, "length_m");
  if (flutes < 1) throw InputError(fmt::format("auger: flutes must be at least 1, not {}", flutes));
  if (segments_per_turn < min_segments_per_turn || segments_per_turn > max_segments_per_turn)
    throw InputError(fmt::format("auger: segments_per_turn must be between {} and {}, not {}", min_segments_per_turn,
                                 max_segments_per_turn, segments_per_turn));
  if (core_diameter_m >= outer_diameter_m)
    throw InputError(fmt::format("auger: core_diameter_m ({} m) must be smaller than outer_diameter_m ({} m), or "
                                 "the flutes have no height",
                                 core_diameter_m, outer_diameter_m));
  const double spacing = pitch_m / flutes;
  if (flute_thickness_m >= spacing)
    throw InputError(fmt::format("auger: flute_thickness_m ({} m) must be less than pitch_m / flutes ({} m / {} = "
                                 "{} m), or neighbouring flute turns overlap with no gap between them",
                                 flute_thickness_m, pitch_m, flutes, spacing));
  if (tip == AugerTip::cone) {
    if (!std::isfinite(tip_angle_rad) || tip_angle_rad <= 0.0 || tip_angle_rad >= std::numbers::pi)
      throw InputError(fmt::format("auger: tip_angle_rad must be between 0 and pi (180 degrees), exclusive, not {}",
                                   tip_angle_rad));
  }
  const double tip_m = tip_height_m();
  if (!(length_m > tip_m + flute_thickness_m))
    throw InputError(fmt::format("auger: length_m ({} m) leaves no room for the flutes: it must exceed the tip "
                                 "height ({} m) plus flute_thickness_m ({} m)",
                                 length_m, tip_m, flute_thickness_m));
  const double triangles = 4.0 * segments_per_turn + flutes * (8.0 * blade_segments(*this) + 4.0);
  if (triangles > max_triangles)
    throw InputError(fmt::format("auger: the mesh would have {:.3g} triangles, more than {:.0e}; raise pitch_m or "
                                 "lower segments_per_turn",
                                 triangles, max_triangles));
}

AugerShells make_auger_shells(const AugerSpec& spec) {
  spec.validate();
  AugerShells shells;
  shells.core = make_core(spec);
  for (int k = 0; k < spec.flutes; ++k) shells.blades.push_back(make_blade(spec, k));
  return shells;
}

TriangleMesh make_auger(const AugerSpec& spec) {
  const AugerShells shells = make_auger_shells(spec);
  // The shells share no vertex (core at r_core and on the axis, blades at r_root and
  // r_outer), so one builder keeps them as separate components.
  TriangleMeshBuilder builder;
  auto append = [&builder](const TriangleMesh& shell) {
    for (std::size_t t = 0; t < shell.triangle_count(); ++t)
      builder.add_triangle(shell.corner(t, 0), shell.corner(t, 1), shell.corner(t, 2));
  };
  append(shells.core);
  for (const TriangleMesh& blade : shells.blades) append(blade);
  return std::move(builder).finish("auger");
}

}  // namespace regodem
