// The scenario reader: a valid file maps onto ScenarioSpec in SI units; every kind of
// bad input is reported with the file, the line of the offending key and its dotted
// path; --set overrides edit the tree before it is checked.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "scenario/scenario_reader.hpp"

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
  ASSERT_EQ(spec.stages.size(), 2u);
  EXPECT_EQ(spec.stages[1].end, StageEnd::settled);
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
        BadFixture{"region_outside_domain.yaml", 22, "insertions.grains.region", "outside the domain"}),
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

}  // namespace
}  // namespace regodem
