// End to end: `regodem run` on a tiny heated cup with every kind of measurement writes
// regions/*.csv, profiles/*.csv, the thermal-history columns of time_series.csv and the
// final values in summary.json, with sane values (between the coldest and the hottest
// boundary).
#include <unistd.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace {

namespace fs = std::filesystem;

int run_regodem(const std::string& arguments, std::string& output) {
  const std::string command = std::string("'") + REGODEM_BINARY + "' " + arguments + " </dev/null 2>&1";
  std::FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return -1;
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) output.append(buffer, n);
  const int status = ::pclose(pipe);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

std::vector<std::string> lines_of(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<double> numbers_of(const std::string& line) {
  std::vector<double> values;
  std::stringstream in(line);
  for (std::string field; std::getline(in, field, ',');) values.push_back(field == "nan" ? NAN : std::stod(field));
  return values;
}

const char* kScenario = R"(name: measured
seed: 3
domain: {min: [-5 mm, -5 mm, -1 mm], max: [5 mm, 5 mm, 10 mm]}
materials:
  glass: {density: 2500 kg/m^3, shear_modulus: 1e6 Pa, poisson_ratio: 0.25,
          conductivity: 1 W/(m K), specific_heat: 800 J/(kg K)}
interactions:
  - {materials: [glass, glass], restitution: 0.5, sliding_friction: 0.5}
walls:
  - {name: cup, type: cylinder, base: [0, 0, 0], radius: 4 mm, length: 9 mm, ends: {bottom: capped},
     thermal: {mode: fixed, temperature: 400 K}}
  - {name: probe, type: disk, center: [0, 0, 9 mm], normal: [0, 0, 1], radius: 1 mm,
     motion: {velocity: [0, 0, -10 mm/s]}}
insertions:
  - {name: drop, material: glass, region: {type: cylinder, base: [0, 0, 1 mm], radius: 2.5 mm, length: 5 mm},
     diameter: 1 mm, count: 8, temperature: -196 degC}
stages:
  - {name: drop, duration: 0.02 s}
heat: {time_scale_factor: 1e4}
output: {interval: 0.005 s}
measurements:
  thermal_history: {}
  regions:
    - {name: all, region: {type: cylinder, base: [0, 0, 0], radius: 4 mm, length: 9 mm}}
    - {name: near_probe, region: {type: cylinder, base: [0, 0, 5 mm], radius: 3 mm, length: 3 mm},
       moves_with: probe, every_depth: {wall: probe, depth: 0.05 mm}}
  bands:
    - {name: floor, plane: {point: [0, 0, 2 mm], normal: [0, 0, 1]}, width: 2 mm, in_side: back, interval: 0.01 s}
  profiles:
    - {name: axial, type: plane, point: [0, 0, 0], normal: [0, 0, 1], range: [0, 8 mm], bin: 1 mm,
       at_times: [0.01 s, 0.02 s]}
)";

TEST(MeasurementOutputs, RunWritesRegionBandProfileFilesAndSummary) {
  std::string pattern = (fs::temp_directory_path() / "regodem-measure-XXXXXX").string();
  ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
  const fs::path directory = pattern;
  std::ofstream(directory / "measured.yaml") << kScenario;
  std::string output;
  const int status = run_regodem("run '" + (directory / "measured.yaml").string() + "' -o '" +
                                     (directory / "out").string() + "' --threads 1",
                                 output);
  ASSERT_EQ(status, 0) << output;
  const fs::path out = directory / "out";

  const std::vector<std::string> series = lines_of(out / "time_series.csv");
  ASSERT_GE(series.size(), 2u);
  EXPECT_NE(series[0].find("peak_temperature_max [K],crossed_threshold_fraction [-],time_above_threshold_mean [s],"
                           "time_above_threshold_mean_real [s]"),
            std::string::npos)
      << series[0];

  const std::vector<std::string> all = lines_of(out / "regions" / "all.csv");
  ASSERT_EQ(all.size(), series.size());  // sampled with the time series
  EXPECT_EQ(all[0], "time [s],real_time [s],temperature_mean [K],temperature_min [K],temperature_max [K],count [-],"
                    "crossed_threshold_fraction [-]");
  const std::vector<double> last = numbers_of(all.back());
  EXPECT_EQ(last[5], 8.0);
  EXPECT_GE(last[3], 77.15 - 1e-9);  // between the inserted -196 degC and the 400 K cup
  EXPECT_LE(last[4], 400.0 + 1e-9);
  EXPECT_GT(last[2], 77.15);         // the cup's floor has warmed them

  const std::vector<std::string> probe = lines_of(out / "regions" / "near_probe.csv");
  EXPECT_EQ(probe[0], "depth [m],time [s],real_time [s],temperature_mean [K],temperature_min [K],temperature_max [K],count [-],"
                      "crossed_threshold_fraction [-]");
  EXPECT_GE(probe.size(), 4u + 1u);  // every 0.05 mm of 0.2 mm, from 0

  const std::vector<std::string> floor = lines_of(out / "regions" / "floor.csv");
  EXPECT_EQ(floor[0], "time [s],real_time [s],T_in [K],T_out [K],T_d [K],count_in [-],count_out [-]");
  EXPECT_EQ(floor.size(), 1u + 3u);  // 0, 0.01, 0.02 s (the last at the stage end)

  const std::vector<std::string> axial = lines_of(out / "profiles" / "axial.csv");
  EXPECT_EQ(axial[0], "time [s],real_time [s],distance [m],temperature_mean [K],temperature_min [K],temperature_max [K],count [-]");
  ASSERT_EQ(axial.size(), 1u + 2u * 8u);  // two instants of eight bins
  EXPECT_NEAR(numbers_of(axial[1])[2], 0.0005, 1e-15);
  EXPECT_NEAR(numbers_of(axial[16])[0], 0.02, 1e-5);  // the step nearest 0.02 s (steps of ~1e-6 s)

  std::ifstream summary_file(out / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(summary_file);
  const nlohmann::json& m = summary.at("measurements");
  EXPECT_EQ(m.at("thermal_history").at("threshold_K"), 203.15);
  EXPECT_EQ(m.at("thermal_history").at("particles"), 8);
  EXPECT_LE(m.at("thermal_history").at("peak_temperature_max_K").get<double>(), 400.0 + 1e-9);
  EXPECT_EQ(m.at("regions").at("all").at("file"), "regions/all.csv");
  EXPECT_EQ(m.at("regions").at("all").at("final").at("count"), 8);
  EXPECT_EQ(m.at("regions").at("all").at("final").at("temperature_mean_K").get<double>(), last[2]);
  EXPECT_TRUE(m.at("bands").at("floor").at("final").contains("T_d_K"));
  EXPECT_EQ(m.at("profiles").at("axial").at("samples"), 2);
  EXPECT_EQ(m.at("profiles").at("axial").at("final").at("distance_m").size(), 8u);
  fs::remove_all(directory);
}

/// The index of the column `name` in a CSV header line; -1 when it has none.
int column_index(const std::string& header, const std::string& name) {
  std::stringstream in(header);
  int k = 0;
  for (std::string field; std::getline(in, field, ','); ++k)
    if (field == name) return k;
  return -1;
}

/// a equals b to round-off: relative 1e-12 (set before the run), exact at zero.
void expect_round_off(double a, double b, const std::string& where) {
  EXPECT_NEAR(a, b, 1e-12 * std::max(std::abs(a), std::abs(b))) << where;
}

// Issue 22: with heat.time_scale_factor S = 10 every output that gives a compressed time
// or heat rate has its real-time twin beside it: real_time = time x S, heat_flow_real =
// heat_flow / S, the time above the threshold x S, in the CSV files and in summary.json.
// Tolerance, set before running: relative 1e-12 (round-off).
TEST(MeasurementOutputs, CompressedTimeHasItsRealTimeTwins) {
  std::string pattern = (fs::temp_directory_path() / "regodem-real-time-XXXXXX").string();
  ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
  const fs::path directory = pattern;
  std::string scenario = kScenario;
  scenario.replace(scenario.find("time_scale_factor: 1e4"), 22, "time_scale_factor: 10");
  // Above the threshold (203.15 K) from the start, under a 400 K cup: every grain's time
  // above it is the run's time, and heat flows in from the cup once they reach its floor.
  scenario.replace(scenario.find("temperature: -196 degC"), 22, "temperature: 250 K");
  scenario.replace(scenario.find("duration: 0.02 s"), 16, "duration: 0.06 s");  // long enough to reach the floor
  std::ofstream(directory / "compressed.yaml") << scenario;
  std::string output;
  const int status = run_regodem("run '" + (directory / "compressed.yaml").string() + "' -o '" +
                                     (directory / "out").string() + "' --threads 1",
                                 output);
  ASSERT_EQ(status, 0) << output;
  const fs::path out = directory / "out";
  constexpr double S = 10.0;
  // The progress says it too: the stage's start and end in real time.
  EXPECT_NE(output.find("started at t = 0 s, runs to 0.06 s (0 s to 0.6 s real, S = 10)"), std::string::npos)
      << output;

  const std::vector<std::string> series = lines_of(out / "time_series.csv");
  ASSERT_GE(series.size(), 3u);
  const std::string& header = series[0];
  ASSERT_EQ(column_index(header, "time [s]"), 0) << header;
  ASSERT_EQ(column_index(header, "real_time [s]"), 1) << header;
  const int flow = column_index(header, "cup.heat_flow [W]"), flow_real = column_index(header, "cup.heat_flow_real [W]");
  const int above = column_index(header, "time_above_threshold_mean [s]"),
            above_real = column_index(header, "time_above_threshold_mean_real [s]");
  ASSERT_GE(flow, 0) << header;
  ASSERT_EQ(flow_real, flow + 1) << header;
  ASSERT_GE(above, 0) << header;
  ASSERT_EQ(above_real, above + 1) << header;
  bool heat_flowed = false;
  for (std::size_t i = 1; i < series.size(); ++i) {
    const std::vector<double> row = numbers_of(series[i]);
    expect_round_off(row[1], S * row[0], "real_time, row " + std::to_string(i));
    expect_round_off(row[static_cast<std::size_t>(flow_real)], row[static_cast<std::size_t>(flow)] / S,
                     "heat_flow_real, row " + std::to_string(i));
    expect_round_off(row[static_cast<std::size_t>(above_real)], S * row[static_cast<std::size_t>(above)],
                     "time_above_threshold_mean_real, row " + std::to_string(i));
    heat_flowed = heat_flowed || row[static_cast<std::size_t>(flow)] > 0.0;
  }
  EXPECT_TRUE(heat_flowed) << "the cup never heated a grain: the heat-flow check compared zeros";
  const std::vector<double> last = numbers_of(series.back());
  EXPECT_GT(last[static_cast<std::size_t>(above)], 0.0);

  // Every measurement file: real_time right after time.
  for (const char* file : {"regions/all.csv", "regions/near_probe.csv", "regions/floor.csv", "profiles/axial.csv"}) {
    const std::vector<std::string> lines = lines_of(out / file);
    ASSERT_GE(lines.size(), 2u) << file;
    const int time = column_index(lines[0], "time [s]");
    ASSERT_GE(time, 0) << file << ": " << lines[0];
    ASSERT_EQ(column_index(lines[0], "real_time [s]"), time + 1) << file << ": " << lines[0];
    for (std::size_t i = 1; i < lines.size(); ++i) {
      const std::vector<double> row = numbers_of(lines[i]);
      expect_round_off(row[static_cast<std::size_t>(time) + 1], S * row[static_cast<std::size_t>(time)],
                       std::string(file) + " row " + std::to_string(i));
    }
  }

  std::ifstream summary_file(out / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(summary_file);
  EXPECT_EQ(summary.at("heat").at("time_scale_factor").get<double>(), S);
  expect_round_off(summary.at("real_time_s").get<double>(), S * summary.at("simulated_time_s").get<double>(),
                   "real_time_s");
  const nlohmann::json& stage = summary.at("stages")[0];
  expect_round_off(stage.at("duration_real_s").get<double>(), S * stage.at("duration_s").get<double>(),
                   "duration_real_s");
  expect_round_off(stage.at("end_time_real_s").get<double>(), S * stage.at("end_time_s").get<double>(),
                   "end_time_real_s");
  const nlohmann::json& history = summary.at("measurements").at("thermal_history");
  EXPECT_GT(history.at("time_above_threshold_mean_s").get<double>(), 0.0);
  expect_round_off(history.at("time_above_threshold_mean_real_s").get<double>(),
                   S * history.at("time_above_threshold_mean_s").get<double>(), "time_above_threshold_mean_real_s");
  expect_round_off(history.at("time_above_threshold_max_real_s").get<double>(),
                   S * history.at("time_above_threshold_max_s").get<double>(), "time_above_threshold_max_real_s");
  // The summary's last time-above value is the time series' last one.
  expect_round_off(history.at("time_above_threshold_mean_real_s").get<double>(),
                   last[static_cast<std::size_t>(above_real)], "summary against time series");
  const nlohmann::json& all = summary.at("measurements").at("regions").at("all").at("final");
  expect_round_off(all.at("real_time_s").get<double>(), S * all.at("time_s").get<double>(), "regions.all final");
  const nlohmann::json& axial = summary.at("measurements").at("profiles").at("axial").at("final");
  EXPECT_TRUE(axial.at("real_time_s").is_number()) << axial.dump();  // once, as time, not per bin
  fs::remove_all(directory);
}

}  // namespace
