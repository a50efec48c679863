// The calibration file of `regodem calibrate`: a complete file maps onto
// doe::CalibrationSpec; bad keys and values are refused with the file, the line and
// the key path, all problems at once.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "core/error.hpp"
#include "scenario/calibration_reader.hpp"

namespace regodem {
namespace {

// Beside tests/data/scenarios/calibrate/plate.yaml, so that `scenario: plate.yaml` exists.
const std::string kFile = std::string(REGODEM_SOURCE_DIR) + "/tests/data/scenarios/calibrate/test.yaml";
const std::string kPlate = std::string(REGODEM_SOURCE_DIR) + "/tests/data/scenarios/calibrate/plate.yaml";

// One key per line, so that a test can break one line and expect its number.
const std::string kValid = R"(calibration:
  scenario: plate.yaml
  reference:
    scenario: ./plate.yaml
    set: ["walls.plate.thermal.temperature=410 K"]
    pass_on:
      - {from: stages.heat.end_time_s, set: stages.heat.duration, unit: s}
  set: ["output.interval=0.2 s", "heat.enabled=true"]
  factors:
    - {name: C_wall, set: walls.sieve.thermal.specific_heat, centre: 1200, step: 600, unit: J/(kg K)}
    - {name: lambda_wall, set: walls.sieve.thermal.conductivity, centre: 300, step: 200, unit: W/(m K)}
  design: {alpha: face, centre_points: 5}
  responses:
    - {name: T_d, value: measurements.bands.sieve.final.T_d_K, unit: K, target: {reference: measurements.bands.w0.final.T_d_K}}
    - {name: T_in, value: measurements.bands.sieve.final.T_in_K, unit: K, target: {value: 446.8}, terms: "C_wall, lambda_wall, lambda_wall^2"}
  solve:
    mode: sequential
    fix: {C_wall: 1200}
    steps:
      - {response: T_d, factor: lambda_wall}
      - {response: T_in, factor: C_wall}
  processes: 3
  threads_per_run: 2
)";

std::string replace_line(const std::string& text, int line, const std::string& replacement) {
  std::size_t start = 0;
  for (int l = 1; l < line; ++l) start = text.find('\n', start) + 1;
  return text.substr(0, start) + replacement + text.substr(text.find('\n', start));
}

/// The InputError message of reading `text`, or "" when it reads.
std::string problem(const std::string& text) {
  try {
    read_calibration_string(text, kFile);
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(CalibrationReader, ReadsEveryKey) {
  const doe::CalibrationSpec spec = read_calibration_string(kValid, kFile);
  EXPECT_EQ(spec.scenario, kPlate);
  EXPECT_EQ(spec.reference.scenario, kPlate);
  ASSERT_EQ(spec.reference.set.size(), 1u);
  EXPECT_EQ(spec.reference.set[0], "walls.plate.thermal.temperature=410 K");
  ASSERT_EQ(spec.reference.pass_on.size(), 1u);
  EXPECT_EQ(spec.reference.pass_on[0].from_json_path, "stages.heat.end_time_s");
  EXPECT_EQ(spec.reference.pass_on[0].set_path, "stages.heat.duration");
  EXPECT_EQ(spec.reference.pass_on[0].unit, "s");
  EXPECT_EQ(spec.set, (std::vector<std::string>{"output.interval=0.2 s", "heat.enabled=true"}));
  ASSERT_EQ(spec.factors.size(), 2u);
  EXPECT_EQ(spec.factors[0].design.name, "C_wall");
  EXPECT_EQ(spec.factors[0].design.unit, "J/(kg K)");
  EXPECT_EQ(spec.factors[0].design.centre, 1200.0);
  EXPECT_EQ(spec.factors[0].design.step, 600.0);
  EXPECT_EQ(spec.factors[1].set_path, "walls.sieve.thermal.conductivity");
  EXPECT_EQ(spec.design.alpha_kind, doe::AlphaKind::face);
  EXPECT_EQ(spec.design.centre_points, 5);
  ASSERT_EQ(spec.responses.size(), 2u);
  EXPECT_EQ(spec.responses[0].json_path, "measurements.bands.sieve.final.T_d_K");
  EXPECT_EQ(spec.responses[0].target_reference_path, "measurements.bands.w0.final.T_d_K");
  EXPECT_FALSE(spec.responses[0].target_value);
  EXPECT_TRUE(spec.responses[0].terms.empty());  // the full quadratic
  EXPECT_EQ(spec.responses[1].target_value, 446.8);
  EXPECT_EQ(spec.responses[1].terms, "C_wall, lambda_wall, lambda_wall^2");
  EXPECT_EQ(spec.solve.mode, doe::CalibrationSolveMode::sequential);
  ASSERT_EQ(spec.solve.fixed.size(), 1u);
  EXPECT_EQ(spec.solve.fixed[0], (std::pair<std::string, double>{"C_wall", 1200.0}));
  ASSERT_EQ(spec.solve.steps.size(), 2u);
  EXPECT_EQ(spec.solve.steps[1].response, "T_in");
  EXPECT_EQ(spec.solve.steps[1].factor, "C_wall");
  EXPECT_EQ(spec.processes, 3);
  EXPECT_EQ(spec.threads_per_run, 2);
}

TEST(CalibrationReader, DefaultsAndShortForms) {
  const std::string text = R"(calibration:
  scenario: plate.yaml
  reference: {scenario: plate.yaml}
  factors:
    - {name: A, set: walls.plate.thermal.conductivity, centre: 20, step: 2}
  responses:
    - {name: Y, value: measurements.regions.late.final.temperature_mean_K, target: reference}
)";
  const doe::CalibrationSpec spec = read_calibration_string(text, kFile);
  EXPECT_EQ(spec.design.alpha_kind, doe::AlphaKind::rotatable);
  EXPECT_EQ(spec.design.centre_points, 3);
  EXPECT_EQ(spec.responses[0].target_reference_path, spec.responses[0].json_path);  // `target: reference`
  EXPECT_EQ(spec.solve.mode, doe::CalibrationSolveMode::simultaneous);
  EXPECT_EQ(spec.processes, 0);  // the command's choice: cores / threads_per_run
  EXPECT_EQ(spec.threads_per_run, 1);
}

TEST(CalibrationReader, BadKeysAndValuesNameFileLineAndKey) {
  struct Case {
    int line;
    std::string replacement;
    std::string expected;  // after "test.yaml:"
  };
  const std::vector<Case> cases{
      {2, "  scenario: missing.yaml", "2:13: calibration.scenario: no such scenario file"},
      {2, "  scenari: plate.yaml", "2:3: calibration.scenari: unknown key (did you mean 'scenario'?)"},
      {7, "      - {from: stages.heat.end_time_s, set: stages heat, unit: s}",
       "calibration.reference.pass_on[0].set: 'stages heat' is not a key path"},
      {8, "  set: [\"output.interval\"]", "8:9: calibration.set[0]: 'output.interval' is not a --set override"},
      {10, "    - {name: C_wall, set: walls.sieve.thermal.specific_heat, centre: 1200, step: -6, unit: J/(kg K)}",
       "10:82: calibration.factors.C_wall.step: must be greater than 0"},
      {11, "    - {name: C_wall, set: walls.sieve.thermal.conductivity, centre: 300, step: 200}",
       "11:7: calibration.factors.C_wall: a second factor named 'C_wall'"},
      {11, "    - {name: lambda_wall, set: walls.sieve.thermal.conductivity, centre: 3 hundred, step: 200}",
       "calibration.factors.lambda_wall.centre:"},
      {12, "  design: {alpha: wide, centre_points: 5}",
       "calibration.design.alpha: 'wide' is not rotatable, face or a number"},
      {14, "    - {name: T_d, value: measurements.bands.sieve.final.T_d_K, unit: K, target: {reference: a, value: 1}}",
       "14:73: calibration.responses.T_d.target: give only one of 'reference' or 'value'"},
      {15, "    - {name: T_in, value: x.y, target: {value: 446.8}, terms: \"C_wall, D^2\"}",
       "calibration.responses.T_in.terms:"},
      {21, "      - {response: T_out, factor: C_wall}",
       "calibration.solve.steps[1].response: 'T_out' is not one of the responses"},
      {16, "  solve: {mode: together}", "calibration.solve.mode: 'together' is not one of simultaneous or sequential"},
      {23, "  threads_per_run: 0", "23:20: calibration.threads_per_run: must be at least 1"},
  };
  for (const Case& c : cases) {
    std::string text = replace_line(kValid, c.line, c.replacement);
    if (c.line == 16) {  // one line for the whole solve section
      for (int l = 17; l <= 21; ++l) text = replace_line(text, l, "#");
    }
    const std::string message = problem(text);
    EXPECT_TRUE(contains(message, "test.yaml:" + c.expected) || contains(message, c.expected))
        << "line " << c.line << ": " << message;
    EXPECT_TRUE(contains(message, "test.yaml:")) << message;
  }
}

TEST(CalibrationReader, EveryProblemAtOnceAndMissingKeys) {
  const std::string text = R"(calibration:
  reference: {scenario: plate.yaml}
  factors:
    - {name: A, set: x.y, centre: 1, step: 1}
    - {name: B, set: x.z, centre: 1, step: 1}
  responses:
    - {name: Y, value: a.b, target: reference}
)";
  const std::string message = problem(text);
  EXPECT_TRUE(contains(message, "test.yaml:1:1: calibration: missing required key 'scenario'")) << message;
  EXPECT_TRUE(contains(message,
                       "a simultaneous solve needs as many responses as free factors: 1 responses, 2 free "
                       "factors"))
      << message;
  EXPECT_TRUE(contains(problem("name: demo\n"), "not a calibration file")) << problem("name: demo\n");
  EXPECT_TRUE(contains(problem("calibration: [1, 2\n"), "YAML syntax error")) << problem("calibration: [1, 2\n");
}

}  // namespace
}  // namespace regodem
