// Checkpoints through the command line, with a real signal: `regodem run` gets SIGINT
// once its time series has begun, exits 130 with the command that continues it, and
// `regodem resume` ends in the very state of a run that was never stopped (time
// series, snapshots and the final checkpoint's state sections, byte for byte). A
// corrupt newest checkpoint is reported and the previous one used; a changed scenario
// is refused; a checkpoint whose contents do not fit is refused with nothing changed;
// a new scenario starts from another run's checkpoint.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/checkpoint_file.hpp"
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

class CliResume : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::folder_with_the_small_run("regodem_cli_resume"); }
  void TearDown() override { fs::remove_all(dir_); }

  /// The uninterrupted run, once per test program.
  const fs::path& full_run() {
    static fs::path full;
    static const struct RemoveAtExit {
      ~RemoveAtExit() { fs::remove_all(full); }
    } remove_at_exit;
    if (full.empty()) {
      full = fs::temp_directory_path() / ("regodem_cli_resume_full_" + std::to_string(::getpid()));
      fs::remove_all(full);
      fs::create_directories(full);
      fs::copy_file(dir_ / "small.yaml", full / "small.yaml");
      const Finished f = run_regodem({"run", "small.yaml", "-o", "out", "--threads", "1"}, full);
      EXPECT_EQ(f.exit_code, 0) << f.output;
    }
    return full;
  }

  /// The newest checkpoint of a run directory.
  static fs::path newest_checkpoint(const fs::path& run) {
    fs::path newest;
    for (const auto& e : fs::directory_iterator(run / "checkpoints"))
      if (newest.empty() || e.path().filename() > newest.filename()) newest = e.path();
    return newest;
  }

  /// Same final state: the outputs, and every state section of the last checkpoint
  /// (the outputs section holds wall-clock times, which differ).
  static void expect_same_run(const fs::path& a, const fs::path& b) {
    EXPECT_EQ(read_file(a / "time_series.csv"), read_file(b / "time_series.csv"));
    for (const char* file : {"regions/low.csv", "regions/under_press.csv", "regions/cup_band.csv", "profiles/height.csv"}) {
      EXPECT_GT(line_count(a / file), 1u) << file;  // a header and samples
      EXPECT_EQ(read_file(a / file), read_file(b / file)) << file;
    }
    const auto measurements = [](const fs::path& dir) {
      return nlohmann::json::parse(read_file(dir / "summary.json")).at("measurements").dump();
    };
    EXPECT_EQ(measurements(a), measurements(b));
    EXPECT_EQ(read_file(a / "particles.pvd"), read_file(b / "particles.pvd"));
    EXPECT_EQ(read_file(a / "walls.pvd"), read_file(b / "walls.pvd"));
    for (const auto& e : fs::directory_iterator(a / "vtk"))
      EXPECT_EQ(read_file(e.path()), read_file(b / "vtk" / e.path().filename())) << e.path().filename();
    std::size_t vtk_files = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(b / "vtk")) ++vtk_files;
    EXPECT_EQ(vtk_files, static_cast<std::size_t>(std::distance(fs::directory_iterator(a / "vtk"), fs::directory_iterator{})));
    const Checkpoint ca = read_checkpoint_file(newest_checkpoint(a)), cb = read_checkpoint_file(newest_checkpoint(b));
    for (const char* tag : {"PART", "SIMU", "NBRS", "WALL", "WTHM", "BOND", "RUNP", "MEAS"}) {
      const auto body = [&](const Checkpoint& c) {
        for (const CheckpointSection& s : c.sections())
          if (s.tag == tag) return s.body;
        return std::string("missing");
      };
      EXPECT_EQ(body(ca), body(cb)) << "section " << tag;
    }
  }

  fs::path dir_;
};

TEST_F(CliResume, SigintLeavesACheckpointAndResumeEndsAsTheUninterruptedRun) {
  const fs::path full = full_run() / "out";
  const fs::path log = dir_ / "run.log";
  const pid_t pid = start_regodem({"run", "small.yaml", "-o", "out", "--threads", "1"}, dir_, log);
  // Once the time series has its header and two rows, the run is under way.
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (line_count(dir_ / "out/time_series.csv") < 3 && std::chrono::steady_clock::now() < give_up)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  ASSERT_EQ(::kill(pid, SIGINT), 0);
  const Finished interrupted = wait_for(pid, log);
  ASSERT_EQ(interrupted.exit_code, 130) << interrupted.output;
  EXPECT_TRUE(contains(interrupted.output, "interrupted by SIGINT")) << interrupted.output;
  EXPECT_TRUE(contains(interrupted.output, "continue with: regodem resume out")) << interrupted.output;
  ASSERT_FALSE(newest_checkpoint(dir_ / "out").empty());
  EXPECT_LT(line_count(dir_ / "out/time_series.csv"), line_count(full / "time_series.csv"));

  const Finished resumed = run_regodem({"resume", "out"}, dir_);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_TRUE(contains(resumed.output, "resuming from")) << resumed.output;
  expect_same_run(full, dir_ / "out");
}

TEST_F(CliResume, CorruptNewestCheckpointIsReportedAndThePreviousUsed) {
  fs::copy(full_run() / "out", dir_ / "out", fs::copy_options::recursive);
  // The run is complete: its newest checkpoint is the end of the last stage, the one
  // before it the end of the first. Damage the newest.
  const fs::path newest = newest_checkpoint(dir_ / "out");
  std::string bytes = read_file(newest);
  bytes[bytes.size() / 2] = static_cast<char>(bytes[bytes.size() / 2] ^ 0x40);
  std::ofstream(newest, std::ios::binary | std::ios::trunc) << bytes;
  const Finished resumed = run_regodem({"resume", "out"}, dir_);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_TRUE(contains(resumed.output, newest.filename().string())) << resumed.output;
  EXPECT_TRUE(contains(resumed.output, "is corrupt")) << resumed.output;
  EXPECT_TRUE(contains(resumed.output, "resuming from the previous checkpoint")) << resumed.output;
  expect_same_run(full_run() / "out", dir_ / "out");  // the second stage again, the same
}

TEST_F(CliResume, ChangedScenarioIsRefused) {
  fs::copy(full_run() / "out", dir_ / "out", fs::copy_options::recursive);
  fs::remove(newest_checkpoint(dir_ / "out"));
  // resume reads the scenario where the run found it: change that file.
  const fs::path scenario = full_run() / "small.yaml";
  const std::string original = read_file(scenario);
  std::ofstream(scenario, std::ios::app) << "# edited\n";
  const Finished resumed = run_regodem({"resume", "out"}, dir_);
  std::ofstream(scenario, std::ios::binary | std::ios::trunc) << original;
  EXPECT_EQ(resumed.exit_code, 2) << resumed.output;
  EXPECT_TRUE(contains(resumed.output, "has changed")) << resumed.output;
}

/// Every file under `root`, by its path there, with its bytes.
std::map<std::string, std::string> files_under(const fs::path& root) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(root))
    if (e.is_regular_file()) files[fs::relative(e.path(), root).string()] = read_file(e.path());
  return files;
}

/// The body of section `tag`.
std::string& section_body(Checkpoint& checkpoint, const std::string& tag) {
  for (CheckpointSection& s : checkpoint.sections())
    if (s.tag == tag) return s.body;
  ADD_FAILURE() << "no section " << tag;
  static std::string none;
  return none;
}

void add_to_u32(std::string& bytes, std::size_t at, std::uint32_t amount) {
  std::uint32_t value;
  std::memcpy(&value, bytes.data() + at, sizeof value);
  value += amount;
  std::memcpy(bytes.data() + at, &value, sizeof value);
}

// Checkpoints whose checksum is right but whose contents do not fit (written by another
// version, or damaged before the checksum was taken): resume refuses with the reason and
// leaves every file of the run directory as it was, summary.json included.
TEST_F(CliResume, CheckpointWhoseContentsDoNotFitIsRefusedAndChangesNothing) {
  struct Damage {
    const char* what;
    void (*apply)(Checkpoint&);
    const char* reason;
  };
  const Damage damages[] = {
      {"another particle field count", [](Checkpoint& c) { add_to_u32(section_body(c, "PART"), 0, 1); },
       "particle fields"},
      {"another element size of the second particle field",
       [](Checkpoint& c) {
         // PART: u32 field count; per field a u32 element size, a u64 count, the elements.
         std::string& body = section_body(c, "PART");
         std::uint32_t element_bytes;
         std::uint64_t count;
         std::memcpy(&element_bytes, body.data() + 4, sizeof element_bytes);
         std::memcpy(&count, body.data() + 8, sizeof count);
         add_to_u32(body, 4 + 4 + 8 + element_bytes * count, 1);
       },
       "particle field 1 has"},
      {"another number of walls", [](Checkpoint& c) { add_to_u32(section_body(c, "WALL"), 0, 1); }, "wall bodies"},
  };
  for (const Damage& damage : damages) {
    SCOPED_TRACE(damage.what);
    fs::remove_all(dir_ / "out");
    fs::copy(full_run() / "out", dir_ / "out", fs::copy_options::recursive);
    fs::remove(newest_checkpoint(dir_ / "out"));  // resume from the end of the first stage
    const fs::path file = newest_checkpoint(dir_ / "out");
    Checkpoint checkpoint = read_checkpoint_file(file);
    damage.apply(checkpoint);
    write_checkpoint_file(file, checkpoint);
    const std::map<std::string, std::string> before = files_under(dir_ / "out");

    const Finished resumed = run_regodem({"resume", "out"}, dir_);
    EXPECT_EQ(resumed.exit_code, 2) << resumed.output;
    EXPECT_TRUE(contains(resumed.output, file.filename().string())) << resumed.output;
    EXPECT_TRUE(contains(resumed.output, damage.reason)) << resumed.output;
    const std::map<std::string, std::string> after = files_under(dir_ / "out");
    EXPECT_EQ(after.size(), before.size());
    for (const auto& [name, bytes] : before) {
      const auto found = after.find(name);
      EXPECT_TRUE(found != after.end() && found->second == bytes) << name << " changed";
    }
  }
}

/// Field `column` of a CSV line (no quoting in these files).
std::string csv_field(const std::string& line, int column) {
  std::size_t begin = 0;
  for (int c = 0; c < column; ++c) begin = line.find(',', begin) + 1;
  return line.substr(begin, line.find(',', begin) - begin);
}

std::vector<std::string> lines_of(const fs::path& path) {
  std::ifstream input(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(input, line);) lines.push_back(line);
  return lines;
}

TEST_F(CliResume, NewScenarioStartsFromAnotherRunsCheckpoint) {
  // The same bed under a hotter floor and without the press: initial_state names the
  // finished run's directory (its newest checkpoint).
  std::string scenario = read_file(dir_ / "small.yaml");
  scenario.replace(scenario.find("insertions:"), std::string::npos,
                   "initial_state: {checkpoint: " + (full_run() / "out").string() +
                       "}\nstages:\n  - {name: heat, duration: 0.05 s}\noutput: {interval: 0.01 s}\n");
  scenario.replace(scenario.find("temperature: 400 K"), 18, "temperature: 500 K");
  std::ofstream(dir_ / "next.yaml") << scenario;
  const Finished next = run_regodem({"run", "next.yaml", "-o", "next", "--threads", "1"}, dir_);
  ASSERT_EQ(next.exit_code, 0) << next.output;
  const std::vector<std::string> before = lines_of(full_run() / "out/time_series.csv");
  const std::vector<std::string> after = lines_of(dir_ / "next/time_series.csv");
  ASSERT_GE(after.size(), 2u);
  EXPECT_EQ(csv_field(after[1], 0), "0");  // a new run: its own clock
  for (const int column : {4, 5, 6, 7, 8, 9}) {  // after time, real_time, step, stage
    // particles, kinetic energies, potential energy, largest speed, particle contacts
    EXPECT_EQ(csv_field(after[1], column), csv_field(before.back(), column)) << "column " << column;
  }
  // The bonds came along (the counts depend on the build's floating point: compare).
  const auto intact = [](const fs::path& summary) {
    return nlohmann::json::parse(read_file(summary)).at("bonds").at("intact").get<int>();
  };
  EXPECT_GT(intact(full_run() / "out/summary.json"), 0);
  EXPECT_EQ(intact(dir_ / "next/summary.json"), intact(full_run() / "out/summary.json"));
}

TEST_F(CliResume, NoCheckpointIsABadInput) {
  fs::create_directories(dir_ / "empty");
  const Finished resumed = run_regodem({"resume", "empty"}, dir_);
  EXPECT_EQ(resumed.exit_code, 2) << resumed.output;
  EXPECT_TRUE(contains(resumed.output, "holds no checkpoint")) << resumed.output;
}

}  // namespace
}  // namespace regodem
