// summary.json: every field reads back with a JSON parser, with the names and values
// that scripts comparing runs rely on.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/summary_json_writer.hpp"

namespace regodem {
namespace {

namespace fs = std::filesystem;

class SummaryJsonWriterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = (fs::temp_directory_path() / "regodem-summary-XXXXXX").string();
    ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
    directory_ = pattern;
  }
  void TearDown() override { fs::remove_all(directory_); }

  nlohmann::json write_and_parse(const RunSummary& summary) const {
    write_summary_json(directory_ / "summary.json", summary);
    std::ifstream input(directory_ / "summary.json");
    return nlohmann::json::parse(input);
  }

  static RunSummary example() {
    RunSummary summary;
    summary.status = RunStatus::failed;
    summary.message = "particle 17 left the domain at t = 0.25 s";
    summary.particles = 1234;
    summary.steps = 9876543210ull;  // beyond 32 bits
    summary.simulated_time_s = 0.25;
    summary.wall_time_s = 93.4;
    summary.particle_steps_per_s = 2.1e7;
    summary.time_step_s = 1.5e-7;
    summary.threads = 2;
    summary.version = "0.1.0";
    summary.build_type = "Release";
    summary.compiler = "GNU 12.2.0";
    summary.started_at_utc = "2024-05-01T12:00:00Z";
    summary.scenario_name = "demo";
    summary.scenario_file = "scenarios/demo.yaml";
    summary.scenario_hash = "0123abcd";
    summary.scenario_copy = "scenario.yaml";
    summary.overrides = {"seed=7", "stages[0].duration=0.1 s"};
    StageSummary fill;
    fill.name = "fill";
    fill.result = StageResult::finished;
    fill.start_time_s = 0.0;
    fill.end_time_s = 0.1;
    fill.wall_time_s = 40.0;
    StageSummary settle;
    settle.name = "settle";
    settle.result = StageResult::failed;
    settle.start_time_s = 0.1;
    settle.end_time_s = 0.25;
    settle.message = "blow-up";
    StageSummary drill;
    drill.name = "drill";  // never started
    summary.stages = {fill, settle, drill};
    summary.notices = {"insertion 'coarse': placed 80 of 100 particles; the region is full"};
    return summary;
  }

  fs::path directory_;
};

TEST_F(SummaryJsonWriterTest, EveryFieldReadsBack) {
  const nlohmann::json json = write_and_parse(example());
  EXPECT_EQ(json.at("outcome"), "failed");
  EXPECT_EQ(json.at("message"), "particle 17 left the domain at t = 0.25 s");
  EXPECT_EQ(json.at("particles").get<std::size_t>(), 1234u);
  EXPECT_EQ(json.at("steps").get<std::uint64_t>(), 9876543210ull);
  EXPECT_EQ(json.at("simulated_time_s").get<double>(), 0.25);
  EXPECT_EQ(json.at("wall_time_s").get<double>(), 93.4);
  EXPECT_EQ(json.at("particle_steps_per_s").get<double>(), 2.1e7);
  EXPECT_EQ(json.at("time_step_s").get<double>(), 1.5e-7);
  EXPECT_EQ(json.at("threads").get<int>(), 2);
  EXPECT_EQ(json.at("version"), "0.1.0");
  EXPECT_EQ(json.at("build_type"), "Release");
  EXPECT_EQ(json.at("compiler"), "GNU 12.2.0");
  EXPECT_EQ(json.at("started_at_utc"), "2024-05-01T12:00:00Z");
  const nlohmann::json& scenario = json.at("scenario");
  EXPECT_EQ(scenario.at("name"), "demo");
  EXPECT_EQ(scenario.at("file"), "scenarios/demo.yaml");
  EXPECT_EQ(scenario.at("hash"), "0123abcd");
  EXPECT_EQ(scenario.at("copy"), "scenario.yaml");
  EXPECT_EQ(scenario.at("overrides"), nlohmann::json::array({"seed=7", "stages[0].duration=0.1 s"}));

  const nlohmann::json& stages = json.at("stages");
  ASSERT_EQ(stages.size(), 3u);
  EXPECT_EQ(stages[0].at("name"), "fill");
  EXPECT_EQ(stages[0].at("result"), "finished");
  EXPECT_EQ(stages[0].at("start_time_s").get<double>(), 0.0);
  EXPECT_EQ(stages[0].at("end_time_s").get<double>(), 0.1);
  EXPECT_EQ(stages[0].at("wall_time_s").get<double>(), 40.0);
  EXPECT_EQ(stages[1].at("result"), "failed");
  EXPECT_EQ(stages[1].at("message"), "blow-up");
  EXPECT_TRUE(stages[1].at("wall_time_s").is_null());
  EXPECT_EQ(stages[2].at("name"), "drill");
  EXPECT_EQ(stages[2].at("result"), "not started");
  EXPECT_TRUE(stages[2].at("start_time_s").is_null());
  EXPECT_TRUE(stages[2].at("end_time_s").is_null());
  EXPECT_EQ(json.at("notices"),
            nlohmann::json::array({"insertion 'coarse': placed 80 of 100 particles; the region is full"}));
}

// heat.time_scale_factor S: each simulated time has its real-time twin (x S) beside it;
// with S = 1 the twins equal the simulated times.
TEST_F(SummaryJsonWriterTest, CompressedTimesHaveRealTimeTwins) {
  RunSummary summary = example();
  summary.heat.enabled = true;
  summary.heat.time_scale_factor = 80.0;
  summary.thermal_history = ThermalHistoryFinal{203.15, 10, 4, 0.4, 250.0, 0.03, 0.1};
  const nlohmann::json json = write_and_parse(summary);
  EXPECT_EQ(json.at("heat").at("time_scale_factor").get<double>(), 80.0);
  EXPECT_EQ(json.at("simulated_time_s").get<double>(), 0.25);
  EXPECT_DOUBLE_EQ(json.at("real_time_s").get<double>(), 0.25 * 80.0);
  const nlohmann::json& stages = json.at("stages");
  EXPECT_DOUBLE_EQ(stages[1].at("start_time_real_s").get<double>(), 0.1 * 80.0);
  EXPECT_DOUBLE_EQ(stages[1].at("end_time_real_s").get<double>(), 0.25 * 80.0);
  EXPECT_DOUBLE_EQ(stages[1].at("duration_real_s").get<double>(), (0.25 - 0.1) * 80.0);
  EXPECT_TRUE(stages[2].at("duration_real_s").is_null());  // never started
  const nlohmann::json& history = json.at("measurements").at("thermal_history");
  EXPECT_EQ(history.at("time_above_threshold_mean_s").get<double>(), 0.03);
  EXPECT_DOUBLE_EQ(history.at("time_above_threshold_mean_real_s").get<double>(), 0.03 * 80.0);
  EXPECT_DOUBLE_EQ(history.at("time_above_threshold_max_real_s").get<double>(), 0.1 * 80.0);

  summary.heat.time_scale_factor = 1.0;
  const nlohmann::json real = write_and_parse(summary);
  EXPECT_EQ(real.at("real_time_s"), real.at("simulated_time_s"));
  EXPECT_EQ(real.at("stages")[0].at("duration_real_s"), real.at("stages")[0].at("duration_s"));
}

TEST_F(SummaryJsonWriterTest, OutcomeNamesAndStageResultNames) {
  EXPECT_EQ(to_string(RunStatus::completed), "completed");
  EXPECT_EQ(to_string(RunStatus::failed), "failed");
  EXPECT_EQ(to_string(RunStatus::interrupted), "interrupted");
  EXPECT_EQ(to_string(StageResult::finished), "finished");
  EXPECT_EQ(to_string(StageResult::failed), "failed");
  EXPECT_EQ(to_string(StageResult::interrupted), "interrupted");

  RunSummary summary = example();
  summary.status = RunStatus::interrupted;
  EXPECT_EQ(write_and_parse(summary).at("outcome"), "interrupted");
}

TEST_F(SummaryJsonWriterTest, NonFiniteNumbersBecomeNullAndTheFileStillParses) {
  RunSummary summary = example();
  summary.particle_steps_per_s = std::numeric_limits<double>::quiet_NaN();
  summary.stages[1].end_time_s = std::numeric_limits<double>::infinity();
  const nlohmann::json json = write_and_parse(summary);
  EXPECT_TRUE(json.at("particle_steps_per_s").is_null());
  EXPECT_TRUE(json.at("stages")[1].at("end_time_s").is_null());
}

TEST_F(SummaryJsonWriterTest, RewritingReplacesTheWholeFile) {
  RunSummary summary = example();
  write_and_parse(summary);
  summary.stages.clear();
  summary.overrides.clear();
  summary.message.clear();
  const nlohmann::json json = write_and_parse(summary);
  EXPECT_TRUE(json.at("stages").empty());
  EXPECT_TRUE(json.at("scenario").at("overrides").empty());
  EXPECT_EQ(std::distance(fs::directory_iterator(directory_), fs::directory_iterator()), 1);
}

}  // namespace
}  // namespace regodem
