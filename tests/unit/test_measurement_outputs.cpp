// End to end: `regodem run` on a tiny heated cup with every kind of measurement writes
// regions/*.csv, profiles/*.csv, the thermal-history columns of time_series.csv and the
// final values in summary.json, with sane values (between the coldest and the hottest
// boundary).
#include <unistd.h>
#include <sys/wait.h>

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
  EXPECT_NE(series[0].find("peak_temperature_max [K],crossed_threshold_fraction [-],time_above_threshold_mean [s]"),
            std::string::npos)
      << series[0];

  const std::vector<std::string> all = lines_of(out / "regions" / "all.csv");
  ASSERT_EQ(all.size(), series.size());  // sampled with the time series
  EXPECT_EQ(all[0], "time [s],temperature_mean [K],temperature_min [K],temperature_max [K],count [-],"
                    "crossed_threshold_fraction [-]");
  const std::vector<double> last = numbers_of(all.back());
  EXPECT_EQ(last[4], 8.0);
  EXPECT_GE(last[2], 77.15 - 1e-9);  // between the inserted -196 degC and the 400 K cup
  EXPECT_LE(last[3], 400.0 + 1e-9);
  EXPECT_GT(last[1], 77.15);         // the cup's floor has warmed them

  const std::vector<std::string> probe = lines_of(out / "regions" / "near_probe.csv");
  EXPECT_EQ(probe[0], "depth [m],time [s],temperature_mean [K],temperature_min [K],temperature_max [K],count [-],"
                      "crossed_threshold_fraction [-]");
  EXPECT_GE(probe.size(), 4u + 1u);  // every 0.05 mm of 0.2 mm, from 0

  const std::vector<std::string> floor = lines_of(out / "regions" / "floor.csv");
  EXPECT_EQ(floor[0], "time [s],T_in [K],T_out [K],T_d [K],count_in [-],count_out [-]");
  EXPECT_EQ(floor.size(), 1u + 3u);  // 0, 0.01, 0.02 s (the last at the stage end)

  const std::vector<std::string> axial = lines_of(out / "profiles" / "axial.csv");
  EXPECT_EQ(axial[0], "time [s],distance [m],temperature_mean [K],temperature_min [K],temperature_max [K],count [-]");
  ASSERT_EQ(axial.size(), 1u + 2u * 8u);  // two instants of eight bins
  EXPECT_NEAR(numbers_of(axial[1])[1], 0.0005, 1e-15);
  EXPECT_NEAR(numbers_of(axial[16])[0], 0.02, 1e-5);  // the step nearest 0.02 s (steps of ~1e-6 s)

  std::ifstream summary_file(out / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(summary_file);
  const nlohmann::json& m = summary.at("measurements");
  EXPECT_EQ(m.at("thermal_history").at("threshold_K"), 203.15);
  EXPECT_EQ(m.at("thermal_history").at("particles"), 8);
  EXPECT_LE(m.at("thermal_history").at("peak_temperature_max_K").get<double>(), 400.0 + 1e-9);
  EXPECT_EQ(m.at("regions").at("all").at("file"), "regions/all.csv");
  EXPECT_EQ(m.at("regions").at("all").at("final").at("count"), 8);
  EXPECT_EQ(m.at("regions").at("all").at("final").at("temperature_mean_K").get<double>(), last[1]);
  EXPECT_TRUE(m.at("bands").at("floor").at("final").contains("T_d_K"));
  EXPECT_EQ(m.at("profiles").at("axial").at("samples"), 2);
  EXPECT_EQ(m.at("profiles").at("axial").at("final").at("distance_m").size(), 8u);
  fs::remove_all(directory);
}

}  // namespace
