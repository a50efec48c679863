// A run under real signals and beside a second writer, through the command line:
// every SIGINT/SIGTERM of a burst (coreutils `timeout` signals the child, then its
// process group) ends with the summary and a checkpoint (a second signal used to kill
// the run outright); and while a run is live, `resume` or `run --overwrite` into its
// directory is refused with exit 2 naming the holder, the live run's files untouched.
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <string>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "regodem_process.hpp"

namespace regodem {
namespace {

namespace fs = std::filesystem;

using test::contains;
using test::Finished;
using test::line_count;
using test::read_file;
using test::run_regodem;
using test::start_regodem;
using test::wait_for;

class CliStopAndLock : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::folder_with_the_small_run("regodem_cli_stop"); }
  void TearDown() override { fs::remove_all(dir_); }

  /// A run of the small scenario made long (its second stage 100 s), under way: its
  /// time series has a header and two rows.
  pid_t start_long_run(const std::string& out, const fs::path& log) {
    const pid_t pid = start_regodem(
        {"run", "small.yaml", "-o", out, "--threads", "1", "--set", "stages.press.duration=100 s"}, dir_, log);
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (line_count(dir_ / out / "time_series.csv") < 3 && std::chrono::steady_clock::now() < give_up)
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    return pid;
  }

  fs::path dir_;
};

TEST_F(CliStopAndLock, EverySignalOfABurstEndsWithTheSummaryAndACheckpoint) {
  // Two SIGTERMs and a SIGINT, the gaps 0, 1 ms and 20 ms: with the handler reset after
  // the first, any second signal delivered on its own killed the run (exit 143).
  for (const int gap_us : {0, 1000, 20000}) {
    const std::string out = "burst_" + std::to_string(gap_us);
    const fs::path log = dir_ / (out + ".log");
    const pid_t pid = start_long_run(out, log);
    ASSERT_EQ(::kill(pid, SIGTERM), 0);
    std::this_thread::sleep_for(std::chrono::microseconds(gap_us));
    ::kill(pid, SIGTERM);
    std::this_thread::sleep_for(std::chrono::microseconds(gap_us));
    ::kill(pid, SIGINT);
    const Finished finished = wait_for(pid, log);
    EXPECT_EQ(finished.exit_code, 130) << "gap " << gap_us << " us\n" << finished.output;
    EXPECT_TRUE(contains(finished.output, "continue with: regodem resume " + out)) << finished.output;
    const nlohmann::json summary = nlohmann::json::parse(read_file(dir_ / out / "summary.json"));
    EXPECT_EQ(summary.at("outcome"), "interrupted") << "gap " << gap_us << " us";
    EXPECT_FALSE(fs::is_empty(dir_ / out / "checkpoints")) << "gap " << gap_us << " us";
  }
}

TEST_F(CliStopAndLock, ASecondWriterIsRefusedWhileARunIsLive) {
  const fs::path log = dir_ / "live.log";
  const pid_t pid = start_long_run("out", log);
  const std::string holder = "in use by pid " + std::to_string(pid) + " (regodem run small.yaml)";

  const Finished resume = run_regodem({"resume", "out"}, dir_);
  EXPECT_EQ(resume.exit_code, 2) << resume.output;
  EXPECT_TRUE(contains(resume.output, holder)) << resume.output;
  const Finished overwrite = run_regodem({"run", "small.yaml", "-o", "out", "--overwrite"}, dir_);
  EXPECT_EQ(overwrite.exit_code, 2) << overwrite.output;
  EXPECT_TRUE(contains(overwrite.output, holder)) << overwrite.output;

  ASSERT_EQ(::kill(pid, SIGINT), 0);
  const Finished live = wait_for(pid, log);
  ASSERT_EQ(live.exit_code, 130) << live.output;
  // The live run's files are its own: no NUL block or foreign rows, every row complete.
  const std::string series = read_file(dir_ / "out" / "time_series.csv");
  EXPECT_EQ(series.find('\0'), std::string::npos);
  ASSERT_FALSE(series.empty());
  EXPECT_EQ(series.back(), '\n');
  EXPECT_FALSE(fs::exists(dir_ / "out" / ".regodem-lock"));  // released at the end

  // Once it has ended, the directory is free again (a short run over it).
  const Finished later =
      run_regodem({"run", "small.yaml", "-o", "out", "--overwrite", "--threads", "1", "--set", "stages.press.duration=0.01 s"},
                  dir_);
  EXPECT_EQ(later.exit_code, 0) << later.output;
}

}  // namespace
}  // namespace regodem
