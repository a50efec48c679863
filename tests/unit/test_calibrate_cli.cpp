// `regodem calibrate` end to end, on a scenario whose answer is known: one grain on a
// heated plate (tests/data/scenarios/calibrate/plate.yaml), whose temperature follows
// T(t) = T_w + (T_0 - T_w) exp(-2 k_w a t / (m c)). The reference is the same scenario
// at k_w = 21 W/(m K), T_w = 410 K; the calibration must find these values again from a
// central composite design around 20 W/(m K) and 400 K. Then: an interrupted
// calibration continues without running its finished runs again, to the same result;
// and a failed run is reported as such.
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/run_directory_lock.hpp"
#include "regodem_process.hpp"

namespace regodem {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::Finished;
using test::read_file;
using test::run_regodem;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::size_t occurrences(const std::string& text, const std::string& part) {
  std::size_t count = 0;
  for (auto at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++count;
  return count;
}

class CalibrateCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("regodem_calibrate_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    const fs::path data = fs::path(REGODEM_SOURCE_DIR) / "tests/data/scenarios/calibrate";
    for (const char* file : {"plate.yaml", "grain.csv", "plate_calibration.yaml"})
      fs::copy_file(data / file, dir_ / file);
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// plate_calibration.yaml with `extra` lines appended inside `calibration:` (a later
  /// key replaces nothing: YAML refuses duplicates, so only new keys go here) and its
  /// solve section replaced by `solve`.
  void write_calibration(const std::string& name, const std::string& solve, const std::string& set) const {
    std::string text = read_file(dir_ / "plate_calibration.yaml");
    const auto replace = [&](const std::string& from, const std::string& to) {
      const auto at = text.find(from);
      ASSERT_NE(at, std::string::npos) << from;
      text.replace(at, from.size(), to);
    };
    replace("  solve: {mode: simultaneous}", solve);
    replace("  set: [\"output.interval=0.2 s\"]", set);
    std::ofstream(dir_ / name) << text;
  }

  static json calibration(const fs::path& out) { return json::parse(read_file(out / "calibration.json")); }

  fs::path dir_;
};

// The fitted quadratics approximate exp(-k_w ...) over k_w ± 14 %: for the analytic
// response, a fit at these 11 points and a solve recover k_w to 6e-5 and T_w to 0.004 K
// (evaluated apart, in double precision), and stay within 3e-4 and 0.035 K when tau is
// half or twice the scenario's. The tolerances, 0.2 % and 0.2 K, leave room for that
// and for what the analytic form leaves out (heat during the settle, Crank–Nicolson),
// which reference and design share. The verification run must then reach both targets
// to within 0.05 K (the surfaces' own error there, a few mK, times ten).
TEST_F(CalibrateCli, RecoversTheReferencesFactorsAndVerifiesThem) {
  const Finished f = run_regodem({"calibrate", "plate_calibration.yaml", "-o", "out"}, dir_);
  ASSERT_EQ(f.exit_code, 0) << f.output;
  const json c = calibration(dir_ / "out");
  const json& solution = c.at("solution").at("factors");
  EXPECT_NEAR(solution.at("k_wall").get<double>(), 21.0, 0.002 * 21.0) << f.output;
  EXPECT_NEAR(solution.at("T_plate").get<double>(), 410.0, 0.2) << f.output;
  EXPECT_TRUE(c.at("solution").at("inside_design_range").get<bool>());
  for (const char* response : {"T_early", "T_late"}) {
    const json& v = c.at("verification").at("responses").at(response);
    EXPECT_NEAR(v.at("achieved").get<double>(), v.at("target").get<double>(), 0.05) << response;
    EXPECT_DOUBLE_EQ(v.at("target").get<double>(), c.at("targets").at(response).at("value").get<double>());
  }
  // The targets are the reference's own values.
  const json reference = json::parse(read_file(dir_ / "out/runs/reference/summary.json"));
  EXPECT_EQ(c.at("targets").at("T_late").at("value"),
            reference.at("measurements").at("regions").at("late").at("final").at("temperature_mean_K"));
  // Every run kept; runs.csv reads back with `regodem fit`, to the same surfaces.
  for (const char* run : {"reference", "point_01", "point_11", "verification"})
    EXPECT_TRUE(fs::exists(dir_ / "out/runs" / run / "summary.json")) << run;
  for (const char* file : {"design.csv", "runs.csv", "fit.txt", "fit.json"})
    EXPECT_TRUE(fs::exists(dir_ / "out" / file)) << file;
  const Finished fit = run_regodem(
      {"fit", "out/runs.csv", "--factors", "k_wall,T_plate", "--response", "T_early", "--json", "refit.json"}, dir_);
  ASSERT_EQ(fit.exit_code, 0) << fit.output;
  EXPECT_EQ(json::parse(read_file(dir_ / "refit.json")).at("responses")[0].at("equation"),
            json::parse(read_file(dir_ / "out/fit.json")).at("responses")[0].at("equation"));
  EXPECT_TRUE(contains(f.output, "about")) << f.output;  // the estimate of time left
  EXPECT_TRUE(contains(f.output, "[13/13] verification done")) << f.output;

  // The paper's way on the same runs: T_late for k_w with T_w held at 410 K, then
  // T_early for T_w at that k_w. Only the verification runs again (its factors moved).
  write_calibration("sequential.yaml",
                    "  solve:\n    mode: sequential\n    fix: {T_plate: 410}\n    steps:\n"
                    "      - {response: T_late, factor: k_wall}\n      - {response: T_early, factor: T_plate}",
                    "  set: [\"output.interval=0.2 s\"]");
  const Finished s = run_regodem({"calibrate", "sequential.yaml", "-o", "out"}, dir_);
  ASSERT_EQ(s.exit_code, 0) << s.output;
  EXPECT_EQ(occurrences(s.output, "already done, skipped"), 12u) << s.output;
  EXPECT_TRUE(contains(s.output, "verification: runs again: its inputs changed")) << s.output;
  const json q = calibration(dir_ / "out");
  EXPECT_EQ(q.at("solve").at("mode"), "sequential");
  EXPECT_NEAR(q.at("solution").at("factors").at("k_wall").get<double>(), 21.0, 0.002 * 21.0) << s.output;
  EXPECT_NEAR(q.at("solution").at("factors").at("T_plate").get<double>(), 410.0, 0.2) << s.output;
}

struct FileIdentity {
  ino_t inode = 0;
  std::string started_at;
  bool operator==(const FileIdentity&) const = default;
};

FileIdentity identity(const fs::path& run) {
  struct stat info {};
  ::stat((run / "summary.json").c_str(), &info);
  return {info.st_ino, json::parse(read_file(run / "summary.json")).at("started_at_utc").get<std::string>()};
}

// One run at a time, each made slower (a 0.5 s settle), so that SIGINT reaches the
// calibration while it runs: after the reference and two design points have finished.
TEST_F(CalibrateCli, InterruptedCalibrationContinuesWithoutRerunningFinishedRuns) {
  write_calibration("slow.yaml", "  solve: {mode: simultaneous}",
                    "  set: [\"output.interval=0.2 s\", \"stages.settle.duration=0.5 s\"]");
  const Finished whole = run_regodem({"calibrate", "slow.yaml", "-o", "whole", "--processes", "1"}, dir_);
  ASSERT_EQ(whole.exit_code, 0) << whole.output;

  const fs::path log = dir_ / "interrupted.log";
  const pid_t pid = test::start_regodem({"calibrate", "slow.yaml", "-o", "out", "--processes", "1"}, dir_, log);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!fs::exists(dir_ / "out/runs/point_02/summary.json") && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  // Two signals, 1 ms apart, as `timeout` sends them: the second is reported, not passed
  // on, and the running child still stops cleanly with its summary.
  ASSERT_EQ(::kill(pid, SIGINT), 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(1));
  ::kill(pid, SIGINT);
  const Finished interrupted = test::wait_for(pid, log);
  ASSERT_EQ(interrupted.exit_code, 130) << interrupted.output;
  EXPECT_TRUE(contains(interrupted.output, "Continue with: regodem calibrate slow.yaml -o")) << interrupted.output;
  EXPECT_FALSE(fs::exists(dir_ / "out/calibration.json"));
  std::vector<std::string> finished;
  for (const auto& entry : fs::directory_iterator(dir_ / "out/runs")) {
    const fs::path summary = entry.path() / "summary.json";
    if (fs::exists(summary) && json::parse(read_file(summary)).at("outcome") == "completed")
      finished.push_back(entry.path().filename().string());
  }
  ASSERT_GE(finished.size(), 3u) << interrupted.output;  // the reference, point_01, point_02 at least
  ASSERT_LT(finished.size(), 13u) << interrupted.output;
  std::vector<FileIdentity> before;
  for (const std::string& run : finished) before.push_back(identity(dir_ / "out/runs" / run));

  std::this_thread::sleep_for(std::chrono::milliseconds(1100));  // a new run would get another started_at_utc
  const Finished resumed = run_regodem({"calibrate", "slow.yaml", "-o", "out", "--processes", "1"}, dir_);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_EQ(occurrences(resumed.output, "already done, skipped"), finished.size()) << resumed.output;
  for (std::size_t i = 0; i < finished.size(); ++i) {
    EXPECT_TRUE(contains(resumed.output, finished[i] + ": already done, skipped")) << finished[i];
    EXPECT_EQ(identity(dir_ / "out/runs" / finished[i]), before[i]) << finished[i] << " ran again";
  }
  const json a = calibration(dir_ / "whole"), b = calibration(dir_ / "out");
  for (const char* key : {"targets", "solve", "solution"}) EXPECT_EQ(a.at(key), b.at(key)) << key;
  EXPECT_EQ(a.at("verification").at("responses"), b.at("verification").at("responses"));
}

// Another process holds the calibration's directory: refused before any run starts.
TEST_F(CalibrateCli, ADirectoryInUseIsRefusedNamingItsHolder) {
  const RunDirectoryLock held(dir_ / "out", "regodem calibrate other.yaml");
  const Finished f = run_regodem({"calibrate", "plate_calibration.yaml", "-o", "out"}, dir_);
  EXPECT_EQ(f.exit_code, 2) << f.output;
  EXPECT_TRUE(contains(f.output, "is in use by pid " + std::to_string(::getpid()) + " (regodem calibrate other.yaml)"))
      << f.output;
  EXPECT_FALSE(fs::exists(dir_ / "out/runs"));
}

TEST_F(CalibrateCli, FailedRunAndBadInputAreReported) {
  // A response key that the summaries lack: found in the reference's summary (its
  // target), before the design runs; the message names the calibration file's line and
  // what summary.json has instead.
  std::string text = read_file(dir_ / "plate_calibration.yaml");
  text.replace(text.find("late.final.temperature_mean_K"), 29, "late.final.temperature_mean");
  std::ofstream(dir_ / "bad_key.yaml") << text;
  const Finished bad = run_regodem({"calibrate", "bad_key.yaml", "-o", "out"}, dir_);
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_TRUE(contains(bad.output,
                       "bad_key.yaml:18:7: calibration.responses.T_late: in runs/reference/summary.json: "
                       "'measurements.regions.late.final.temperature_mean': no 'temperature_mean'"))
      << bad.output;
  EXPECT_FALSE(fs::exists(dir_ / "out/runs/point_01"));

  // A factor path the scenario does not have: refused before anything runs.
  write_calibration("bad_set.yaml", "  solve: {mode: simultaneous}", "  set: [\"walls.floor.radius=1 mm\"]");
  const Finished refused = run_regodem({"calibrate", "bad_set.yaml", "-o", "refused"}, dir_);
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_TRUE(contains(refused.output, "does not read with the calibration's --set values")) << refused.output;
  EXPECT_FALSE(fs::exists(dir_ / "refused/runs"));

  // A run that fails (gravity upwards: the grain leaves the domain): exit status 1, the
  // run named with its own message, nothing else started after it.
  write_calibration("failing.yaml", "  solve: {mode: simultaneous}",
                    "  set: [\"output.interval=0.2 s\", \"gravity=[0, 0, 100 m/s^2]\"]");
  const Finished failed = run_regodem({"calibrate", "failing.yaml", "-o", "failing"}, dir_);
  EXPECT_EQ(failed.exit_code, 1) << failed.output;
  EXPECT_FALSE(fs::exists(dir_ / "failing/runs/point_01"));
  EXPECT_TRUE(contains(failed.output, "run 'reference' failed (exit status 1): ")) << failed.output;
}

// An earlier run's summary.json that is JSON but not a run's summary (edited, or from
// something else): the run is run again, with the file and the key named, and the
// calibration goes on (here to the bad response key, found in the new summary: exit 2).
TEST_F(CalibrateCli, SummaryOfTheWrongShapeIsNamedAndTheRunRunsAgain) {
  std::string text = read_file(dir_ / "plate_calibration.yaml");
  text.replace(text.find("late.final.temperature_mean_K"), 29, "late.final.temperature_mean");
  std::ofstream(dir_ / "bad_key.yaml") << text;
  const struct {
    const char* summary;
    const char* key;
  } shapes[] = {{"[1, 2]", "'outcome'"},
                {"{\"outcome\": 1}", "'outcome' is 1"},
                {"{\"outcome\": \"completed\", \"scenario\": \"plate\"}", "'scenario.hash'"},
                {"{\"outcome\": \"completed\", \"scenario\": {\"hash\": 7}}", "'scenario.hash' is 7"}};
  int k = 0;
  for (const auto& shape : shapes) {
    SCOPED_TRACE(shape.summary);
    const std::string out = "out" + std::to_string(k++);
    fs::create_directories(dir_ / out / "runs/reference");
    std::ofstream(dir_ / out / "runs/reference/summary.json") << shape.summary;
    const Finished f = run_regodem({"calibrate", "bad_key.yaml", "-o", out}, dir_);
    EXPECT_EQ(f.exit_code, 2) << f.output;
    EXPECT_FALSE(contains(f.output, "internal error")) << f.output;
    EXPECT_TRUE(contains(f.output, "reference: runs again: " + (dir_ / out / "runs/reference/summary.json").string() + ": ")) << f.output;
    EXPECT_TRUE(contains(f.output, shape.key)) << f.output;
    EXPECT_TRUE(contains(f.output, "in runs/reference/summary.json: 'measurements.regions.late.final")) << f.output;
  }
}

}  // namespace
}  // namespace regodem
