// The scenario reader: a valid file maps onto ScenarioSpec in SI units; every kind of
// bad input is reported with the file, the line of the offending key and its dotted
// path; --set overrides edit the tree before it is checked.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "geometry/wall_primitive.hpp"
#include "scenario/scenario_builder.hpp"
#include "scenario/scenario_reader.hpp"
#include "sim/simulation.hpp"
#include "sim/stage_plan.hpp"

namespace regodem {
namespace {

constexpr const char* kFile = "test.yaml";

// A small valid scenario, one key per line so that a test can change one line and
// expect the error on exactly that line.
const std::string kValid = R"(name: reader-test
seed: 7
gravity: [0, 0, -9.81 m/s^2]
domain:
  min: [-10 mm, -10 mm, 0]
  max: [10 mm, 10 mm, 40 mm]
time_step: auto
materials:
  regolith:
    density: 3000 kg/m^3
    shear_modulus: 3e7 Pa
    poisson_ratio: 0.25
  steel:
    density: 7800
    shear_modulus: 79 GPa
    poisson_ratio: 0.3
interactions:
  - materials: [regolith, regolith]
    restitution: 0.24
    sliding_friction: 0.8
    rolling_friction: 0.6
walls:
  - name: barrel
    type: cylinder
    material: steel
    base: [0, 0, 0]
    axis: [0, 0, 1]
    radius: 10 mm
    length: 40 mm
    ends: {bottom: capped}
  - name: lid
    type: disk
    center: [0, 0, 40 mm]
    normal: [0, 0, -1]
    diameter: 20 mm
insertions:
  - name: fine
    material: regolith
    region:
      type: cylinder
      base: [0, 0, 5 mm]
      radius: 5 mm
      length: 20 mm
    diameter: 0.6 mm
    count: 200
    stage: fill
  - name: coarse
    material: regolith
    region:
      type: annulus
      base: [0, 0, 5 mm]
      inner_radius: 5 mm
      radius: 9.5 mm
      length: 20 mm
    sizes:
      - {diameter: 2.4 mm, fraction: 0.75}
      - {radius: 1 mm, fraction: 0.25}
    fractions_by: mass
    solid_fraction: 0.2
    rate: 1000 /s
    interval: 10 ms
stages:
  - name: fill
    duration: 0.1 s
    overrides:
      - {sliding_friction: 0, rolling_friction: 0}
  - name: settle
    until: settled
    kinetic_energy_per_particle: 1e-12 J
    min_duration: 0.01 s
    max_duration: 2 s
output:
  interval: 0.01 s
)";

/// `text` with the one occurrence of `from` replaced by `to`.
std::string with(const std::string& text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "test setup: '" << from << "' is not in the text";
  EXPECT_EQ(text.find(from, at + 1), std::string::npos) << "test setup: '" << from << "' is ambiguous";
  if (at == std::string::npos) return text;
  return text.substr(0, at) + to + text.substr(at + from.size());
}

/// 1-based line of the first occurrence of `needle`.
int line_of(const std::string& text, const std::string& needle) {
  const std::size_t at = text.find(needle);
  EXPECT_NE(at, std::string::npos) << "test setup: '" << needle << "' is not in the text";
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
}

/// The InputError message, or "" when the text reads without error.
std::string error_of(const std::string& text, const std::vector<std::string>& overrides = {}) {
  try {
    read_scenario_string(text, kFile, overrides);
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

std::vector<std::string> lines_of(const std::string& message) {
  std::vector<std::string> lines;
  std::istringstream in(message);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

/// Expects a problem reported as "test.yaml:<line of line_marker>:<col>: <key>: ...<fragment>...".
void expect_problem(const std::string& text, const std::string& line_marker,
                    const std::string& key, const std::string& fragment) {
  const std::string message = error_of(text);
  ASSERT_FALSE(message.empty()) << "expected an error about " << key;
  const std::string prefix = std::string(kFile) + ":" + std::to_string(line_of(text, line_marker)) + ":";
  for (const std::string& line : lines_of(message)) {
    if (line.starts_with(prefix) && line.find(": " + key + ": ") != std::string::npos &&
        line.find(fragment) != std::string::npos) {
      return;
    }
  }
  ADD_FAILURE() << "no line starting '" << prefix << "' naming '" << key << "' and saying '"
                << fragment << "' in:\n"
                << message;
}

// ------------------------------------------------------------------------- valid input

TEST(ScenarioReader, ValidScenarioMapsToSiUnits) {
  const ScenarioSpec spec = read_scenario_string(kValid, kFile);
  EXPECT_EQ(spec.name, "reader-test");
  EXPECT_EQ(spec.file, kFile);
  EXPECT_EQ(spec.seed, 7u);
  EXPECT_DOUBLE_EQ(spec.gravity_m_per_s2.z, -9.81);
  EXPECT_DOUBLE_EQ(spec.domain.min_m.x, -0.01);
  EXPECT_DOUBLE_EQ(spec.domain.max_m.z, 0.04);
  EXPECT_EQ(spec.time_step_s, 0.0);  // auto
  EXPECT_DOUBLE_EQ(spec.rayleigh_fraction, 0.2);

  ASSERT_EQ(spec.materials.size(), 2u);
  EXPECT_EQ(spec.materials[0].name, "regolith");
  EXPECT_DOUBLE_EQ(spec.materials[0].density_kg_per_m3, 3000.0);
  EXPECT_DOUBLE_EQ(spec.materials[1].shear_modulus_Pa, 79e9);
  EXPECT_EQ(spec.materials[1].where.line, line_of(kValid, "  steel:"));
  EXPECT_EQ(spec.materials[1].where.key, "materials.steel");

  ASSERT_EQ(spec.interactions.size(), 1u);
  EXPECT_DOUBLE_EQ(spec.interactions[0].restitution, 0.24);
  EXPECT_DOUBLE_EQ(spec.interactions[0].rolling_friction, 0.6);
  EXPECT_FALSE(spec.interactions[0].clamp_attractive_normal_force);

  ASSERT_EQ(spec.walls.size(), 2u);
  const WallSpec& barrel = spec.walls[0];
  EXPECT_EQ(barrel.shape, WallShape::cylinder);
  EXPECT_EQ(barrel.material, "steel");
  EXPECT_DOUBLE_EQ(barrel.radius_m, 0.01);
  EXPECT_DOUBLE_EQ(barrel.length_m, 0.04);
  EXPECT_EQ(barrel.side, CylinderSide::inside);
  EXPECT_TRUE(barrel.cap_bottom);
  EXPECT_FALSE(barrel.cap_top);
  EXPECT_EQ(barrel.where.key, "walls.barrel");
  const WallSpec& lid = spec.walls[1];
  EXPECT_EQ(lid.shape, WallShape::disk);
  EXPECT_EQ(lid.material, "");  // default: the first material, chosen by the builder
  EXPECT_DOUBLE_EQ(lid.radius_m, 0.01);
  EXPECT_DOUBLE_EQ(lid.normal.z, -1.0);

  ASSERT_EQ(spec.insertions.size(), 2u);
  const InsertionSpec& fine = spec.insertions[0];
  EXPECT_EQ(fine.region_tag, "fine");  // default: the insertion's name
  EXPECT_EQ(fine.region.shape, RegionShape::cylinder);
  EXPECT_DOUBLE_EQ(fine.region.axis.z, 1.0);  // default axis
  ASSERT_EQ(fine.sizes.size(), 1u);
  EXPECT_DOUBLE_EQ(fine.sizes[0].radius_m, 0.3e-3);
  EXPECT_EQ(fine.amount_kind, InsertAmount::count);
  EXPECT_DOUBLE_EQ(fine.amount, 200.0);
  EXPECT_EQ(fine.stage, "fill");
  const InsertionSpec& coarse = spec.insertions[1];
  EXPECT_EQ(coarse.region.shape, RegionShape::annulus);
  EXPECT_DOUBLE_EQ(coarse.region.inner_radius_m, 0.005);
  ASSERT_EQ(coarse.sizes.size(), 2u);
  EXPECT_DOUBLE_EQ(coarse.sizes[0].radius_m, 1.2e-3);
  EXPECT_DOUBLE_EQ(coarse.sizes[1].radius_m, 1e-3);
  EXPECT_DOUBLE_EQ(coarse.sizes[0].fraction, 0.75);
  EXPECT_TRUE(coarse.fractions_by_mass);
  EXPECT_EQ(coarse.amount_kind, InsertAmount::solid_fraction);
  EXPECT_DOUBLE_EQ(coarse.rate_per_s, 1000.0);
  EXPECT_DOUBLE_EQ(coarse.interval_s, 0.01);
  EXPECT_EQ(coarse.stage, "");  // default: the first stage

  ASSERT_EQ(spec.stages.size(), 2u);
  EXPECT_EQ(spec.stages[0].end, StageEnd::time);
  EXPECT_DOUBLE_EQ(spec.stages[0].duration_s, 0.1);
  ASSERT_EQ(spec.stages[0].overrides.size(), 1u);
  EXPECT_EQ(spec.stages[0].overrides[0].sliding_friction, 0.0);
  EXPECT_FALSE(spec.stages[0].overrides[0].restitution.has_value());
  EXPECT_TRUE(spec.stages[0].overrides[0].material_a.empty());
  EXPECT_EQ(spec.stages[1].end, StageEnd::settled);
  EXPECT_DOUBLE_EQ(spec.stages[1].settled_kinetic_energy_J, 1e-12);
  EXPECT_DOUBLE_EQ(spec.stages[1].max_duration_s, 2.0);
  EXPECT_DOUBLE_EQ(spec.output.interval_s, 0.01);
  EXPECT_DOUBLE_EQ(spec.output.progress_interval_s, 2.0);
  EXPECT_EQ(spec.content_hash.size(), 16u);
}

TEST(ScenarioReader, DemoScenarioReads) {
  const ScenarioSpec spec =
      read_scenario_file(std::string(REGODEM_SOURCE_DIR) + "/scenarios/demo.yaml");
  EXPECT_EQ(spec.name, "demo");
  ASSERT_EQ(spec.insertions.size(), 2u);
  EXPECT_DOUBLE_EQ(spec.insertions[0].sizes.at(0).radius_m, 0.3e-3);
  EXPECT_DOUBLE_EQ(spec.insertions[1].sizes.at(0).radius_m, 1.2e-3);
  EXPECT_EQ(spec.insertions[1].region.shape, RegionShape::annulus);
  ASSERT_EQ(spec.stages.size(), 3u);
  EXPECT_EQ(spec.stages[1].end, StageEnd::settled);
  EXPECT_EQ(spec.stages[2].heat_stepping, ThermalStepping::static_crank_nicolson);
  EXPECT_TRUE(spec.heat.enabled);
  EXPECT_DOUBLE_EQ(spec.insertions[0].temperature->value_K, 77.15);
}

TEST(ScenarioReader, FixtureDirectoryHasAValidMinimalScenario) {
  const ScenarioSpec spec = read_scenario_file(std::string(REGODEM_SOURCE_DIR) +
                                               "/tests/data/scenarios/minimal.yaml");
  EXPECT_EQ(spec.name, "minimal");  // no `name` key: the file's stem
  EXPECT_EQ(spec.stages.size(), 1u);
}

TEST(ScenarioReader, YoungsModulusIsConvertedToShearModulus) {
  const std::string text =
      with(kValid, "    shear_modulus: 3e7 Pa\n", "    youngs_modulus: 7.5e7 Pa\n");
  const ScenarioSpec spec = read_scenario_string(text, kFile);
  EXPECT_DOUBLE_EQ(spec.materials[0].shear_modulus_Pa, 7.5e7 / (2.0 * 1.25));  // G = E/(2(1+nu))
}

TEST(ScenarioReader, AxesAreNormalised) {
  const std::string text = with(kValid, "    axis: [0, 0, 1]\n    radius: 10 mm", "    axis: [0, 0, 2.5]\n    radius: 10 mm");
  EXPECT_DOUBLE_EQ(read_scenario_string(text, kFile).walls[0].normal.z, 1.0);
}

TEST(ScenarioReader, ExplicitTimeStepAndSkin) {
  std::string text = with(kValid, "time_step: auto", "time_step: 1e-7 s\nneighbor_skin: 0.05 mm");
  const ScenarioSpec spec = read_scenario_string(text, kFile);
  EXPECT_DOUBLE_EQ(spec.time_step_s, 1e-7);
  EXPECT_DOUBLE_EQ(spec.neighbor_skin_m, 0.05e-3);
}

// --------------------------------------------------------------------------- motion

TEST(ScenarioReader, RpmAboutTheWallsOwnAxis) {
  const std::string text = with(kValid, "    ends: {bottom: capped}",
                                "    ends: {bottom: capped}\n    motion: {angular_velocity: 200 rpm}");
  const WallSpec wall = read_scenario_string(text, kFile).walls[0];
  EXPECT_NEAR(wall.motion.angular_velocity_rad_per_s.z, 200.0 * 2.0 * std::numbers::pi / 60.0, 1e-12);
  EXPECT_DOUBLE_EQ(wall.motion.angular_velocity_rad_per_s.x, 0.0);
}

TEST(ScenarioReader, RpmWithAnExplicitAxisAndVectorForm) {
  std::string text = with(kValid, "    ends: {bottom: capped}",
                          "    ends: {bottom: capped}\n"
                          "    motion: {angular_velocity: 60 rpm, axis: [0, 0, -1], velocity: [0, 0, -0.5 mm/s], stop: 10 s}");
  WallSpec wall = read_scenario_string(text, kFile).walls[0];
  EXPECT_NEAR(wall.motion.angular_velocity_rad_per_s.z, -2.0 * std::numbers::pi, 1e-12);
  EXPECT_DOUBLE_EQ(wall.motion.velocity_m_per_s.z, -0.5e-3);
  EXPECT_DOUBLE_EQ(wall.motion.stop_s, 10.0);

  text = with(kValid, "    ends: {bottom: capped}",
              "    ends: {bottom: capped}\n    motion: {angular_velocity: [0, 0, 3]}");
  wall = read_scenario_string(text, kFile).walls[0];
  EXPECT_DOUBLE_EQ(wall.motion.angular_velocity_rad_per_s.z, 3.0);
}

TEST(ScenarioReader, AnalyticWallTurnsOnlyAboutItsAxis) {
  const std::string text = with(kValid, "    ends: {bottom: capped}",
                                "    ends: {bottom: capped}\n    motion: {angular_velocity: [1, 0, 0]}");
  expect_problem(text, "angular_velocity: [1, 0, 0]", "walls.barrel.motion.angular_velocity",
                 "only about its own axis");
}

TEST(ScenarioReader, StopMustFollowStart) {
  const std::string text = with(kValid, "    ends: {bottom: capped}",
                                "    ends: {bottom: capped}\n    motion: {velocity: [0, 0, 1 mm/s], start: 2 s, stop: 1 s}");
  expect_problem(text, "start: 2 s", "walls.barrel.motion.stop", "later than 'start'");
}

// ------------------------------------------------------------------- keys and values

TEST(ScenarioReader, UnknownKeySuggestsTheClosest) {
  const std::string text = with(kValid, "    density: 3000 kg/m^3", "    densty: 3000 kg/m^3");
  expect_problem(text, "densty", "materials.regolith.densty", "unknown key (did you mean 'density'?)");
  // The key is located at its own column.
  EXPECT_NE(error_of(text).find(std::string(kFile) + ":" + std::to_string(line_of(text, "densty")) + ":5:"),
            std::string::npos);
}

TEST(ScenarioReader, UnknownTopLevelKey) {
  expect_problem(with(kValid, "seed: 7", "sead: 7"), "sead", "sead", "did you mean 'seed'?");
}

TEST(ScenarioReader, KeyOfAnotherWallShapeIsExplained) {
  const std::string text = with(kValid, "    axis: [0, 0, 1]\n    radius: 10 mm", "    normal: [0, 0, 1]\n    radius: 10 mm");
  expect_problem(text, "normal: [0, 0, 1]", "walls.barrel.normal", "a cylinder takes 'axis'");
}

TEST(ScenarioReader, UnknownChoiceSuggestsTheClosest) {
  expect_problem(with(kValid, "    type: cylinder\n    material: steel", "    type: cylindr\n    material: steel"),
                 "cylindr", "walls.barrel.type", "did you mean 'cylinder'?");
  expect_problem(with(kValid, "until: settled", "until: setled"), "setled", "stages.settle.until",
                 "did you mean 'settled'?");
}

TEST(ScenarioReader, WrongUnit) {
  const std::string text = with(kValid, "    radius: 10 mm", "    radius: 0.6 kg");
  expect_problem(text, "0.6 kg", "walls.barrel.radius", "expected a length");
}

TEST(ScenarioReader, NotANumber) {
  expect_problem(with(kValid, "density: 3000 kg/m^3", "density: heavy"), "heavy",
                 "materials.regolith.density", "not a number");
}

TEST(ScenarioReader, VectorNeedsThreeComponents) {
  expect_problem(with(kValid, "gravity: [0, 0, -9.81 m/s^2]", "gravity: [0, -9.81]"), "gravity",
                 "gravity", "three components");
  expect_problem(with(kValid, "gravity: [0, 0, -9.81 m/s^2]", "gravity: [0, 0, -9.81 m/s]"),
                 "gravity", "gravity[2]", "expected an acceleration");
}

TEST(ScenarioReader, NegativeOrZeroRadius) {
  expect_problem(with(kValid, "    diameter: 0.6 mm", "    diameter: -0.6 mm"), "-0.6 mm",
                 "insertions.fine.diameter", "must be greater than 0");
  expect_problem(with(kValid, "    radius: 10 mm", "    radius: 0"), "radius: 0",
                 "walls.barrel.radius", "must be greater than 0");
}

TEST(ScenarioReader, NegativeDensityAndModulus) {
  expect_problem(with(kValid, "density: 3000 kg/m^3", "density: -3000 kg/m^3"), "-3000",
                 "materials.regolith.density", "must be greater than 0");
  expect_problem(with(kValid, "shear_modulus: 79 GPa", "shear_modulus: -79 GPa"), "-79 GPa",
                 "materials.steel.shear_modulus", "must be greater than 0");
}

TEST(ScenarioReader, PoissonRatioOutsideItsRange) {
  expect_problem(with(kValid, "poisson_ratio: 0.25", "poisson_ratio: 0.5"), "poisson_ratio: 0.5",
                 "materials.regolith.poisson_ratio", "between -1 and 0.5");
  expect_problem(with(kValid, "poisson_ratio: 0.25", "poisson_ratio: -1"), "poisson_ratio: -1",
                 "materials.regolith.poisson_ratio", "between -1 and 0.5");
}

TEST(ScenarioReader, RestitutionOutsideItsRange) {
  expect_problem(with(kValid, "restitution: 0.24", "restitution: 0"), "restitution: 0",
                 "interactions[0].restitution", "greater than 0 and at most 1");
  expect_problem(with(kValid, "restitution: 0.24", "restitution: 1.2"), "restitution: 1.2",
                 "interactions[0].restitution", "greater than 0 and at most 1");
  EXPECT_EQ(error_of(with(kValid, "restitution: 0.24", "restitution: 1")), "");  // elastic is fine
}

TEST(ScenarioReader, NegativeFriction) {
  expect_problem(with(kValid, "sliding_friction: 0.8", "sliding_friction: -0.1"), "-0.1",
                 "interactions[0].sliding_friction", "be 0 or more");
  expect_problem(with(kValid, "rolling_friction: 0.6", "rolling_friction: -0.6"), "-0.6",
                 "interactions[0].rolling_friction", "be 0 or more");
  expect_problem(with(kValid, "{sliding_friction: 0, rolling_friction: 0}", "{sliding_friction: -1}"),
                 "sliding_friction: -1", "stages.fill.overrides[0].sliding_friction", "be 0 or more");
}

TEST(ScenarioReader, UndefinedMaterialInEverySection) {
  expect_problem(with(kValid, "    material: steel", "    material: steal"), "steal",
                 "walls.barrel.material", "material 'steal' is not defined (did you mean 'steel'?)");
  expect_problem(with(kValid, "    material: regolith\n    region:\n      type: cylinder",
                      "    material: basalt\n    region:\n      type: cylinder"),
                 "basalt", "insertions.fine.material", "material 'basalt' is not defined (defined: regolith, steel)");
  expect_problem(with(kValid, "[regolith, regolith]", "[regolith, rock]"), "rock",
                 "interactions[0].materials[1]", "material 'rock' is not defined");
  expect_problem(with(kValid, "{sliding_friction: 0, rolling_friction: 0}",
                      "{materials: [regolith, ice], sliding_friction: 0}"),
                 "ice", "stages.fill.overrides[0].materials[1]", "material 'ice' is not defined");
}

TEST(ScenarioReader, RegionOutsideTheDomain) {
  // Box: x reaches 12 mm in a domain that ends at 10 mm.
  expect_problem(with(kValid, "      type: cylinder\n      base: [0, 0, 5 mm]\n      radius: 5 mm\n      length: 20 mm",
                      "      type: box\n      min: [-5 mm, -5 mm, 5 mm]\n      max: [12 mm, 5 mm, 20 mm]"),
                 "region:\n      type: box", "insertions.fine.region", "outside the domain: x from -0.005 to 0.012 m");
  // Cylinder: 5 mm + 20 mm... along z reaches 45 mm.
  expect_problem(with(kValid, "      length: 20 mm\n    diameter", "      length: 40 mm\n    diameter"),
                 "region:\n      type: cylinder", "insertions.fine.region", "z from 0.005 to 0.045 m");
  // Annulus: its outer radius reaches past the domain's side.
  expect_problem(with(kValid, "      radius: 9.5 mm", "      radius: 11 mm"), "region:\n      type: annulus",
                 "insertions.coarse.region", "outside the domain");
}

TEST(ScenarioReader, WallOutsideTheDomain) {
  expect_problem(with(kValid, "    radius: 10 mm", "    radius: 11 mm"), "- name: barrel", "walls.barrel",
                 "the wall reaches outside the domain");
  expect_problem(with(kValid, "    center: [0, 0, 40 mm]", "    center: [0, 0, 41 mm]"), "- name: lid",
                 "walls.lid", "the wall reaches outside the domain");
}

TEST(ScenarioReader, LostParticlesPolicy) {
  EXPECT_FALSE(read_scenario_string(kValid, kFile).domain.remove_lost_particles);  // default: stop
  const std::string remove =
      with(kValid, "  max: [10 mm, 10 mm, 40 mm]", "  max: [10 mm, 10 mm, 40 mm]\n  lost_particles: remove");
  EXPECT_TRUE(read_scenario_string(remove, kFile).domain.remove_lost_particles);
  expect_problem(with(kValid, "  max: [10 mm, 10 mm, 40 mm]", "  max: [10 mm, 10 mm, 40 mm]\n  lost_particles: delete"),
                 "  lost_particles", "domain.lost_particles", "'delete' is not one of stop or remove");
}

TEST(ScenarioReader, DomainMinMustBeBelowMax) {
  expect_problem(with(kValid, "  max: [10 mm, 10 mm, 40 mm]", "  max: [10 mm, -10 mm, 40 mm]"),
                 "  max: [10 mm, -10 mm", "domain.max", "above 'min' along every axis (y");
}

TEST(ScenarioReader, MissingRequiredSections) {
  const std::string no_materials =
      with(kValid, "materials:\n  regolith:", "stuff:\n  regolith:");
  EXPECT_NE(error_of(no_materials).find("test.yaml: missing required key 'materials'"), std::string::npos)
      << error_of(no_materials);
  const std::string no_domain = with(kValid, "domain:\n", "bounds:\n");
  EXPECT_NE(error_of(no_domain).find("test.yaml: missing required key 'domain'"), std::string::npos);
  const std::string no_stages = kValid.substr(0, kValid.find("stages:")) + "output:\n  interval: 0.01 s\n";
  EXPECT_NE(error_of(no_stages).find("test.yaml: missing required key 'stages'"), std::string::npos);
  const std::string empty_stages = kValid.substr(0, kValid.find("stages:")) + "stages: []\n";
  expect_problem(empty_stages, "stages: []", "stages", "define at least one stage");
  EXPECT_NE(error_of("").find("test.yaml: the scenario is empty"), std::string::npos);
}

TEST(ScenarioReader, MissingRequiredKeyInAnItem) {
  expect_problem(with(kValid, "    shear_modulus: 79 GPa\n", ""), "  steel:", "materials.steel",
                 "missing 'shear_modulus' or 'youngs_modulus'");
  expect_problem(with(kValid, "    length: 40 mm\n", ""), "- name: barrel", "walls.barrel",
                 "missing required key 'length'");
}

TEST(ScenarioReader, SizeFractionsMustBePositiveAndAddUp) {
  expect_problem(with(kValid, "fraction: 0.25}", "fraction: -0.25}"), "-0.25",
                 "insertions.coarse.sizes[1].fraction", "must be greater than 0");
  expect_problem(with(kValid, "fraction: 0.25}", "fraction: 0.5}"), "sizes:", "insertions.coarse.sizes",
                 "the fractions add up to 1.25");
}

TEST(ScenarioReader, DuplicateNames) {
  expect_problem(with(kValid, "  - name: lid", "  - name: barrel"), "- name: barrel\n    type: disk", "walls.barrel",
                 "duplicate wall name 'barrel' (first used at line 23)");
  expect_problem(with(kValid, "  - name: settle", "  - name: fill"), "- name: fill\n    until", "stages.fill",
                 "duplicate stage name 'fill'");
  expect_problem(with(kValid, "  - name: coarse", "  - name: fine"), "- name: fine\n    material: regolith\n    region:\n      type: annulus", "insertions.fine",
                 "duplicate insertion name 'fine'");
  expect_problem(with(kValid, "  steel:", "  regolith:"), "  regolith:\n    density: 7800", "materials.regolith",
                 "duplicate key 'regolith'");
  const std::string twice = with(kValid, "walls:\n",
                                 "  - materials: [regolith, regolith]\n    restitution: 0.5\n"
                                 "    sliding_friction: 0.5\nwalls:\n");
  expect_problem(twice, "  - materials: [regolith, regolith]\n    restitution: 0.5", "interactions[1]", "the pair [regolith, regolith] is already given");
}

TEST(ScenarioReader, AnnulusInnerRadiusBelowOuter) {
  expect_problem(with(kValid, "      inner_radius: 5 mm", "      inner_radius: 9.5 mm"), "inner_radius: 9.5",
                 "insertions.coarse.region.inner_radius", "must be smaller than the outer radius");
}

TEST(ScenarioReader, InsertionNamesAStageThatDoesNotExist) {
  expect_problem(with(kValid, "    stage: fill", "    stage: fil"), "stage: fil", "insertions.fine.stage",
                 "stage 'fil' is not defined (did you mean 'fill'?)");
}

TEST(ScenarioReader, StageNeedsAnEnd) {
  expect_problem(with(kValid, "    duration: 0.1 s\n", ""), "- name: fill", "stages.fill",
                 "missing 'duration' or 'until'");
  expect_problem(with(kValid, "    duration: 0.1 s\n", "    duration: 0.1 s\n    until: settled\n"),
                 "- name: fill", "stages.fill", "give only one of 'duration' or 'until'");
  expect_problem(with(kValid, "    duration: 0.1 s\n", "    duration: 0.1 s\n    max_duration: 1 s\n"),
                 "max_duration: 1 s", "stages.fill.max_duration", "only with 'until: settled'");
  expect_problem(with(kValid, "    kinetic_energy_per_particle: 1e-12 J\n", ""), "- name: settle",
                 "stages.settle", "missing required key 'kinetic_energy_per_particle'");
}

TEST(ScenarioReader, ZeroLengthDirection) {
  expect_problem(with(kValid, "    normal: [0, 0, -1]", "    normal: [0, 0, 0]"), "normal: [0, 0, 0]",
                 "walls.lid.normal", "must not be [0, 0, 0]");
  expect_problem(with(kValid, "      base: [0, 0, 5 mm]\n      radius: 5 mm",
                      "      base: [0, 0, 5 mm]\n      axis: [0, 0, 0]\n      radius: 5 mm"),
                 "axis: [0, 0, 0]", "insertions.fine.region.axis", "must not be [0, 0, 0]");
}

TEST(ScenarioReader, NegativeIntervalsAndTimeStep) {
  expect_problem(with(kValid, "time_step: auto", "time_step: -1e-7 s"), "time_step", "time_step",
                 "must be greater than 0 (or auto)");
  expect_problem(with(kValid, "    interval: 10 ms", "    interval: -10 ms"), "-10 ms",
                 "insertions.coarse.interval", "must be greater than 0");
  expect_problem(with(kValid, "  interval: 0.01 s\n", "  interval: -0.01 s\n"), "-0.01 s", "output.interval",
                 "must be greater than 0");
}

TEST(ScenarioReader, AmountsOfParticles) {
  expect_problem(with(kValid, "    count: 200", "    count: 200\n    mass: 1 g"), "- name: fine",
                 "insertions.fine", "give only one of 'count' or 'mass'");
  expect_problem(with(kValid, "    count: 200", "    count: 12.5"), "12.5", "insertions.fine.count",
                 "whole number");
  expect_problem(with(kValid, "    count: 200", "    count: 0"), "count: 0", "insertions.fine.count",
                 "at least 1");
  expect_problem(with(kValid, "solid_fraction: 0.2", "solid_fraction: 0.8"), "solid_fraction: 0.8",
                 "insertions.coarse.solid_fraction", "at most 0.74");
}

TEST(ScenarioReader, ParticlesMustFitTheirRegion) {
  expect_problem(with(kValid, "    diameter: 0.6 mm", "    diameter: 12 mm"), "region:\n      type: cylinder",
                 "insertions.fine.region", "do not fit");
}

TEST(ScenarioReader, RayleighFractionAboveTheLimit) {
  expect_problem(with(kValid, "time_step: auto", "time_step: auto\nrayleigh_fraction: 0.7"),
                 "rayleigh_fraction", "rayleigh_fraction", "at most max_rayleigh_fraction (0.5)");
}

TEST(ScenarioReader, YamlSyntaxErrorNamesTheLine) {
  const std::string text = with(kValid, "  max: [10 mm, 10 mm, 40 mm]", "  max: [10 mm, 10 mm, 40 mm");
  const std::string message = error_of(text);
  EXPECT_TRUE(message.starts_with("test.yaml:")) << message;
  EXPECT_NE(message.find("YAML syntax error"), std::string::npos) << message;
  // yaml-cpp notices the open list where the next key starts, a line or so later.
  const int reported = std::stoi(message.substr(std::string("test.yaml:").size()));
  EXPECT_GE(reported, line_of(text, "  max: [10 mm"));
  EXPECT_LE(reported, line_of(text, "  max: [10 mm") + 2);
}

TEST(ScenarioReader, AllProblemsAreReportedInFileOrder) {
  std::string text = with(kValid, "    restitution: 0.24", "    restitution: 2");
  text = with(text, "    density: 3000 kg/m^3", "    densty: 3000 kg/m^3");
  text = with(text, "  - name: lid\n    type: disk", "  - name: lid\n    type: dsk");
  const std::vector<std::string> lines = lines_of(error_of(text));
  ASSERT_EQ(lines.size(), 3u) << error_of(text);
  EXPECT_NE(lines[0].find("materials.regolith.densty: unknown key"), std::string::npos) << lines[0];
  EXPECT_NE(lines[1].find("interactions[0].restitution"), std::string::npos) << lines[1];
  EXPECT_NE(lines[2].find("walls.lid.type"), std::string::npos) << lines[2];
}

TEST(ScenarioReader, MisspeltRequiredKeyIsOneProblemNotTwo) {
  // "densty" is reported with its suggestion; "missing 'density'" would say the same again.
  const std::string message = error_of(with(kValid, "    density: 3000 kg/m^3", "    densty: 3000 kg/m^3"));
  EXPECT_EQ(lines_of(message).size(), 1u) << message;
  // A misspelt key that suggests nothing leaves the required key reported as missing.
  const std::string unrelated = error_of(with(kValid, "    density: 3000 kg/m^3", "    heft: 3000 kg/m^3"));
  EXPECT_NE(unrelated.find("materials.regolith: missing required key 'density'"), std::string::npos)
      << unrelated;
}

// ------------------------------------------------------------------------ files

class TemporaryDirectory {
 public:
  TemporaryDirectory() {
    path_ = std::filesystem::temp_directory_path() /
            ("regodem-reader-test-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
             "-" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(path_);
  }
  ~TemporaryDirectory() { std::filesystem::remove_all(path_); }
  TemporaryDirectory(const TemporaryDirectory&) = delete;
  TemporaryDirectory& operator=(const TemporaryDirectory&) = delete;
  const std::filesystem::path& path() const { return path_; }
  void write(const std::string& name, const std::string& text) const {
    std::ofstream(path_ / name) << text;
  }

 private:
  std::filesystem::path path_;
};

TEST(ScenarioReader, MissingFile) {
  try {
    read_scenario_file("/nonexistent/scenario.yaml");
    FAIL() << "no error for a missing file";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()), "/nonexistent/scenario.yaml: no such scenario file");
  }
}

TEST(ScenarioReader, ParticlesFromACsvFileNextToTheScenario) {
  const TemporaryDirectory directory;
  directory.write("packing.csv", "x,y,z,radius\n0,0,0.001,0.0003\n");
  const std::string from_file = with(kValid,
                                     "    region:\n      type: cylinder\n      base: [0, 0, 5 mm]\n"
                                     "      radius: 5 mm\n      length: 20 mm\n    diameter: 0.6 mm\n    count: 200\n",
                                     "    file: packing.csv\n");
  directory.write("scenario.yaml", from_file);
  const ScenarioSpec spec = read_scenario_file((directory.path() / "scenario.yaml").string());
  EXPECT_EQ(std::filesystem::path(spec.insertions[0].from_file), directory.path() / "packing.csv");

  // A file insertion takes its sizes from the file: a radius key is refused with a reason.
  directory.write("sized.yaml", with(from_file, "    file: packing.csv\n", "    file: packing.csv\n    radius: 1 mm\n"));
  try {
    read_scenario_file((directory.path() / "sized.yaml").string());
    FAIL() << "radius next to file accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("insertions.fine.radius: unknown key (not used with 'file'"),
              std::string::npos)
        << error.what();
  }

  directory.write("missing.yaml", with(from_file, "packing.csv", "nowhere.csv"));
  try {
    read_scenario_file((directory.path() / "missing.yaml").string());
    FAIL() << "missing CSV accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("insertions.fine.file: no such file"), std::string::npos)
        << error.what();
  }
}

// Fixtures that the command-line tests use too: each names its line and key.
struct BadFixture {
  const char* file;
  int line;
  const char* key;
  const char* fragment;
};

class BadScenarioFixture : public ::testing::TestWithParam<BadFixture> {};

TEST_P(BadScenarioFixture, IsRefusedWithItsLineAndKey) {
  const BadFixture& fixture = GetParam();
  const std::string path = std::string(REGODEM_SOURCE_DIR) + "/tests/data/scenarios/" + fixture.file;
  try {
    read_scenario_file(path);
    FAIL() << fixture.file << " was accepted";
  } catch (const InputError& error) {
    const std::string message = error.what();
    // Each fixture has exactly one problem.
    ASSERT_EQ(lines_of(message).size(), 1u) << message;
    const std::string prefix = path + ":" + std::to_string(fixture.line) + ":";
    EXPECT_TRUE(message.starts_with(prefix)) << message;
    EXPECT_NE(message.find(std::string(": ") + fixture.key + ": "), std::string::npos) << message;
    EXPECT_NE(message.find(fixture.fragment), std::string::npos) << message;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Fixtures, BadScenarioFixture,
    ::testing::Values(
        BadFixture{"unknown_key.yaml", 7, "materials.grain.densty", "did you mean 'density'?"},
        BadFixture{"wrong_unit.yaml", 23, "insertions.grains.radius", "expected a length"},
        BadFixture{"negative_radius.yaml", 23, "insertions.grains.radius", "must be greater than 0"},
        BadFixture{"missing_material.yaml", 17, "walls.floor.material", "material 'steel' is not defined"},
        BadFixture{"region_outside_domain.yaml", 22, "insertions.grains.region", "outside the domain"},
        BadFixture{"negative_conductivity.yaml", 11, "materials.grain.conductivity", "must be greater than 0"},
        BadFixture{"lumped_wall_without_mass.yaml", 23, "walls.floor.thermal",
                   "missing 'mass' or 'areal_density'"},
        BadFixture{"time_table_not_increasing.yaml", 25, "walls.floor.thermal.temperature.time[2]",
                   "the times of a table must increase from row to row: '10 s' follows '20 s'"}),
    [](const ::testing::TestParamInfo<BadFixture>& param_info) {
      std::string name = param_info.param.file;
      return name.substr(0, name.find('.'));
    });

TEST(ScenarioReader, SyntaxErrorFixture) {
  const std::string path = std::string(REGODEM_SOURCE_DIR) + "/tests/data/scenarios/syntax_error.yaml";
  EXPECT_THROW(
      {
        try {
          read_scenario_file(path);
        } catch (const InputError& error) {
          EXPECT_TRUE(std::string(error.what()).starts_with(path + ":")) << error.what();
          EXPECT_NE(std::string(error.what()).find("YAML syntax error"), std::string::npos);
          throw;
        }
      },
      InputError);
}

// -------------------------------------------------------------------- --set overrides

TEST(ScenarioReaderOverrides, ByMapKeyListIndexAndItemName) {
  const ScenarioSpec spec = read_scenario_string(
      kValid, kFile,
      {"materials.regolith.density=2500", "stages.settle.max_duration=0.5s", "walls.0.radius=9 mm",
       "walls[1].diameter=10 mm", "gravity=[0, 0, -1.62]"});
  EXPECT_DOUBLE_EQ(spec.materials[0].density_kg_per_m3, 2500.0);
  EXPECT_DOUBLE_EQ(spec.stages[1].max_duration_s, 0.5);
  EXPECT_DOUBLE_EQ(spec.walls[0].radius_m, 0.009);
  EXPECT_DOUBLE_EQ(spec.walls[1].radius_m, 0.005);
  EXPECT_DOUBLE_EQ(spec.gravity_m_per_s2.z, -1.62);
}

TEST(ScenarioReaderOverrides, CanAddAKey) {
  const ScenarioSpec spec = read_scenario_string(kValid, kFile, {"neighbor_skin=0.1 mm", "walls.barrel.contact=both"});
  EXPECT_DOUBLE_EQ(spec.neighbor_skin_m, 1e-4);
  EXPECT_EQ(spec.walls[0].side, CylinderSide::both);
}

TEST(ScenarioReaderOverrides, ReplacingASizeKeyStillChecksExclusiveness) {
  // The file gives `diameter`; adding `radius` makes two sizes, which is refused.
  const std::string message = error_of(kValid, {"insertions.fine.radius=0.2 mm"});
  EXPECT_NE(message.find("give only one of 'radius' or 'diameter'"), std::string::npos) << message;
}

TEST(ScenarioReaderOverrides, UnknownPathIsRefused) {
  std::string message = error_of(kValid, {"materials.basalt.density=2500"});
  EXPECT_EQ(message, "--set materials.basalt.density=2500: no key 'basalt' in 'materials'");
  message = error_of(kValid, {"walls.drum.radius=1 mm"});
  EXPECT_EQ(message, "--set walls.drum.radius=1 mm: no item 'drum' in 'walls' (its items: barrel, lid)");
  message = error_of(kValid, {"walls.5.radius=1 mm"});
  EXPECT_NE(message.find("no item '5'"), std::string::npos) << message;
  message = error_of(kValid, {"seed.value=3"});
  EXPECT_NE(message.find("'seed' is a single value"), std::string::npos) << message;
  message = error_of(kValid, {"seed"});
  EXPECT_NE(message.find("expected key.path=value"), std::string::npos) << message;
  message = error_of(kValid, {"materials.regolith.densty=3"});
  EXPECT_EQ(message, "--set materials.regolith.densty=3: materials.regolith.densty: unknown key "
                     "(did you mean 'density'?)");
}

TEST(ScenarioReaderOverrides, BadValueNamesTheOverride) {
  const std::string message = error_of(kValid, {"materials.regolith.density=-5"});
  EXPECT_EQ(message, "--set materials.regolith.density=-5: materials.regolith.density: must be "
                     "greater than 0, got '-5'");
}

TEST(ScenarioReaderOverrides, ChangeTheContentHash) {
  const std::string plain = read_scenario_string(kValid, kFile).content_hash;
  EXPECT_EQ(plain, read_scenario_string(kValid, "elsewhere.yaml").content_hash);  // bytes, not the name
  EXPECT_NE(plain, read_scenario_string(kValid, kFile, {"seed=8"}).content_hash);
  EXPECT_NE(plain, read_scenario_string(with(kValid, "seed: 7", "seed: 8"), kFile).content_hash);
  EXPECT_NE(read_scenario_string(kValid, kFile, {"seed=8", "seed=7"}).content_hash,
            read_scenario_string(kValid, kFile, {"seed=7", "seed=8"}).content_hash);
}

// ----------------------------------------------------------------------------- heat

// The paper's thermal pieces in one file (DESIGN.md sections 2 and 3), one key per line.
const std::string kHeat = R"(name: heat-test
domain:
  min: [-20 mm, -20 mm, 0]
  max: [20 mm, 20 mm, 150 mm]
materials:
  regolith:
    density: 3000 kg/m^3
    shear_modulus: 3e7 Pa
    poisson_ratio: 0.25
    conductivity: 14.76 W/(m K)
    specific_heat: {temperature: [100 K, 200 K, 77 degC], value: [300, 600 J/(kg K), 0.9 kJ/(kg K)]}
    real_shear_modulus: 3 GPa
  steel:
    density: 7800
    shear_modulus: 79 GPa
    poisson_ratio: 0.3
    conductivity: 50 W/(m K)
interactions:
  - materials: [regolith, regolith]
    restitution: 0.24
    sliding_friction: 0.8
    conduction: radius
  - materials: [regolith, steel]
    restitution: 0.3
    sliding_friction: 0.5
    conduction: area
    heat_transfer_coefficient: 5e4 W/(m^2 K)
walls:
  - name: barrel
    type: cylinder
    base: [0, 0, 0]
    radius: 15 mm
    length: 150 mm
    ends: {bottom: capped}
  - name: plate
    type: plane
    material: steel
    point: [0, 0, 0]
    normal: [0, 0, 1]
    thermal:
      mode: fixed
      temperature: {time: [0 s, 10 s, 1 min], value: [-196 degC, 700 degC, 700 degC]}
      conductivity_mix: harmonic_mean
  - name: sieve
    type: sieve
    segments: 10
    base: [0, 0, 10 mm]
    radius: 11 mm
    length: 12 mm
    ends: {bottom: capped}
    thermal:
      mode: lumped
      temperature: -196 degC
      conductivity: 100 W/(m K)
      specific_heat: 500 J/(kg K)
      areal_density: 2 kg/m^2
insertions:
  - name: fine
    material: regolith
    region: {type: cylinder, base: [0, 0, 12 mm], radius: 8 mm, length: 20 mm}
    diameter: 2 mm
    count: 20
    temperature: -196 degC
  - name: coarse
    material: regolith
    region: {type: annulus, base: [0, 0, 12 mm], inner_radius: 12 mm, radius: 14.5 mm, length: 20 mm}
    diameter: 2 mm
    count: 20
    temperature: {value: 100 K, gradient: [0, 0, 1000 K/m], reference_point: [0, 0, 10 mm]}
stages:
  - name: fill
    duration: 0.01 s
  - name: heat
    duration: 10 s
    heat_stepping: static_backward_euler
    thermal_time_step: 0.1 s
heat:
  time_scale_factor: 100
  friction_heating: true
  friction_partition: 0.7
)";

TEST(ScenarioReaderHeat, ThermalKeysMapToSiUnits) {
  const ScenarioSpec spec = read_scenario_string(kHeat, kFile);
  const MaterialSpec& regolith = spec.materials[0];
  ASSERT_TRUE(regolith.conductivity_W_per_mK.has_value());
  EXPECT_TRUE(regolith.conductivity_W_per_mK->temperature_K.empty());
  EXPECT_DOUBLE_EQ(regolith.conductivity_W_per_mK->constant, 14.76);
  ASSERT_TRUE(regolith.specific_heat_J_per_kgK.has_value());
  const TemperatureCurveSpec& c = *regolith.specific_heat_J_per_kgK;
  ASSERT_EQ(c.temperature_K.size(), 3u);
  EXPECT_DOUBLE_EQ(c.temperature_K[0], 100.0);
  EXPECT_DOUBLE_EQ(c.temperature_K[2], 350.15);  // 77 degC
  ASSERT_EQ(c.value.size(), 3u);
  EXPECT_DOUBLE_EQ(c.value[0], 300.0);
  EXPECT_DOUBLE_EQ(c.value[2], 900.0);  // 0.9 kJ/(kg K)
  EXPECT_DOUBLE_EQ(regolith.real_shear_modulus_Pa, 3e9);
  EXPECT_DOUBLE_EQ(spec.materials[1].conductivity_W_per_mK->constant, 50.0);
  EXPECT_FALSE(spec.materials[1].specific_heat_J_per_kgK.has_value());  // a wall's material needs none
  EXPECT_DOUBLE_EQ(spec.materials[1].real_shear_modulus_Pa, 0.0);

  EXPECT_EQ(spec.interactions[0].conduction, ConductionLawSpec::radius);
  EXPECT_EQ(spec.interactions[1].conduction, ConductionLawSpec::area);
  EXPECT_DOUBLE_EQ(spec.interactions[1].heat_transfer_coefficient_W_per_m2K, 5e4);

  EXPECT_EQ(spec.walls[0].thermal.mode, WallThermalModeSpec::adiabatic);  // no thermal block
  const WallThermalSpec& plate = spec.walls[1].thermal;
  EXPECT_EQ(plate.mode, WallThermalModeSpec::fixed);
  ASSERT_EQ(plate.time_s.size(), 3u);
  EXPECT_DOUBLE_EQ(plate.time_s[2], 60.0);
  EXPECT_DOUBLE_EQ(plate.temperature_K[0], 77.15);
  EXPECT_DOUBLE_EQ(plate.temperature_K[1], 973.15);
  EXPECT_TRUE(plate.harmonic_mean);
  EXPECT_FALSE(plate.conductivity_W_per_mK.has_value());
  const WallSpec& sieve = spec.walls[2];
  EXPECT_EQ(sieve.shape, WallShape::sieve);
  EXPECT_EQ(sieve.segments, 10);
  EXPECT_DOUBLE_EQ(sieve.radius_m, 0.011);
  EXPECT_DOUBLE_EQ(sieve.length_m, 0.012);
  EXPECT_DOUBLE_EQ(sieve.point_m.z, 0.01);
  EXPECT_DOUBLE_EQ(sieve.normal.z, 1.0);  // default axis
  EXPECT_TRUE(sieve.cap_bottom);
  EXPECT_EQ(sieve.side, CylinderSide::both);
  EXPECT_EQ(sieve.thermal.mode, WallThermalModeSpec::lumped);
  EXPECT_DOUBLE_EQ(sieve.thermal.temperature_K.at(0), 77.15);
  EXPECT_DOUBLE_EQ(*sieve.thermal.conductivity_W_per_mK, 100.0);
  EXPECT_DOUBLE_EQ(sieve.thermal.specific_heat_J_per_kgK, 500.0);
  EXPECT_DOUBLE_EQ(sieve.thermal.areal_density_kg_per_m2, 2.0);
  EXPECT_DOUBLE_EQ(sieve.thermal.mass_kg, 0.0);
  EXPECT_FALSE(sieve.thermal.harmonic_mean);

  ASSERT_TRUE(spec.insertions[0].temperature.has_value());
  EXPECT_DOUBLE_EQ(spec.insertions[0].temperature->value_K, 77.15);
  EXPECT_DOUBLE_EQ(spec.insertions[0].temperature->gradient_K_per_m.z, 0.0);
  const InitialTemperatureSpec& field = *spec.insertions[1].temperature;
  EXPECT_DOUBLE_EQ(field.value_K, 100.0);
  EXPECT_DOUBLE_EQ(field.gradient_K_per_m.z, 1000.0);
  EXPECT_DOUBLE_EQ(field.reference_point_m.z, 0.01);

  EXPECT_EQ(spec.stages[0].heat_stepping, ThermalStepping::coupled);
  EXPECT_EQ(spec.stages[1].heat_stepping, ThermalStepping::static_backward_euler);
  EXPECT_DOUBLE_EQ(spec.stages[1].thermal_time_step_s, 0.1);
  EXPECT_DOUBLE_EQ(spec.stages[1].stability_fraction, 0.5);  // default

  EXPECT_TRUE(spec.heat.enabled);
  EXPECT_DOUBLE_EQ(spec.heat.time_scale_factor, 100.0);
  EXPECT_TRUE(spec.heat.friction_heating);
  EXPECT_DOUBLE_EQ(spec.heat.friction_partition, 0.7);
}

TEST(ScenarioReaderHeat, DefaultsWithoutAndWithAnEmptyHeatSection) {
  const ScenarioSpec plain = read_scenario_string(kValid, kFile);
  EXPECT_FALSE(plain.heat.enabled);
  EXPECT_EQ(plain.interactions[0].conduction, ConductionLawSpec::force);
  EXPECT_FALSE(plain.materials[0].conductivity_W_per_mK.has_value());
  EXPECT_FALSE(plain.insertions[0].temperature.has_value());

  const std::string text = with(with(kHeat, "heat:\n  time_scale_factor: 100\n  friction_heating: true\n"
                                            "  friction_partition: 0.7\n", "heat: {}\n"),
                                "    conduction: radius\n", "");
  const ScenarioSpec spec = read_scenario_string(text, kFile);
  EXPECT_TRUE(spec.heat.enabled);
  EXPECT_DOUBLE_EQ(spec.heat.time_scale_factor, 1.0);
  EXPECT_FALSE(spec.heat.friction_heating);
  EXPECT_DOUBLE_EQ(spec.heat.friction_partition, 0.5);
  EXPECT_EQ(spec.interactions[0].conduction, ConductionLawSpec::force);
}

TEST(ScenarioReaderHeat, LumpedWallByMassAndStaticExplicitByFraction) {
  std::string text = with(kHeat, "      areal_density: 2 kg/m^2", "      mass: 3 g");
  text = with(text, "    heat_stepping: static_backward_euler\n    thermal_time_step: 0.1 s",
              "    heat_stepping: static_explicit\n    stability_fraction: 0.25");
  const ScenarioSpec spec = read_scenario_string(text, kFile);
  EXPECT_DOUBLE_EQ(spec.walls[2].thermal.mass_kg, 0.003);
  EXPECT_EQ(spec.stages[1].heat_stepping, ThermalStepping::static_explicit);
  EXPECT_DOUBLE_EQ(spec.stages[1].stability_fraction, 0.25);
  EXPECT_DOUBLE_EQ(spec.stages[1].thermal_time_step_s, 0.0);
}

TEST(ScenarioReaderHeat, YoungsFormOfTheRealModulus) {
  const ScenarioSpec spec =
      read_scenario_string(with(kHeat, "real_shear_modulus: 3 GPa", "real_youngs_modulus: 7.5 GPa"), kFile);
  EXPECT_DOUBLE_EQ(spec.materials[0].real_shear_modulus_Pa, 7.5e9 / 2.5);
}

TEST(ScenarioReaderHeat, NegativeOrZeroThermalProperties) {
  expect_problem(with(kHeat, "conductivity: 14.76 W/(m K)", "conductivity: -14.76 W/(m K)"), "-14.76",
                 "materials.regolith.conductivity", "must be greater than 0, got '-14.76 W/(m K)'");
  expect_problem(with(kHeat, "conductivity: 14.76 W/(m K)", "conductivity: 0"), "conductivity: 0",
                 "materials.regolith.conductivity", "must be greater than 0");
  expect_problem(with(kHeat, "value: [300, 600 J/(kg K)", "value: [300, -600 J/(kg K)"), "-600",
                 "materials.regolith.specific_heat.value[1]", "must be greater than 0");
  expect_problem(with(kHeat, "      specific_heat: 500 J/(kg K)", "      specific_heat: -500 J/(kg K)"),
                 "-500 J/(kg K)", "walls.sieve.thermal.specific_heat", "must be greater than 0");
  expect_problem(with(kHeat, "conductivity: 100 W/(m K)", "conductivity: -1 W/(m K)"), "-1 W/(m K)",
                 "walls.sieve.thermal.conductivity", "must be greater than 0");
  expect_problem(with(kHeat, "conductivity: 14.76 W/(m K)", "conductivity: 14.76 J/(kg K)"), "14.76 J/(kg K)",
                 "materials.regolith.conductivity", "expected a thermal conductivity");
}

TEST(ScenarioReaderHeat, TablesMustIncreaseAndMatch) {
  expect_problem(with(kHeat, "[100 K, 200 K, 77 degC]", "[100 K, 200 K, -100 degC]"), "[100 K, 200 K, -100 degC]",
                 "materials.regolith.specific_heat.temperature[2]",
                 "must increase from row to row: '-100 degC' follows '200 K'");
  expect_problem(with(kHeat, "[100 K, 200 K, 77 degC]", "[100 K, 200 K]"), "[100 K, 200 K]",
                 "materials.regolith.specific_heat.value", "has 3 values but 'temperature' has 2");
  expect_problem(with(kHeat, "[0 s, 10 s, 1 min]", "[0 s, 10 s, 10 s]"), "[0 s, 10 s, 10 s]",
                 "walls.plate.thermal.temperature.time[2]", "must increase from row to row");
  expect_problem(with(kHeat, "[0 s, 10 s, 1 min]", "[0 s, 1 min]"), "{time: [0 s, 1 min]",
                 "walls.plate.thermal.temperature.value", "has 3 values but 'time' has 2");
  expect_problem(with(kHeat, "{temperature: [100 K", "{temperatures: [100 K"), "temperatures",
                 "materials.regolith.specific_heat.temperatures", "did you mean 'temperature'?");
  expect_problem(with(kHeat, "[100 K, 200 K, 77 degC]", "[]"), "temperature: []",
                 "materials.regolith.specific_heat.temperature", "a list of one or more values");
}

TEST(ScenarioReaderHeat, AreaLawNeedsItsCoefficient) {
  expect_problem(with(kHeat, "    heat_transfer_coefficient: 5e4 W/(m^2 K)\n", ""), "conduction: area",
                 "interactions[1].conduction", "needs 'heat_transfer_coefficient'");
  expect_problem(with(kHeat, "    conduction: radius\n",
                      "    conduction: radius\n    heat_transfer_coefficient: 1 W/(m^2 K)\n"),
                 "heat_transfer_coefficient: 1 W", "interactions[0].heat_transfer_coefficient",
                 "only used with 'conduction: area'");
  expect_problem(with(kHeat, "conduction: radius", "conduction: radial"), "conduction: radial",
                 "interactions[0].conduction", "did you mean 'radius'?");
  expect_problem(with(kHeat, "5e4 W/(m^2 K)", "5e4 W/(m K)"), "5e4 W/(m K)",
                 "interactions[1].heat_transfer_coefficient", "expected a heat transfer coefficient");
}

TEST(ScenarioReaderHeat, LumpedWallNeedsItsMassAndCapacity) {
  const std::string sieve_thermal = "    thermal:\n      mode: lumped";
  expect_problem(with(kHeat, "      areal_density: 2 kg/m^2\n", ""), sieve_thermal, "walls.sieve.thermal",
                 "missing 'mass' or 'areal_density'");
  expect_problem(with(kHeat, "      areal_density: 2 kg/m^2\n", "      areal_density: 2 kg/m^2\n      mass: 1 g\n"),
                 sieve_thermal, "walls.sieve.thermal", "give only one of 'mass' or 'areal_density'");
  expect_problem(with(kHeat, "      specific_heat: 500 J/(kg K)\n", ""), sieve_thermal, "walls.sieve.thermal",
                 "missing required key 'specific_heat'");
  expect_problem(with(kHeat, "      temperature: -196 degC\n", ""), sieve_thermal, "walls.sieve.thermal",
                 "missing required key 'temperature'");
  expect_problem(with(kHeat, "      temperature: -196 degC\n", "      temperature: {time: [0], value: [77]}\n"),
                 "temperature: {time: [0]", "walls.sieve.thermal.temperature", "give one temperature");
  // A plane has no area.
  const std::string plane = with(kHeat,
                                 "      mode: fixed\n      temperature: {time: [0 s, 10 s, 1 min], value: [-196 degC, "
                                 "700 degC, 700 degC]}\n",
                                 "      mode: lumped\n      temperature: 300 K\n      specific_heat: 500\n"
                                 "      areal_density: 1 kg/m^2\n");
  expect_problem(plane, "areal_density: 1 kg/m^2", "walls.plate.thermal.areal_density", "a plane is unbounded");
}

TEST(ScenarioReaderHeat, ThermalKeysOfAnotherModeAreExplained) {
  expect_problem(with(kHeat, "      conductivity_mix: harmonic_mean", "      mass: 1 kg"), "mass: 1 kg",
                 "walls.plate.thermal.mass", "only a lumped wall has a heat capacity");
  const std::string adiabatic = with(kHeat, "    length: 150 mm\n    ends: {bottom: capped}\n",
                                     "    length: 150 mm\n    ends: {bottom: capped}\n"
                                     "    thermal: {mode: adiabatic, temperature: 300 K}\n");
  expect_problem(adiabatic, "thermal: {mode: adiabatic", "walls.barrel.thermal.temperature",
                 "an adiabatic wall passes no heat");
  expect_problem(with(kHeat, "      mode: fixed", "      mode: fxed"), "mode: fxed", "walls.plate.thermal.mode",
                 "did you mean 'fixed'?");
  expect_problem(with(kHeat, "conductivity_mix: harmonic_mean", "conductivity_mix: harmonic_man"),
                 "conductivity_mix: harmonic_man", "walls.plate.thermal.conductivity_mix",
                 "did you mean 'harmonic_mean'?");
}

TEST(ScenarioReaderHeat, SieveKeys) {
  expect_problem(with(kHeat, "    segments: 10\n", ""), "- name: sieve", "walls.sieve", "missing required key 'segments'");
  expect_problem(with(kHeat, "    segments: 10\n", "    segments: 0\n"), "segments: 0", "walls.sieve.segments",
                 "at least 1");
  expect_problem(with(kHeat, "    segments: 10\n", "    segments: 2.5\n"), "segments: 2.5", "walls.sieve.segments",
                 "whole number");
  expect_problem(with(kHeat, "    base: [0, 0, 10 mm]", "    point: [0, 0, 10 mm]"), "point: [0, 0, 10 mm]",
                 "walls.sieve.point", "a sieve takes 'base'");
  expect_problem(with(kHeat, "    length: 12 mm\n    ends: {bottom: capped}", "    length: 12 mm\n    cap_bottom: true"),
                 "cap_bottom", "walls.sieve.cap_bottom", "'ends: {bottom: capped}'");
  expect_problem(with(kHeat, "    length: 12 mm\n    ends: {bottom: capped}", "    length: 12 mm\n    ends: {top: capped}"),
                 "ends: {top: capped}", "walls.sieve.ends.top", "the top of a sieve is open");
  expect_problem(with(kHeat, "    length: 12 mm\n    ends: {bottom: capped}",
                      "    length: 12 mm\n    ends: {bottom: capped}\n    contact: inside"),
                 "contact: inside", "walls.sieve.contact", "from both sides");
  expect_problem(with(kHeat, "    segments: 10\n", "    segments: 12\n"), "- name: sieve", "walls.sieve",
                 "outside the domain");  // 10 mm + 12 x 12 mm = 154 mm > 150 mm
}

TEST(ScenarioReaderHeat, InsertionTemperatureFields) {
  expect_problem(with(kHeat, "gradient: [0, 0, 1000 K/m]", "gradient: [0, 0, 1000 K]"), "1000 K]",
                 "insertions.coarse.temperature.gradient[2]", "expected a temperature gradient");
  expect_problem(with(kHeat, "temperature: {value: 100 K", "temperature: {valu: 100 K"), "valu:",
                 "insertions.coarse.temperature.valu", "did you mean 'value'?");
  // 100 K - 5000 K/m x (32 mm - 10 mm) at the region's top: -10 K.
  expect_problem(with(kHeat, "gradient: [0, 0, 1000 K/m]", "gradient: [0, 0, -5000 K/m]"),
                 "gradient: [0, 0, -5000 K/m]", "insertions.coarse.temperature",
                 "falls below absolute zero in the region (to -10 K)");
  EXPECT_EQ(error_of(with(kHeat, "gradient: [0, 0, 1000 K/m]", "gradient: [0, 0, -4000 K/m]")), "");  // 12 K
  // Radially: 14.5 mm from the axis at -1e4 K/m along x takes 100 K down to -45 K.
  expect_problem(with(kHeat, "gradient: [0, 0, 1000 K/m]", "gradient: [-1e4 K/m, 0, 0]"),
                 "gradient: [-1e4 K/m, 0, 0]", "insertions.coarse.temperature", "(to -45 K)");
  expect_problem(with(kHeat, "    count: 20\n    temperature: -196 degC\n", "    count: 20\n    temperature: -300 degC\n"),
                 "-300 degC",
                 "insertions.fine.temperature", "below absolute zero");
}

TEST(ScenarioReaderHeat, HeatOnNeedsThermalPropertiesAndTemperatures) {
  expect_problem(with(kHeat, "    conductivity: 14.76 W/(m K)\n", ""), "  regolith:", "materials.regolith",
                 "heat is on, so the particle material 'regolith' needs 'conductivity'");
  const std::string neither = with(with(kHeat, "    conductivity: 14.76 W/(m K)\n", ""),
                                   "    specific_heat: {temperature: [100 K, 200 K, 77 degC], value: [300, "
                                   "600 J/(kg K), 0.9 kJ/(kg K)]}\n",
                                   "");
  expect_problem(neither, "  regolith:", "materials.regolith", "needs 'conductivity' (e.g. 14.76 W/(m K)) and "
                                                                "'specific_heat'");
  const std::string fine_temperature = "    count: 20\n    temperature: -196 degC\n";
  expect_problem(with(kHeat, fine_temperature, "    count: 20\n"), "- name: fine", "insertions.fine",
                 "heat is on: give the particles' initial 'temperature'");
  // The same file with heat switched off reads: nothing thermal is then required.
  std::string off = with(with(kHeat, "    conductivity: 14.76 W/(m K)\n", ""), fine_temperature, "    count: 20\n");
  off = with(off, "    heat_stepping: static_backward_euler\n    thermal_time_step: 0.1 s\n", "");
  off = with(off, "heat:\n", "heat:\n  enabled: false\n");
  const ScenarioSpec spec = read_scenario_string(off, kFile);
  EXPECT_FALSE(spec.heat.enabled);
  EXPECT_EQ(spec.walls[1].thermal.mode, WallThermalModeSpec::fixed);  // kept, ignored while heat is off
}

TEST(ScenarioReaderHeat, ThermalWallOrStaticStageWithoutAHeatSection) {
  const std::string no_heat = kHeat.substr(0, kHeat.find("heat:\n  time_scale"));
  expect_problem(no_heat, "      mode: fixed", "walls.plate.thermal.mode",
                 "a fixed wall exchanges heat, but heat transfer is off: add a top-level `heat:` section");
  expect_problem(no_heat, "      mode: lumped", "walls.sieve.thermal.mode", "add a top-level `heat:` section");
  expect_problem(no_heat, "heat_stepping: static_backward_euler", "stages.heat.heat_stepping",
                 "add a top-level `heat:` section");
  expect_problem(with(kHeat, "heat:\n", "heat:\n  enabled: false\n"), "heat_stepping: static_backward_euler",
                 "stages.heat.heat_stepping", "heat is off (`heat: {enabled: false}`)");
}

TEST(ScenarioReaderHeat, HeatSectionValues) {
  expect_problem(with(kHeat, "friction_partition: 0.7", "friction_partition: 1.5"), "friction_partition: 1.5",
                 "heat.friction_partition", "must lie between 0 and 1, got '1.5'");
  expect_problem(with(kHeat, "time_scale_factor: 100", "time_scale_factor: 0"), "time_scale_factor: 0",
                 "heat.time_scale_factor", "must be greater than 0");
  expect_problem(with(kHeat, "friction_heating: true", "friction_heating: yes please"), "yes please",
                 "heat.friction_heating", "expected true or false");
  expect_problem(with(kHeat, "time_scale_factor: 100", "timescale_factor: 100"), "timescale_factor",
                 "heat.timescale_factor", "did you mean 'time_scale_factor'?");
  EXPECT_EQ(error_of(with(kHeat, "friction_partition: 0.7", "friction_partition: 0")), "");  // all to the wall
}

// heat_partition and dissipation_heating (docs/scenario-format.md, `heat`): the model is
// read; dissipation heating with friction heating is refused; a partition that weighs the
// walls needs the properties of the material of every wall that takes heat (the plate is
// steel, which has a conductivity but no specific heat).
TEST(ScenarioReaderHeat, HeatPartitionAndDissipationHeating) {
  const auto heat = [](const std::string& lines) {
    return with(kHeat, "  friction_partition: 0.7\n", "  friction_partition: 0.7\n" + lines);
  };
  EXPECT_EQ(read_scenario_string(kHeat, kFile).heat.heat_partition, "fixed");
  EXPECT_EQ(read_scenario_string(heat("  heat_partition: conductivity\n"), kFile).heat.heat_partition,
            "conductivity");
  expect_problem(heat("  heat_partition: effusivity\n"), "- name: plate", "walls.plate",
                 "heat.heat_partition: effusivity weighs the wall 'plate' by its material 'steel', which needs "
                 "'specific_heat'");
  expect_problem(heat("  heat_partition: by_area\n"), "by_area", "heat.heat_partition", "conductivity");
  expect_problem(heat("  dissipation_heating: true\n"), "dissipation_heating", "heat.dissipation_heating", "keep one");
  const ScenarioSpec losses =
      read_scenario_string(with(heat("  dissipation_heating: true\n"), "  friction_heating: true\n", ""), kFile);
  EXPECT_TRUE(losses.heat.dissipation_heating);
  EXPECT_FALSE(losses.heat.friction_heating);
}

TEST(ScenarioReaderHeat, StaticStages) {
  expect_problem(with(kHeat, "    duration: 10 s\n", "    until: settled\n    kinetic_energy_per_particle: 1e-12 J\n"),
                 "until: settled", "stages.heat.until", "give its 'duration'");
  expect_problem(with(kHeat, "    thermal_time_step: 0.1 s\n",
                      "    thermal_time_step: 0.1 s\n    overrides: [{sliding_friction: 0}]\n"),
                 "overrides: [", "stages.heat.overrides", "would change nothing");
  expect_problem(with(kHeat, "    thermal_time_step: 0.1 s\n", "    thermal_time_step: 0.1 s\n    stability_fraction: 0.5\n"),
                 "- name: heat", "stages.heat", "give only one of 'thermal_time_step' or 'stability_fraction'");
  expect_problem(with(kHeat, "    thermal_time_step: 0.1 s\n", "    stability_fraction: 1.5\n"),
                 "stability_fraction: 1.5", "stages.heat.stability_fraction", "greater than 0 and at most 1");
  expect_problem(with(kHeat, "    thermal_time_step: 0.1 s\n", "    thermal_time_step: -0.1 s\n"), "-0.1 s",
                 "stages.heat.thermal_time_step", "must be greater than 0");
  expect_problem(with(kHeat, "    duration: 0.01 s\n", "    duration: 0.01 s\n    thermal_time_step: 1 s\n"),
                 "thermal_time_step: 1 s", "stages.fill.thermal_time_step", "only for a static-bed stage");
  expect_problem(with(kHeat, "static_backward_euler", "static_backwards_euler"), "static_backwards_euler",
                 "stages.heat.heat_stepping", "did you mean 'static_backward_euler'?");
  // Nothing is inserted in a static stage: named, or the first stage by default.
  expect_problem(with(kHeat, "    count: 20\n    temperature: -196 degC\n",
                      "    count: 20\n    temperature: -196 degC\n    stage: heat\n"),
                 "stage: heat", "insertions.fine.stage", "stage 'heat' is a static-bed stage");
  std::string first_static = with(kHeat, "stages:\n  - name: fill\n    duration: 0.01 s\n", "stages:\n");
  first_static = with(first_static, "    thermal_time_step: 0.1 s\n",
                      "    thermal_time_step: 0.1 s\n  - name: fill\n    duration: 0.01 s\n");
  expect_problem(first_static, "- name: fine", "insertions.fine", "without 'stage' an insertion belongs to the first stage");
}

// The builder maps the spec onto the engine: materials, pairs, thermal walls and the
// sieve's segments, heat settings, stages (values in SI, so exact).
TEST(ScenarioBuilderHeat, MapsEverythingOntoTheSimulation) {
  const ScenarioSpec spec = read_scenario_string(kHeat, kFile);
  const PreparedRun run = PreparedRun::build(spec, 1);
  const Simulation& sim = run.simulation();

  const Material& regolith = sim.model().materials[0];
  EXPECT_DOUBLE_EQ(regolith.conductivity_W_per_mK.at(300.0), 14.76);
  EXPECT_DOUBLE_EQ(regolith.specific_heat_J_per_kgK.at(150.0), 450.0);  // halfway between 300 and 600
  EXPECT_DOUBLE_EQ(regolith.real_shear_modulus_Pa, 3e9);
  EXPECT_EQ(sim.model().materials.pair(0, 0).conduction, ConductionLaw::radius);
  EXPECT_EQ(sim.model().materials.pair(0, 1).conduction, ConductionLaw::area);
  EXPECT_DOUBLE_EQ(sim.model().materials.pair(1, 0).heat_transfer_coefficient_W_per_m2K, 5e4);

  const HeatSettings& heat = sim.settings().heat;
  EXPECT_TRUE(heat.enabled);
  EXPECT_DOUBLE_EQ(heat.time_scale_factor, 100.0);
  EXPECT_TRUE(heat.friction_heating);
  EXPECT_DOUBLE_EQ(heat.friction_partition, 0.7);

  // barrel, plate, then the sieve's ten segments, top first.
  ASSERT_EQ(sim.walls.bodies.size(), 12u);
  ASSERT_EQ(sim.wall_thermal_state.size(), 12u);
  EXPECT_EQ(sim.model().wall_thermal[0].mode, WallThermalMode::adiabatic);
  const ThermalWall& plate = sim.model().wall_thermal[1];
  EXPECT_EQ(plate.mode, WallThermalMode::fixed);
  EXPECT_DOUBLE_EQ(sim.wall_thermal_state[1].temperature_K, 77.15);
  EXPECT_DOUBLE_EQ(plate.prescribed_temperature_K.at(5.0), 0.5 * (77.15 + 973.15));
  EXPECT_DOUBLE_EQ(plate.prescribed_temperature_K.at(100.0), 973.15);
  ASSERT_TRUE(plate.conductivity_W_per_mK.has_value());  // from its material, steel
  EXPECT_DOUBLE_EQ(*plate.conductivity_W_per_mK, 50.0);
  EXPECT_EQ(plate.mix, WallConductivityMix::harmonic_mean);

  constexpr double kPi = std::numbers::pi;
  const double r = 0.011, length = 0.012;
  for (int k = 1; k <= 10; ++k) {
    SCOPED_TRACE(k);
    const std::uint32_t body = static_cast<std::uint32_t>(1 + k);
    EXPECT_EQ(sim.walls.bodies[body].name, "sieve[" + std::to_string(k) + "]");
    const ThermalWall& segment = sim.model().wall_thermal[body];
    EXPECT_EQ(segment.mode, WallThermalMode::lumped);
    EXPECT_DOUBLE_EQ(sim.wall_thermal_state[body].temperature_K, 77.15);
    EXPECT_DOUBLE_EQ(*segment.conductivity_W_per_mK, 100.0);
    EXPECT_EQ(segment.mix, WallConductivityMix::wall);
    // Areal density x area: the shell, and the bottom disk of the lowest segment.
    const double area = 2.0 * kPi * r * length + (k == 10 ? kPi * r * r : 0.0);
    EXPECT_NEAR(segment.heat_capacity_J_per_K, 2.0 * area * 500.0, 1e-12);
    // The segment's shell starts (10 - k) segment lengths above the sieve's base.
    int shells = 0, disks = 0;
    for (const WallPrimitive& p : sim.walls.primitives) {
      if (p.body != body) continue;
      if (p.shape == PrimitiveShape::cylinder) {
        ++shells;
        EXPECT_NEAR(p.point_m.z, 0.01 + length * (10 - k), 1e-15);
        EXPECT_DOUBLE_EQ(p.length_m, length);
        EXPECT_DOUBLE_EQ(p.radius_m, r);
        EXPECT_TRUE(p.contact_inside && p.contact_outside);
        EXPECT_EQ(p.rim_top, k == 1);  // edges only at the sieve's own ends
        EXPECT_FALSE(p.rim_bottom);    // the bottom one is capped
      } else if (p.shape == PrimitiveShape::disk) {
        ++disks;
        EXPECT_NEAR(p.point_m.z, 0.01, 1e-15);
      }
    }
    EXPECT_EQ(shells, 1);
    EXPECT_EQ(disks, k == 10 ? 1 : 0);
  }

  const StagePlan& plan = run.plan();
  ASSERT_EQ(plan.stages.size(), 2u);
  EXPECT_EQ(plan.stages[0].heat_stepping, HeatStepping::coupled);
  EXPECT_EQ(plan.stages[1].heat_stepping, HeatStepping::static_backward_euler);
  EXPECT_DOUBLE_EQ(plan.stages[1].thermal_time_step_s, 0.1);
  ASSERT_EQ(plan.insertions.size(), 2u);
  EXPECT_DOUBLE_EQ(plan.insertions[0].temperature.at(Vec3{0.0, 0.0, 0.02}), 77.15);
  EXPECT_DOUBLE_EQ(plan.insertions[1].temperature.at(Vec3{0.0, 0.0, 0.02}), 110.0);  // 100 K + 1000 K/m x 10 mm

  const std::vector<std::string> lines = run.describe();
  const auto mentions = [&](const std::string& fragment) {
    return std::any_of(lines.begin(), lines.end(), [&](const std::string& l) { return l.find(fragment) != std::string::npos; });
  };
  EXPECT_TRUE(mentions("heat: on, time-scale factor S = 100"));
  EXPECT_TRUE(mentions("sieve 'sieve' (10 segments 'sieve[1]' at the top to 'sieve[10]' at the bottom, each): lumped"));
  EXPECT_TRUE(mentions("wall 'plate': fixed at 77.15 K to 973.15 K"));
  EXPECT_TRUE(mentions("static bed (mechanics frozen), heat by backward Euler, thermal step 0.1 s"));
}

TEST(ScenarioBuilderHeat, OpenSieveHasEdgesAtBothEndsAndAMassPerSegment) {
  std::string text = with(kHeat, "    length: 12 mm\n    ends: {bottom: capped}", "    length: 12 mm");
  text = with(text, "      areal_density: 2 kg/m^2", "      mass: 3 g");
  text = with(text, "    segments: 10", "    segments: 2");
  const PreparedRun run = PreparedRun::build(read_scenario_string(text, kFile), 1);
  const Simulation& sim = run.simulation();
  ASSERT_EQ(sim.walls.bodies.size(), 4u);
  EXPECT_EQ(sim.walls.bodies[3].name, "sieve[2]");
  for (std::uint32_t body : {2u, 3u}) {
    EXPECT_DOUBLE_EQ(sim.model().wall_thermal[body].heat_capacity_J_per_K, 0.003 * 500.0);
    for (const WallPrimitive& p : sim.walls.primitives) {
      if (p.body != body) continue;
      EXPECT_EQ(p.shape, PrimitiveShape::cylinder);
      EXPECT_EQ(p.rim_top, body == 2u);
      EXPECT_EQ(p.rim_bottom, body == 3u);
    }
  }
}

TEST(ScenarioBuilderHeat, ParticlesFromAFileTakeTheirOwnTemperatureOrTheField) {
  const TemporaryDirectory directory;
  directory.write("with.csv", "x,y,z,radius,temperature\n0,0,0.02,0.001,300\n0,0.003,0.02,0.001,310\n");
  directory.write("without.csv", "x,y,z,radius\n0,0,0.02,0.001\n");
  const std::string region = "    region: {type: cylinder, base: [0, 0, 12 mm], radius: 8 mm, length: 20 mm}\n"
                             "    diameter: 2 mm\n    count: 20\n";
  // The file's column wins over the insertion's temperature.
  directory.write("with.yaml", with(kHeat, region, "    file: with.csv\n"));
  PreparedRun run = PreparedRun::build(read_scenario_file((directory.path() / "with.yaml").string()), 1);
  ASSERT_EQ(run.plan().insertions[0].from_file.size(), 2u);
  EXPECT_DOUBLE_EQ(run.plan().insertions[0].from_file[0].temperature_K, 300.0);
  EXPECT_DOUBLE_EQ(run.plan().insertions[0].from_file[1].temperature_K, 310.0);
  // Without a column: the insertion's field at the particle.
  directory.write("field.yaml", with(kHeat, region, "    file: without.csv\n"));
  run = PreparedRun::build(read_scenario_file((directory.path() / "field.yaml").string()), 1);
  EXPECT_DOUBLE_EQ(run.plan().insertions[0].from_file[0].temperature_K, 77.15);
  // Neither, with heat on: refused, naming the insertion.
  directory.write("neither.yaml",
                  with(kHeat, region + "    temperature: -196 degC\n", "    file: without.csv\n"));
  const ScenarioSpec neither = read_scenario_file((directory.path() / "neither.yaml").string());
  try {
    PreparedRun::build(neither, 1);
    FAIL() << "a file without temperatures was accepted with heat on";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("insertions.fine: heat is on, but"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("no temperature for 1 of its 1 particles"), std::string::npos)
        << error.what();
  }
}

TEST(ScenarioBuilderHeat, HeatOffLeavesTheWallsThermalSideForTheRecord) {
  std::string text = with(kHeat, "heat:\n", "heat:\n  enabled: false\n");
  text = with(text, "    heat_stepping: static_backward_euler\n    thermal_time_step: 0.1 s\n", "");
  const PreparedRun run = PreparedRun::build(read_scenario_string(text, kFile), 1);
  EXPECT_FALSE(run.simulation().settings().heat.enabled);
  const std::vector<std::string> lines = run.describe();
  EXPECT_NE(std::find(lines.begin(), lines.end(), "heat: off"), lines.end());
}

}  // namespace
}  // namespace regodem
