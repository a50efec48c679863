// Key paths into summary.json (src/io/json_path.hpp), as `regodem calibrate` reads its
// responses: stages by name or index, nested keys with units in their names, and
// messages that say what is there when a key is not.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/error.hpp"
#include "io/json_path.hpp"
#include "io/summary_json_writer.hpp"

namespace regodem {
namespace {

/// A summary as the run writes it (summary_to_json), with two stages and a band.
nlohmann::ordered_json example_summary() {
  RunSummary summary;
  summary.status = RunStatus::completed;
  summary.simulated_time_s = 2.02;
  summary.stages.push_back({"settle", StageResult::finished, 0.0, 0.02, 0.5, ""});
  summary.stages.push_back({"heat", StageResult::finished, 0.02, 2.02, 0.1, ""});
  MeasurementFinal band;
  band.table.kind = "band";
  band.table.name = "sieve";
  band.table.columns = {{"time", "s"}, {"T_in", "K"}, {"T_out", "K"}, {"T_d", "K"}, {"count_in", "-"}};
  band.file = "regions/sieve.csv";
  band.samples = 3;
  band.last_rows = {{2.02, 446.8, 354.4, 92.4, 12.0}};
  summary.measurements.push_back(band);
  MeasurementFinal empty_region;
  empty_region.table.kind = "region";
  empty_region.table.name = "empty";
  empty_region.table.columns = {{"time", "s"}, {"temperature_mean", "K"}};
  empty_region.last_rows = {{2.02, std::nan("")}};
  summary.measurements.push_back(empty_region);
  return summary_to_json(summary);
}

std::string problem(const nlohmann::ordered_json& root, const std::string& path) {
  try {
    json_number_at_path(root, path);
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

TEST(JsonPath, StagesByNameOrIndexAndNestedKeysWithUnits) {
  const auto summary = example_summary();
  EXPECT_EQ(json_number_at_path(summary, "stages.heat.end_time_s"), 2.02);
  EXPECT_EQ(json_number_at_path(summary, "stages.settle.end_time_s"), 0.02);
  EXPECT_EQ(json_number_at_path(summary, "stages.1.start_time_s"), 0.02);
  EXPECT_EQ(json_number_at_path(summary, "stages[1].start_time_s"), 0.02);
  EXPECT_EQ(json_number_at_path(summary, "measurements.bands.sieve.final.T_d_K"), 92.4);
  EXPECT_EQ(json_number_at_path(summary, "measurements.bands.sieve.final.T_in_K"), 446.8);
  EXPECT_EQ(json_number_at_path(summary, "measurements.bands.sieve.final.count_in"), 12.0);
  EXPECT_EQ(json_number_at_path(summary, "simulated_time_s"), 2.02);
  EXPECT_EQ(json_at_path(summary, "outcome"), "completed");
  EXPECT_EQ(json_at_path(summary, "stages.heat.result"), "finished");
}

TEST(JsonPath, MessagesSayWhatIsThere) {
  const auto summary = example_summary();
  const auto contains = [](const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
  };
  std::string message = problem(summary, "stages.cool.end_time_s");
  EXPECT_TRUE(contains(message, "no 'cool' in 'stages', which has the elements settle, heat")) << message;
  message = problem(summary, "measurements.bands.sieve.final.T_d");
  EXPECT_TRUE(contains(message, "no 'T_d' in 'measurements.bands.sieve.final', which has the keys time_s, T_in_K"))
      << message;
  message = problem(summary, "stages.7.end_time_s");
  EXPECT_TRUE(contains(message, "no '7' in 'stages'")) << message;
  message = problem(summary, "outcome.x");
  EXPECT_TRUE(contains(message, "'outcome' is a value, not an object or a list")) << message;
  message = problem(summary, "measurements.regions.empty.final.temperature_mean_K");
  EXPECT_TRUE(contains(message, "is null")) << message;
  message = problem(summary, "stages.heat");
  EXPECT_TRUE(contains(message, "is not a number")) << message;
  message = problem(summary, "stages..x");
  EXPECT_TRUE(contains(message, "no '' in 'stages'")) << message;
}

}  // namespace
}  // namespace regodem
