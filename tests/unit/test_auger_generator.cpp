// Parametric auger: every shell watertight and wound outwards; the core's volume equals
// the N-gon prism (+ pyramid) to 1e-12 and the circle's to the polygon error; each
// blade's volume equals its polygonal helical sweep to 1e-12 and the smooth sweep to
// its chord error; points on the axis, in a blade, outside the flutes and in the gap
// between turns classified by the winding number; the left hand is the mirror image;
// the drill sits in z in [0, length]; bad specs refused by name; STL round trip.
// Also the winding number and enclosed volume of a unit cube.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "geometry/auger_generator.hpp"
#include "geometry/mesh_inside.hpp"
#include "geometry/triangle_mesh.hpp"
#include "io/stl_reader.hpp"
#include "io/stl_writer.hpp"

namespace regodem {
namespace {

namespace fs = std::filesystem;
constexpr double pi = std::numbers::pi;

/// A two-flute drill of the paper's size class (20 mm over the flutes).
AugerSpec drill(AugerTip tip = AugerTip::cone, int flutes = 2, FluteHand hand = FluteHand::right) {
  AugerSpec s;
  s.outer_diameter_m = 0.020;
  s.core_diameter_m = 0.008;
  s.pitch_m = 0.012;
  s.flutes = flutes;
  s.flute_thickness_m = 0.002;
  s.length_m = 0.100;
  s.tip = tip;
  s.tip_angle_rad = 118.0 * pi / 180.0;
  s.segments_per_turn = 64;
  s.hand = hand;
  return s;
}

/// x rounded to float. Through a volatile: GCC 12.2's SLP vectorizer turns
/// {(float)p.x, (float)p.y} widened back to double into a plain copy (wrong code at -O2).
double float_rounded(double x) {
  volatile float f = static_cast<float>(x);
  return f;
}

Vec3 cylindrical(double r, double angle, double z) { return {r * std::cos(angle), r * std::sin(angle), z}; }

/// Every directed edge once and its reverse once: closed, 2-manifold at edges and
/// consistently wound. Returns the number of offending edges (0 when watertight).
std::size_t bad_edges(const TriangleMesh& mesh) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) ++directed[{t[static_cast<std::size_t>(k)], t[static_cast<std::size_t>((k + 1) % 3)]}];
  std::size_t bad = 0;
  for (const auto& [edge, count] : directed) {
    const auto reverse = directed.find({edge.second, edge.first});
    if (count != 1 || reverse == directed.end() || reverse->second != 1) ++bad;
  }
  return bad;
}

// ---------------------------------------------------------------------------------
TEST(Auger, EveryShellIsWatertightAndWoundOutwards) {
  for (AugerTip tip : {AugerTip::flat, AugerTip::cone})
    for (int flutes : {1, 2, 3})
      for (FluteHand hand : {FluteHand::right, FluteHand::left}) {
        SCOPED_TRACE(::testing::Message() << "tip " << static_cast<int>(tip) << ", flutes " << flutes << ", hand "
                                          << static_cast<int>(hand));
        const AugerSpec spec = drill(tip, flutes, hand);
        const AugerShells shells = make_auger_shells(spec);
        ASSERT_EQ(shells.blades.size(), static_cast<std::size_t>(flutes));
        std::size_t vertices = shells.core.vertices.size(), triangles = shells.core.triangle_count();
        EXPECT_EQ(bad_edges(shells.core), 0U);
        EXPECT_GT(enclosed_volume(shells.core), 0.0);
        EXPECT_EQ(shells.core.dropped_degenerate_triangles, 0U);
        for (const TriangleMesh& blade : shells.blades) {
          EXPECT_EQ(bad_edges(blade), 0U);
          EXPECT_GT(enclosed_volume(blade), 0.0);
          EXPECT_EQ(blade.dropped_degenerate_triangles, 0U);
          vertices += blade.vertices.size();
          triangles += blade.triangle_count();
        }
        // The union mesh holds the shells unchanged and sharing no vertex.
        const TriangleMesh all = make_auger(spec);
        EXPECT_EQ(all.vertices.size(), vertices);
        EXPECT_EQ(all.triangle_count(), triangles);
        EXPECT_EQ(bad_edges(all), 0U);
      }
}

TEST(Auger, CoreVolumeIsTheNgonPrismAndPyramidAndNearTheCylinderAndCone) {
  for (AugerTip tip : {AugerTip::flat, AugerTip::cone}) {
    const AugerSpec spec = drill(tip);
    const double r = 0.5 * spec.core_diameter_m;
    const double h = tip == AugerTip::cone ? r / std::tan(0.5 * spec.tip_angle_rad) : 0.0;
    EXPECT_DOUBLE_EQ(spec.tip_height_m(), h);
    const int n = spec.segments_per_turn;
    // Regular N-gon inscribed in radius r: area (N/2) sin(2 pi / N) r^2; prism above
    // the tip, pyramid (1/3 base x height) below it.
    const double polygon = 0.5 * n * std::sin(2.0 * pi / n) * r * r;
    const double exact_polygonal = polygon * (spec.length_m - h) + polygon * h / 3.0;
    const double volume = enclosed_volume(make_auger_shells(spec).core);
    EXPECT_NEAR(volume / exact_polygonal - 1.0, 0.0, 1e-12);
    // Against the smooth solid: the N-gon's area falls short of pi r^2 by the factor
    // sin(x)/x, x = 2 pi / N, so 0 < 1 - V/V_smooth <= x^2/6 (= 1.6e-3 at N = 64).
    const double smooth = pi * r * r * (spec.length_m - h) + pi * r * r * h / 3.0;
    const double x = 2.0 * pi / n;
    const double deficit = 1.0 - volume / smooth;
    EXPECT_GT(deficit, 0.0);
    EXPECT_LE(deficit, x * x / 6.0);
    RecordProperty(tip == AugerTip::cone ? "core_cone_relative_deficit" : "core_flat_relative_deficit",
                   std::to_string(deficit));
  }
}

TEST(Auger, BladeVolumeIsThePolygonalHelicalSweepAndNearTheSmoothOne) {
  for (AugerTip tip : {AugerTip::flat, AugerTip::cone}) {
    const AugerSpec spec = drill(tip, 3);
    const AugerShells shells = make_auger_shells(spec);
    const double r_in = kBladeRootFraction * 0.5 * spec.core_diameter_m;
    const double r_out = 0.5 * spec.outer_diameter_m;
    const double t = spec.flute_thickness_m;
    const double z0 = spec.tip_height_m();                // the blade's bottom runs from here
    const double z1 = spec.length_m - t;                  // to here
    const double turns = (z1 - z0) / spec.pitch_m;
    for (const TriangleMesh& blade : shells.blades) {
      // n segments of 8 triangles (4 twisted quads) plus two end faces of 2.
      ASSERT_EQ((blade.triangle_count() - 4) % 8, 0U);
      const double n = static_cast<double>((blade.triangle_count() - 4) / 8);
      EXPECT_EQ(n, std::ceil(turns * spec.segments_per_turn));
      // Each segment turns by a = 2 pi turns / n. Its inner and outer faces are
      // vertical, and its top face is its bottom face raised by t, so by the divergence
      // theorem with F = (0, 0, z) its volume is t x the xy-projection of its bottom
      // face, the annular sector polygon (1/2)(r_out^2 - r_in^2) sin(a): exact for the
      // mesh whatever diagonal splits the twisted quads.
      const double a = 2.0 * pi * turns / n;
      const double polygonal = n * t * 0.5 * (r_out * r_out - r_in * r_in) * std::sin(a);
      const double volume = enclosed_volume(blade);
      EXPECT_NEAR(volume / polygonal - 1.0, 0.0, 1e-12);
      // The smooth helical sweep of the rectangle keeps its volume (each angular slice
      // is the cross-section shifted in z): annulus area x t x turns. The polygon
      // falls short by sin(a)/a: 0 < deficit <= a^2/6.
      const double smooth = pi * (r_out * r_out - r_in * r_in) * t * turns;
      const double deficit = 1.0 - volume / smooth;
      EXPECT_GT(deficit, 0.0);
      EXPECT_LE(deficit, a * a / 6.0);
      RecordProperty("blade_relative_deficit", std::to_string(deficit));
    }
  }
}

TEST(Auger, PointsOnTheAxisInABladeOutsideAndInTheFluteGapAreClassified) {
  const AugerSpec spec = drill(AugerTip::cone, 2);
  const TriangleMesh auger = make_auger(spec);
  const double rc = 0.5 * spec.core_diameter_m, ro = 0.5 * spec.outer_diameter_m;
  const double h = spec.tip_height_m(), p = spec.pitch_m, t = spec.flute_thickness_m, L = spec.length_m;
  // On the axis, from just above the apex to just below the top: inside the core.
  for (double z : {0.001 * h, 0.5 * h, h, 0.25 * L, 0.5 * L, 0.999 * L})
    EXPECT_NEAR(winding_number(auger, {0, 0, z}), 1.0, 1e-9) << "z " << z;
  EXPECT_NEAR(winding_number(auger, {0, 0, -0.001}), 0.0, 1e-9);
  EXPECT_NEAR(winding_number(auger, {0, 0, L + 0.001}), 0.0, 1e-9);
  // The cone: half way up it, its radius is rc / 2.
  EXPECT_TRUE(point_inside(auger, cylindrical(0.4 * rc, 0.1, 0.5 * h)));
  EXPECT_FALSE(point_inside(auger, cylindrical(0.6 * rc, 0.1, 0.5 * h)));
  // Beyond the outer radius, all around and all along: outside.
  for (double angle = 0.0; angle < 2.0 * pi; angle += 0.37)
    for (double z = 0.0; z <= L; z += 0.0071)
      EXPECT_LT(winding_number(auger, cylindrical(1.05 * ro, angle, z)), 1e-6) << angle << " " << z;
  // At angle phi, flute 0's bottom face is at h + p phi / (2 pi) (+ turns of p), and
  // flute 1's half a pitch higher; between them lies the gap, from +t to +p/2.
  const double phi = 0.3;
  const double r_mid = 0.5 * (rc + ro);
  for (int turn : {0, 2, 5}) {
    const double bottom = h + p * phi / (2.0 * pi) + turn * p;
    EXPECT_NEAR(winding_number(auger, cylindrical(r_mid, phi, bottom + 0.5 * t)), 1.0, 1e-9) << "in flute 0";
    EXPECT_NEAR(winding_number(auger, cylindrical(r_mid, phi, bottom + 0.5 * p + 0.5 * t)), 1.0, 1e-9)
        << "in flute 1";
    const Vec3 gap = cylindrical(r_mid, phi, bottom + t + 0.5 * (0.5 * p - t));
    EXPECT_NEAR(winding_number(auger, gap), 0.0, 1e-9) << "flute gap";
    EXPECT_FALSE(point_inside(auger, gap));
    // In the gap but inside the core: the core alone.
    EXPECT_NEAR(winding_number(auger, cylindrical(0.5 * rc, phi, gap.z)), 1.0, 1e-9);
    // The blade's root, inside the core too: both shells count (the union overlaps).
    EXPECT_NEAR(winding_number(auger, cylindrical(0.975 * rc, phi, bottom + 0.5 * t)), 2.0, 1e-9);
  }
}

TEST(Auger, LeftHandIsTheMirrorImageOfTheRightHand) {
  const TriangleMesh right = make_auger(drill(AugerTip::cone, 1, FluteHand::right));
  const TriangleMesh left = make_auger(drill(AugerTip::cone, 1, FluteHand::left));
  ASSERT_EQ(left.triangle_count(), right.triangle_count());
  EXPECT_NEAR(enclosed_volume(left) / enclosed_volume(right), 1.0, 1e-12);
  // y -> -y maps the left blade (angle falling with z) onto the right one; a mirror
  // reverses orientation, so the left triangles are the mirrored right ones reversed.
  // The core is mirror-symmetric but not generated reversed: compare blades only.
  const AugerShells r = make_auger_shells(drill(AugerTip::cone, 1, FluteHand::right));
  const AugerShells l = make_auger_shells(drill(AugerTip::cone, 1, FluteHand::left));
  const TriangleMesh& rb = r.blades[0];
  const TriangleMesh& lb = l.blades[0];
  ASSERT_EQ(lb.triangle_count(), rb.triangle_count());
  double worst = 0.0;
  for (std::size_t t = 0; t < rb.triangle_count(); ++t)
    for (auto [kl, kr] : {std::pair{0, 0}, std::pair{1, 2}, std::pair{2, 1}}) {
      const Vec3 a = lb.corner(t, kl), b = rb.corner(t, kr);
      worst = std::max(worst, norm(a - Vec3{b.x, -b.y, b.z}));
    }
  EXPECT_LT(worst, 1e-15);
  // A point in the right-hand blade, mirrored, is in the left-hand blade.
  const AugerSpec spec = drill(AugerTip::cone, 1);
  const Vec3 in = cylindrical(0.007, 0.3, spec.tip_height_m() + spec.pitch_m * 0.3 / (2 * pi) + spec.pitch_m +
                                              0.5 * spec.flute_thickness_m);
  EXPECT_NEAR(winding_number(rb, in), 1.0, 1e-9);
  EXPECT_NEAR(winding_number(lb, in), 0.0, 1e-9);
  EXPECT_NEAR(winding_number(lb, {in.x, -in.y, in.z}), 1.0, 1e-9);
}

TEST(Auger, SitsInItsOwnFrameTipAtOriginTopAtLength) {
  for (AugerTip tip : {AugerTip::flat, AugerTip::cone}) {
    const AugerSpec spec = drill(tip, 2);
    const TriangleMesh auger = make_auger(spec);
    const Aabb box = auger.bounding_box();
    EXPECT_EQ(box.lo_m.z, 0.0);
    EXPECT_EQ(box.hi_m.z, spec.length_m);
    const double ro = 0.5 * spec.outer_diameter_m;
    for (const Vec3& v : auger.vertices) EXPECT_LE(std::hypot(v.x, v.y), ro * (1.0 + 1e-15));
    EXPECT_GT(box.hi_m.x, ro * (1.0 - 2e-3));  // the flutes reach the outer radius (to the chord sag)
    if (tip == AugerTip::cone) {
      // The apex: the one vertex at z = 0, on the axis.
      std::size_t at_zero = 0;
      for (const Vec3& v : auger.vertices)
        if (v.z == 0.0) {
          ++at_zero;
          EXPECT_EQ(v, (Vec3{0, 0, 0}));
        }
      EXPECT_EQ(at_zero, 1U);
    }
  }
}

TEST(Auger, BadSpecsAreRefusedWithMessagesNamingTheParameter) {
  const std::vector<std::pair<std::function<void(AugerSpec&)>, std::vector<std::string>>> cases = {
      {[](AugerSpec& s) { s.core_diameter_m = s.outer_diameter_m; },
       {"core_diameter_m", "smaller than outer_diameter_m"}},
      {[](AugerSpec& s) { s.core_diameter_m = 0.03; }, {"core_diameter_m (0.03 m)", "outer_diameter_m (0.02 m)"}},
      {[](AugerSpec& s) { s.flute_thickness_m = 0.006; }, {"flute_thickness_m (0.006 m)", "pitch_m / flutes", "overlap"}},
      {[](AugerSpec& s) { s.flutes = 6; }, {"flute_thickness_m", "0.012 m / 6 = "}},
      {[](AugerSpec& s) { s.outer_diameter_m = -0.02; }, {"outer_diameter_m must be positive", "-0.02"}},
      {[](AugerSpec& s) { s.core_diameter_m = 0.0; }, {"core_diameter_m must be positive"}},
      {[](AugerSpec& s) { s.flute_thickness_m = 0.0; }, {"flute_thickness_m must be positive"}},
      {[](AugerSpec& s) { s.pitch_m = std::numeric_limits<double>::quiet_NaN(); },
       {"pitch_m must be a finite number", "nan"}},
      {[](AugerSpec& s) { s.length_m = std::numeric_limits<double>::infinity(); },
       {"length_m must be a finite number", "inf"}},
      {[](AugerSpec& s) { s.flutes = 0; }, {"flutes must be at least 1, not 0"}},
      {[](AugerSpec& s) { s.segments_per_turn = 8; }, {"segments_per_turn must be between 16 and 4096, not 8"}},
      {[](AugerSpec& s) { s.tip_angle_rad = 0.0; }, {"tip_angle_rad", "between 0 and pi"}},
      {[](AugerSpec& s) { s.tip_angle_rad = pi; }, {"tip_angle_rad", "between 0 and pi"}},
      {[](AugerSpec& s) { s.tip_angle_rad = std::numeric_limits<double>::quiet_NaN(); }, {"tip_angle_rad"}},
      {[](AugerSpec& s) { s.length_m = 0.004; }, {"length_m (0.004 m)", "no room for the flutes", "tip height"}},
      {[](AugerSpec& s) {
         s.pitch_m = 4e-6;
         s.flute_thickness_m = 1e-6;
       },
       {"triangles", "raise pitch_m"}},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    AugerSpec spec = drill();
    cases[i].first(spec);
    try {
      (void)make_auger(spec);
      ADD_FAILURE() << "case " << i << ": no InputError";
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind("auger: ", 0), 0U) << message;
      for (const std::string& part : cases[i].second)
        EXPECT_NE(message.find(part), std::string::npos) << "case " << i << ": '" << part << "' not in: " << message;
    }
  }
  // A flat tip ignores the tip angle.
  AugerSpec flat = drill(AugerTip::flat);
  flat.tip_angle_rad = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NO_THROW(flat.validate());
}

TEST(Auger, WrittenToStlReadsBackTheSameMesh) {
  std::string pattern = (fs::temp_directory_path() / "regodem-auger-XXXXXX").string();
  ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
  const fs::path dir = pattern;
  const TriangleMesh auger = make_auger(drill(AugerTip::cone, 2));
  write_stl(dir / "auger.stl", auger);
  write_stl(dir / "auger_ascii.stl", auger, StlFormat::ascii, "auger");
  const TriangleMesh binary = read_stl((dir / "auger.stl").string());
  const TriangleMesh ascii = read_stl((dir / "auger_ascii.stl").string());
  EXPECT_EQ(ascii.vertices, auger.vertices);
  EXPECT_EQ(ascii.triangles, auger.triangles);
  // Float rounding (1e-9 m at these sizes) neither merges vertices nor flattens facets.
  EXPECT_EQ(binary.triangles, auger.triangles);
  ASSERT_EQ(binary.vertices.size(), auger.vertices.size());
  for (std::size_t i = 0; i < auger.vertices.size(); ++i) {
    const Vec3& v = auger.vertices[i];
    EXPECT_EQ(binary.vertices[i], (Vec3{float_rounded(v.x), float_rounded(v.y), float_rounded(v.z)})) << i;
  }
  EXPECT_NEAR(enclosed_volume(binary) / enclosed_volume(auger), 1.0, 1e-6);
  fs::remove_all(dir);
}

// ---------------------------------------------------------------------------------
TriangleMesh unit_cube(const Vec3& offset = {}, bool inward = false) {
  const std::array<Vec3, 8> v = {Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{1, 1, 0}, Vec3{0, 1, 0},
                                 Vec3{0, 0, 1}, Vec3{1, 0, 1}, Vec3{1, 1, 1}, Vec3{0, 1, 1}};
  const std::array<std::array<int, 4>, 6> quads = {
      {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 4, 7, 3}, {1, 2, 6, 5}}};
  TriangleMeshBuilder builder;
  for (const auto& q : quads) {
    const Vec3 a = v[q[0]] + offset, b = v[q[1]] + offset, c = v[q[2]] + offset, d = v[q[3]] + offset;
    if (inward) {
      builder.add_triangle(a, c, b);
      builder.add_triangle(a, d, c);
    } else {
      builder.add_triangle(a, b, c);
      builder.add_triangle(a, c, d);
    }
  }
  return std::move(builder).finish("cube");
}

TEST(WindingNumber, UnitCubeIsOneInsideAndZeroOutside) {
  const TriangleMesh cube = unit_cube();
  for (const Vec3& p : {Vec3{0.5, 0.5, 0.5}, Vec3{0.01, 0.02, 0.99}, Vec3{0.999, 0.5, 0.001}}) {
    EXPECT_NEAR(winding_number(cube, p), 1.0, 1e-12);
    EXPECT_TRUE(point_inside(cube, p));
  }
  for (const Vec3& p : {Vec3{1.5, 0.5, 0.5}, Vec3{-0.01, 0.5, 0.5}, Vec3{0.5, 0.5, 1.001}, Vec3{10, -7, 3},
                        Vec3{2, 2, 2}}) {
    EXPECT_NEAR(winding_number(cube, p), 0.0, 1e-12);
    EXPECT_FALSE(point_inside(cube, p));
  }
  // A hair's breadth either side of a face (on it, the value depends on rounding).
  EXPECT_NEAR(winding_number(cube, {0.5, 0.3, 1e-9}), 1.0, 1e-12);
  EXPECT_NEAR(winding_number(cube, {0.5, 0.3, -1e-9}), 0.0, 1e-12);
  // Wound inwards, the inside counts -1: not inside.
  const TriangleMesh inward = unit_cube({}, true);
  EXPECT_NEAR(winding_number(inward, {0.5, 0.5, 0.5}), -1.0, 1e-12);
  EXPECT_FALSE(point_inside(inward, {0.5, 0.5, 0.5}));
}

TEST(WindingNumber, EnclosedVolumeOfAUnitCubeFarFromTheOriginIsOne) {
  EXPECT_NEAR(enclosed_volume(unit_cube()), 1.0, 1e-15);
  EXPECT_NEAR(enclosed_volume(unit_cube({}, true)), -1.0, 1e-15);
  // Tetrahedra from the first vertex, not the origin: no cancellation far away.
  EXPECT_NEAR(enclosed_volume(unit_cube({1e6, -2e6, 3e6})), 1.0, 1e-9);
  EXPECT_EQ(enclosed_volume(TriangleMesh{}), 0.0);
}

}  // namespace
}  // namespace regodem
