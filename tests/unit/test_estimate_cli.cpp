// `regodem estimate` run as a user runs it: a table with a total, the JSON file, and
// bad input refused with exit status 2.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "regodem_process.hpp"

namespace regodem::test {
namespace {

namespace fs = std::filesystem;

fs::path fresh_directory(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("regodem-estimate-cli-" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

const std::string kDemo = std::string(REGODEM_SOURCE_DIR) + "/scenarios/demo.yaml";

TEST(EstimateCli, DemoPrintsATotalAndWritesJson) {
  const fs::path dir = fresh_directory("demo");
  const Finished done = run_regodem(
      {"estimate", kDemo, "--threads", "1", "--sample-steps", "20", "--sample-seconds", "1", "--json", "estimate.json"},
      dir);
  ASSERT_EQ(done.exit_code, 0) << done.output;
  EXPECT_NE(done.output.find("total: "), std::string::npos) << done.output;
  EXPECT_NE(done.output.find("machine: "), std::string::npos) << done.output;
  EXPECT_NE(done.output.find("estimate: stage 1/3 'fill'"), std::string::npos) << done.output;  // progress

  const nlohmann::json json = nlohmann::json::parse(read_file(dir / "estimate.json"));
  ASSERT_EQ(json.at("stages").size(), 3u);
  EXPECT_EQ(json["stages"][0]["name"], "fill");
  EXPECT_EQ(json["stages"][0]["particles"], 1560);  // 1500 fine + 60 coarse
  EXPECT_EQ(json["stages"][1]["steps_basis"], "upper_bound");  // until settled, max_duration 2 s
  EXPECT_TRUE(json["stages"][2]["static_bed"].get<bool>());
  EXPECT_GT(json["stages"][2]["step_s"].get<double>(), 0.0);  // from the sampled bed's stability limit
  EXPECT_TRUE(json["total"]["upper_bound"].get<bool>());
  EXPECT_GT(json["total"]["predicted_wall_s"].get<double>(), 0.0);
  EXPECT_GT(json["total"]["peak_resident_bytes"].get<double>(), 0.0);
  EXPECT_EQ(json["machine"]["threads"], 1);
}

// --ranks projects the run onto MPI ranks (src/parallel/rank_cost_model.hpp): one rank is
// the one process's prediction; two share the bed across one cut, each with the other's
// nearest grains as ghosts.
TEST(EstimateCli, RanksProjectTheRunOntoBricks) {
  const fs::path dir = fresh_directory("ranks");
  const Finished done = run_regodem({"estimate", kDemo, "--threads", "1", "--sample-steps", "20", "--sample-seconds",
                                     "1", "--ranks", "1,2", "--json", "r.json"},
                                    dir);
  ASSERT_EQ(done.exit_code, 0) << done.output;
  EXPECT_NE(done.output.find("total on 2 ranks: "), std::string::npos) << done.output;
  const nlohmann::json json = nlohmann::json::parse(read_file(dir / "r.json"));
  const nlohmann::json& fill = json["stages"][0];
  ASSERT_EQ(fill["over_ranks"].size(), 2u);
  const nlohmann::json& one = fill["over_ranks"][0];
  const nlohmann::json& two = fill["over_ranks"][1];
  EXPECT_EQ(one["ranks"], 1);
  EXPECT_NEAR(one["predicted_wall_s"].get<double>(), fill["predicted_wall_s"].get<double>(),
              1e-12 * fill["predicted_wall_s"].get<double>());
  EXPECT_EQ(one["ghosts"].get<double>(), 0.0);
  EXPECT_EQ(two["partners"], 1);
  EXPECT_GT(two["ghosts"].get<double>(), 0.0);
  EXPECT_NEAR(two["own_particles"].get<double>(), 780.0, 0.1 * 780.0);  // half the 1,560
  EXPECT_GT(two["efficiency"].get<double>(), 0.0);
  EXPECT_LT(two["efficiency"].get<double>(), 1.0);
  // Every 10th of the 25 samples (every 0.01 s of the 0.25 s fill), the end, and the two
  // pours' attempts.
  EXPECT_GT(two["gathers_at_most"].get<int>(), 26);
  ASSERT_EQ(json["total"]["over_ranks"].size(), 2u);
  EXPECT_EQ(json["network"]["latency_s"].get<double>(), 2e-6);
}

// The drill feeds during its stage: it is timed at three times, in the bed, with the
// grains in its way taken out.
TEST(EstimateCli, DrillStageIsTimedWithTheDrillInTheBed) {
  const fs::path dir = fresh_directory("drill");
  const std::string scenario = std::string(REGODEM_SOURCE_DIR) + "/scenarios/drill-small.yaml";
  const Finished done = run_regodem(
      {"estimate", scenario, "--threads", "1", "--sample-steps", "9", "--sample-seconds", "1", "--json", "d.json"}, dir);
  ASSERT_EQ(done.exit_code, 0) << done.output;
  const nlohmann::json json = nlohmann::json::parse(read_file(dir / "d.json"));
  ASSERT_EQ(json.at("stages").size(), 3u);
  const nlohmann::json& drill = json["stages"][2];
  EXPECT_EQ(drill["end"], "depth");
  EXPECT_EQ(drill["steps_basis"], "exact");
  // 18 mm at 20 mm/s from the stage's start at 0.15 s (when the feed starts) = 0.9 s.
  EXPECT_NEAR(drill["simulated_time_s"].get<double>(), 0.9, 1e-9);
  EXPECT_EQ(drill["particles"], 2500);
  EXPECT_LT(drill["sample_particles"].get<int>(), 2500);  // the hole
  EXPECT_NE(drill["note"].get<std::string>().find("walls move"), std::string::npos);
  EXPECT_TRUE(json["total"]["complete"].get<bool>());
  EXPECT_FALSE(json["total"]["upper_bound"].get<bool>());
}

TEST(EstimateCli, BadInputIsRefusedWithExitStatus2) {
  const fs::path dir = fresh_directory("bad");
  const Finished bad_value = run_regodem({"estimate", kDemo, "--set", "stages.fill.duration=soon"}, dir);
  EXPECT_EQ(bad_value.exit_code, 2) << bad_value.output;
  EXPECT_NE(bad_value.output.find("regodem: error:"), std::string::npos) << bad_value.output;

  const Finished bad_form = run_regodem({"estimate", kDemo, "--set", "no-equals-sign"}, dir);
  EXPECT_EQ(bad_form.exit_code, 2) << bad_form.output;

  const Finished bad_fraction = run_regodem({"estimate", kDemo, "--solid-fraction", "0.9"}, dir);
  EXPECT_EQ(bad_fraction.exit_code, 2) << bad_fraction.output;

  const Finished no_folder = run_regodem({"estimate", kDemo, "--json", "missing/estimate.json"}, dir);
  EXPECT_EQ(no_folder.exit_code, 2) << no_folder.output;
}

}  // namespace
}  // namespace regodem::test
