// The `measurements` section: what it reads into (SI units, walls resolved to bodies by
// the builder), and bad input reported with the file, line and key.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "core/error.hpp"
#include "scenario/scenario_builder.hpp"
#include "scenario/scenario_reader.hpp"
#include "sim/simulation.hpp"
#include "sim/stage_plan.hpp"

namespace regodem {
namespace {

constexpr const char* kFile = "measure.yaml";

const std::string kBase = R"(name: measure-test
domain: {min: [-20 mm, -20 mm, -1 mm], max: [20 mm, 20 mm, 60 mm]}
materials:
  regolith: {density: 3000 kg/m^3, shear_modulus: 3e7 Pa, poisson_ratio: 0.25,
             conductivity: 14.76 W/(m K), specific_heat: 800 J/(kg K)}
interactions:
  - {materials: [regolith, regolith], restitution: 0.24, sliding_friction: 0.8}
walls:
  - {name: barrel, type: cylinder, base: [0, 0, 0], radius: 15 mm, length: 50 mm, ends: {bottom: capped}}
  - {name: sieve, type: sieve, segments: 2, base: [0, 0, 5 mm], radius: 8 mm, length: 10 mm}
  - {name: plate, type: disk, center: [0, 0, 30 mm], normal: [0, 0, 1], radius: 15 mm}
  - name: drill
    type: cylinder
    base: [0, 0, 30 mm]
    radius: 2 mm
    length: 20 mm
    contact: outside
    motion: {velocity: [0, 0, -1 mm/s]}
insertions:
  - {name: fine, material: regolith, region: {type: cylinder, base: [0, 0, 1 mm], radius: 6 mm, length: 20 mm},
     diameter: 1 mm, count: 20, temperature: -196 degC}
stages:
  - {name: drill, duration: 1 s}
heat: {}
)";

const std::string kMeasurements = R"(measurements:
  thermal_history: {threshold: -60 degC}
  regions:
    - name: chip
      region: {type: chip_zone, center: [0, 0, 25 mm], inner_radius: 3 mm, radius: 12 mm, height: 5 mm}
      every_depth: {wall: drill, depth: 0.5 mm}
    - name: bit
      region: {type: cylinder, base: [0, 0, 27 mm], radius: 4 mm, length: 3 mm}
      moves_with: drill
      interval: 0.1 s
    - name: skin
      region: {type: band, wall: sieve, width: 1 mm, side: inside}
  bands:
    - {name: sieve_band, wall: sieve, width: 2 mm, in_side: inside, at_stage_end: false, every_steps: 100}
    - {name: w0, plane: {point: [0, 0, 10 mm], normal: [0, 0, 1]}, width: 2 mm, in_side: back}
  profiles:
    - {name: axial, type: plane, point: [0, 0, 0], normal: [0, 0, 1], range: [0, 30 mm], bin: 1 mm,
       at_times: [0.5 s, 1 s]}
    - {name: radial, type: radial, axis_point: [0, 0, 25 mm], axis: [0, 0, -1], slab: [4 mm, 6 mm],
       range: [0, 15 mm], bin: 0.5 mm, at_depths: {wall: drill, depths: [0.5 mm, 1 mm]}}
)";

std::string error_of(const std::string& text) {
  try {
    PreparedRun::build(read_scenario_string(text, kFile), 1);
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

/// `kBase + measurements` must fail at the line holding `marker`, naming `key` and `fragment`.
void expect_problem(const std::string& measurements, const std::string& marker, const std::string& key,
                    const std::string& fragment) {
  const std::string text = kBase + measurements;
  const std::string message = error_of(text);
  const std::size_t at = text.find(marker);
  ASSERT_NE(at, std::string::npos) << marker;
  const int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
  EXPECT_NE(message.find(std::string(kFile) + ":" + std::to_string(line) + ":"), std::string::npos)
      << "expected line " << line << " in: " << message;
  EXPECT_NE(message.find(key), std::string::npos) << message;
  EXPECT_NE(message.find(fragment), std::string::npos) << message;
}

TEST(ScenarioMeasurements, ReadsEveryKindInSIUnitsAndResolvesWalls) {
  const ScenarioSpec spec = read_scenario_string(kBase + kMeasurements, kFile);
  const MeasurementsSpec& m = spec.measurements;
  EXPECT_TRUE(m.thermal_history);
  EXPECT_NEAR(m.thermal_history_threshold_K, 213.15, 1e-9);
  ASSERT_EQ(m.items.size(), 7u);

  const Measurement& chip = m.items[0].measurement;
  EXPECT_EQ(chip.kind, MeasurementKind::region);
  EXPECT_EQ(chip.region.shape, MeasureShape::annulus);
  EXPECT_NEAR(chip.region.base_m.z, 0.025, 1e-12);
  EXPECT_NEAR(chip.region.inner_radius_m, 0.003, 1e-12);
  EXPECT_NEAR(chip.region.length_m, 0.005, 1e-12);
  EXPECT_EQ(chip.schedule.periodic.trigger, SnapshotSchedule::Trigger::depth);
  EXPECT_EQ(m.items[0].depth_wall, "drill");
  EXPECT_EQ(m.items[1].moves_with, "drill");
  EXPECT_TRUE(m.items[2].measurement.schedule.with_time_series());
  EXPECT_EQ(m.items[2].measurement.region.shape, MeasureShape::cylinder_band);
  EXPECT_NEAR(m.items[2].measurement.region.length_m, 0.020, 1e-12);  // the sieve: 2 x 10 mm

  const Measurement& band = m.items[3].measurement;
  EXPECT_EQ(band.kind, MeasurementKind::band);
  EXPECT_LT(band.band_in.near_m, 0.0);  // inside the sieve
  EXPECT_FALSE(band.schedule.periodic.at_stage_end);
  EXPECT_EQ(m.items[4].measurement.band_in.near_m, -0.002);  // behind the plane

  const Measurement& axial = m.items[5].measurement;
  EXPECT_EQ(axial.profile.bin_count(), 30u);
  EXPECT_EQ(axial.schedule.at_times_s, (std::vector<double>{0.5, 1.0}));
  const Measurement& radial = m.items[6].measurement;
  EXPECT_EQ(radial.profile.coordinate, ProfileCoordinate::radius);
  EXPECT_NEAR(radial.profile.slab_max_m, 0.006, 1e-12);
  EXPECT_NEAR(radial.schedule.at_depths_m[1], 0.001, 1e-12);

  const PreparedRun run = PreparedRun::build(spec, 1);
  const MeasurementPlan& plan = run.plan().measurements;
  ASSERT_EQ(plan.items.size(), 7u);
  const int drill = 4;  // barrel, sieve[1], sieve[2], plate, drill
  EXPECT_EQ(plan.items[0].depth_body, drill);
  EXPECT_EQ(plan.items[0].schedule.periodic.depth_body, drill);
  EXPECT_EQ(plan.items[0].follow_body, -1);
  EXPECT_EQ(plan.items[1].follow_body, drill);
  EXPECT_EQ(plan.items[1].depth_body, drill);  // rides on a fed wall: its depth is a column
  EXPECT_EQ(plan.items[6].depth_body, drill);
  EXPECT_TRUE(run.simulation().settings().heat.track_thermal_history);
  const std::vector<std::string> lines = run.describe();
  EXPECT_NE(std::find(lines.begin(), lines.end(),
                      "measurement 'bit': region, every 0.1 s, moving with wall 'drill'"),
            lines.end());
}

TEST(ScenarioMeasurements, ThresholdDefaultsToMinus70Celsius) {
  const ScenarioSpec spec = read_scenario_string(kBase + "measurements: {thermal_history: {}}\n", kFile);
  EXPECT_TRUE(spec.measurements.thermal_history);
  EXPECT_NEAR(spec.measurements.thermal_history_threshold_K, 203.15, 1e-12);
}

TEST(ScenarioMeasurements, UnknownWallIsNamedWithASuggestion) {
  expect_problem("measurements:\n  regions:\n    - name: bit\n      region: {type: box, min: [0, 0, 0], max: [1, 1, 1]}\n"
                 "      moves_with: dril\n",
                 "moves_with: dril", "measurements.regions.bit.moves_with", "did you mean 'drill'");
}

TEST(ScenarioMeasurements, NegativeWidthIsRefused) {
  expect_problem("measurements:\n  bands:\n    - {name: b, wall: sieve, in_side: inside,\n       width: -2 mm}\n",
                 "width: -2 mm", "measurements.bands.b.width", "must be greater than 0");
}

TEST(ScenarioMeasurements, InvertedRangeIsRefused) {
  expect_problem("measurements:\n  profiles:\n    - {name: p, type: plane, point: [0, 0, 0], normal: [0, 0, 1], bin: 1 mm,\n"
                 "       range: [30 mm, 0]}\n",
                 "range: [30 mm", "measurements.profiles.p.range", "inverted");
}

TEST(ScenarioMeasurements, InvertedSlabAndDecreasingDepthsAreRefused) {
  expect_problem("measurements:\n  profiles:\n    - {name: p, type: radial, axis_point: [0, 0, 0], range: [0, 5 mm], bin: 1 mm,\n"
                 "       slab: [6 mm, 4 mm]}\n",
                 "slab: [6 mm", "measurements.profiles.p.slab", "low (0.006) must be below high (0.004)");
  expect_problem("measurements:\n  regions:\n    - name: r\n      region: {type: box, min: [0, 0, 0], max: [1, 1, 1]}\n"
                 "      at_depths: {wall: drill,\n        depths: [2 mm, 1 mm]}\n",
                 "depths: [2 mm", "measurements.regions.r.at_depths.depths", "must increase");
}

TEST(ScenarioMeasurements, InnerRadiusAboveOuterIsRefused) {
  expect_problem("measurements:\n  regions:\n    - name: chip\n      region: {type: chip_zone, center: [0, 0, 25 mm], radius: 3 mm,\n"
                 "               inner_radius: 5 mm, height: 5 mm}\n",
                 "inner_radius: 5 mm", "measurements.regions.chip.region.inner_radius", "must be smaller");
}

TEST(ScenarioMeasurements, WrongSideForTheSurfaceIsRefused) {
  expect_problem("measurements:\n  bands:\n    - {name: b, wall: plate, width: 1 mm,\n       in_side: inside}\n",
                 "in_side: inside", "measurements.bands.b.in_side", "not one of front or back");
}

TEST(ScenarioMeasurements, DepthScheduleOfAWallThatDoesNotFeedIsRefused) {
  expect_problem("measurements:\n  regions:\n    - name: r\n      region: {type: box, min: [0, 0, 0], max: [1, 1, 1]}\n"
                 "      every_depth: {wall: plate, depth: 1 mm}\n",
                 "- name: r", "measurement 'r'", "has no feed");
}

TEST(ScenarioMeasurements, TwoTriggersDuplicateNamesAndUnknownKeysAreRefused) {
  expect_problem("measurements:\n  regions:\n    - name: r\n      region: {type: box, min: [0, 0, 0], max: [1, 1, 1]}\n"
                 "      interval: 1 s\n      every_steps: 10\n",
                 "- name: r", "measurements.regions.r", "give only one of 'interval' or 'every_steps'");
  expect_problem("measurements:\n  regions:\n    - name: r\n      region: {type: box, min: [0, 0, 0], max: [1, 1, 1]}\n"
                 "  bands:\n    - {name: r, wall: sieve, width: 1 mm, in_side: inside}\n",
                 "- {name: r", "measurements.bands.r", "'r'");
  expect_problem("measurements:\n  regions:\n    - name: r\n      region: {type: box, min: [0, 0, 0], max: [1, 1, 1]}\n"
                 "      intervall: 1 s\n",
                 "intervall", "measurements.regions.r.intervall", "did you mean 'interval'");
}

TEST(ScenarioMeasurements, HeatOffRefusesTheThermalHistory) {
  std::string no_heat = kBase;
  no_heat.erase(no_heat.find("heat: {}\n"));
  const std::string text = no_heat + "measurements:\n  thermal_history: {}\n";
  EXPECT_NE(error_of(text).find("heat transfer is off"), std::string::npos) << error_of(text);
}

}  // namespace
}  // namespace regodem

namespace regodem {
namespace {

// `until: {measurement, quantity, rises_to | falls_to}` with `max_duration`: read, and
// resolved by the builder to the measurement's index; a wrong name, a quantity the
// measurement does not have, a profile, no bound, two directions: refused.
const std::string kDrillStage = "  - {name: drill, duration: 1 s}";

std::string with_stage(const std::string& stage) {
  std::string text = kBase + kMeasurements;
  text.replace(text.find(kDrillStage), kDrillStage.size(), stage);
  return text;
}

TEST(ScenarioMeasurements, StageEndsWhenABandOrRegionReachesAValue) {
  const PreparedRun run = PreparedRun::build(
      read_scenario_string(with_stage("  - {name: drill, until: {measurement: w0, quantity: T_in, rises_to: 446.8 K},"
                                      " max_duration: 5 s}"),
                           kFile),
      1);
  const Stage& stage = run.plan().stages.at(0);
  ASSERT_TRUE(stage.ends_on_measurement());
  EXPECT_EQ(run.plan().measurements.items[stage.until_measured->measurement].name, "w0");
  EXPECT_EQ(stage.until_measured->quantity, MeasuredQuantity::T_in);
  EXPECT_TRUE(stage.until_measured->rising);
  EXPECT_DOUBLE_EQ(stage.until_measured->value_K, 446.8);
  EXPECT_DOUBLE_EQ(stage.max_duration_s, 5.0);

  const PreparedRun falling = PreparedRun::build(
      read_scenario_string(with_stage("  - {name: drill, until: {measurement: chip, quantity: max, falls_to: -70 degC},"
                                      " max_duration: 5 s}"),
                           kFile),
      1);
  EXPECT_FALSE(falling.plan().stages.at(0).until_measured->rising);
  EXPECT_NEAR(falling.plan().stages.at(0).until_measured->value_K, 203.15, 1e-9);
}

TEST(ScenarioMeasurements, StageEndOnAMeasurementIsChecked) {
  const auto problem = [](const std::string& stage, const std::string& fragment) {
    const std::string message = error_of(with_stage(stage));
    EXPECT_NE(message.find(fragment), std::string::npos) << "expected '" << fragment << "' in: " << message;
  };
  problem("  - {name: drill, until: {measurement: nowhere, quantity: T_in, rises_to: 300 K}, max_duration: 5 s}",
          "no region or band has that name");
  problem("  - {name: drill, until: {measurement: chip, quantity: T_in, rises_to: 300 K}, max_duration: 5 s}",
          "a band gives T_in, T_out or T_d, a region mean, min or max");
  problem("  - {name: drill, until: {measurement: w0, quantity: mean, rises_to: 300 K}, max_duration: 5 s}",
          "a band gives T_in, T_out or T_d");
  problem("  - {name: drill, until: {measurement: axial, quantity: mean, rises_to: 300 K}, max_duration: 5 s}",
          "a profile");
  problem("  - {name: drill, until: {measurement: w0, quantity: T_in, rises_to: 300 K}}", "max_duration");
  problem("  - {name: drill, until: {measurement: w0, quantity: T_in, rises_to: 300 K, falls_to: 200 K},"
          " max_duration: 5 s}",
          "give only one of 'rises_to' or 'falls_to'");
  problem("  - {name: drill, until: {measurement: w0, quantity: T_up, rises_to: 300 K}, max_duration: 5 s}",
          "T_up");
}

}  // namespace
}  // namespace regodem
