// How well the step resolves a moving wall's impacts (scenario/wall_speed_check.hpp): the
// fastest point's speed of a fed plane and of a fed, turning auger, the Hertz contact of
// the smallest grain struck at that speed, and the warning below 10 steps.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "scenario/scenario_builder.hpp"
#include "scenario/scenario_reader.hpp"
#include "scenario/wall_speed_check.hpp"
#include "shipped_scenario_text.hpp"
#include "sim/simulation.hpp"

namespace regodem {
namespace {

Material grain() {
  Material m;
  m.name = "grain";
  m.density_kg_per_m3 = 3000.0;
  m.shear_modulus_Pa = 1e6;
  m.poisson_ratio = 0.3;
  return m;
}

Material steel() {
  Material m;
  m.name = "steel";
  m.density_kg_per_m3 = 7800.0;
  m.shear_modulus_Pa = 79e9;
  m.poisson_ratio = 0.3;
  return m;
}

/// Johnson's impact in its other form, t_c = 2.9432 delta_max / v with delta_max =
/// (15 m v^2 / (16 E* sqrt(R)))^(2/5), written from the material constants here.
double hertz_time_from_overlap_s(double radius_m, double speed_m_per_s) {
  const Material g = grain(), s = steel();
  const double e_star =
      1.0 / ((1.0 - g.poisson_ratio * g.poisson_ratio) / (2.0 * g.shear_modulus_Pa * (1.0 + g.poisson_ratio)) +
             (1.0 - s.poisson_ratio * s.poisson_ratio) / (2.0 * s.shear_modulus_Pa * (1.0 + s.poisson_ratio)));
  const double mass = 4.0 / 3.0 * std::numbers::pi * std::pow(radius_m, 3) * g.density_kg_per_m3;
  const double delta_max =
      std::pow(15.0 * mass * speed_m_per_s * speed_m_per_s / (16.0 * e_star * std::sqrt(radius_m)), 0.4);
  return 2.9432 * delta_max / speed_m_per_s;
}

struct PlaneCase {
  MaterialTable materials;
  WallSet walls;
  std::vector<double> smallest_radius_m;
};

/// A steel plane fed at 2 m/s onto grains of which the smallest has radius 0.5 mm; a
/// resting steel plane beside it.
PlaneCase fed_plane() {
  PlaneCase c;
  const MaterialIndex g = c.materials.add(grain());
  const MaterialIndex s = c.materials.add(steel());
  WallMotion fed;
  fed.velocity_m_per_s = {0.0, 0.0, -2.0};
  c.walls.add_plane(c.walls.add_body("piston", fed), {0, 0, 0.01}, {0, 0, -1}, s);
  c.walls.add_plane(c.walls.add_body("floor", WallMotion{}), {0, 0, 0}, {0, 0, 1}, s);
  c.smallest_radius_m = {0.5e-3, std::numeric_limits<double>::infinity()};
  (void)g;
  return c;
}

// The contact time to 1e-3 (2.87 against 2.9432 (15/16)^0.4 = 2.8682, the same law
// rounded); the steps are the contact time over the step; a resting wall has no line.
TEST(WallSpeedCheck, AFedPlaneStrikesAtItsFeedSpeed) {
  PlaneCase c = fed_plane();
  const double expected_s = hertz_time_from_overlap_s(0.5e-3, 2.0);
  const double dt = expected_s / 12.0;
  const WallSpeedReport report = wall_speed_report(c.walls, c.materials, c.smallest_radius_m, dt, 0.2);
  ASSERT_EQ(report.impacts.size(), 1u);
  EXPECT_EQ(report.impacts[0].body, 0u);
  EXPECT_DOUBLE_EQ(report.impacts[0].fastest_speed_m_per_s, 2.0);
  EXPECT_NEAR(report.impacts[0].contact_time_s, expected_s, 1e-3 * expected_s);
  EXPECT_NEAR(report.impacts[0].steps, 12.0, 12e-3);
  EXPECT_EQ(report.lines.size(), 1u);
  EXPECT_TRUE(report.warnings.empty());  // 12 steps: resolved
}

TEST(WallSpeedCheck, FewerThanTenStepsWarnAndNameTheStepThatWouldDo) {
  PlaneCase c = fed_plane();
  const double contact_s = hertz_time_from_overlap_s(0.5e-3, 2.0);
  const WallSpeedReport report = wall_speed_report(c.walls, c.materials, c.smallest_radius_m, contact_s / 8.0, 0.2);
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("wall 'piston'"), std::string::npos) << report.warnings[0];
  EXPECT_NE(report.warnings[0].find("8.0 steps"), std::string::npos) << report.warnings[0];
  EXPECT_NE(report.warnings[0].find("rayleigh_fraction 0.16"), std::string::npos) << report.warnings[0];  // 0.2 x 8/10
}

// The tiny drilling file's auger, 4 mm across, fed at 40 mm/s and turned at 16000 rpm:
// its fastest point moves 0.04 + 2 mm x 1675.5 rad/s = 3.391 m/s (to 1e-6: the
// generated mesh's outermost vertices lie on the outer radius); its line is among
// validate's, and its warning (under 10 steps) among the run's warnings.
TEST(WallSpeedCheck, ATurningAugerStrikesAtItsEdgeSpeed) {
  const fs::path csv = fs::temp_directory_path() / ("regodem-wall-speed-" + std::to_string(::getpid()) + ".csv");
  const PreparedRun run =
      PreparedRun::build(read_scenario_string(tiny_drill_text([](std::string t) { return t; }, csv), "drill.yaml"), 1);
  fs::remove(csv);
  WallSet walls = run.simulation().walls;  // a copy: the reach is cached on first use
  const double reach = 2e-3, omega = 16000.0 * 2.0 * std::numbers::pi / 60.0;
  const std::uint32_t drill = walls.meshes.at(0).body;
  EXPECT_NEAR(walls.fastest_surface_speed_m_per_s(drill), 0.04 + reach * omega, 1e-6 * 3.391);
  bool line = false;
  for (const std::string& l : run.describe())
    line = line || l.rfind("wall '" + walls.bodies[drill].name + "': its fastest point moves", 0) == 0;
  EXPECT_TRUE(line);
  // Its 1 mm grains at 3.391 m/s: 9.2 steps at the file's 0.2 of the Rayleigh time.
  ASSERT_EQ(run.warnings().size(), 1u);
  EXPECT_NE(run.warnings()[0].find("wall 'drill' strikes grains faster than the step resolves"), std::string::npos)
      << run.warnings()[0];
}

}  // namespace
}  // namespace regodem
