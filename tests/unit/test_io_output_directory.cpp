// The output directory rule: new or empty directories are used, a non-empty one is
// refused unless --overwrite, --overwrite removes only what a run writes, a run
// whose inputs are among its outputs is refused, and a directory another process holds
// locked is refused.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "io/output_directory.hpp"
#include "io/run_directory_lock.hpp"

namespace regodem {
namespace {

namespace fs = std::filesystem;

class OutputDirectoryTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = (fs::temp_directory_path() / "regodem-outdir-XXXXXX").string();
    ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
    root_ = pattern;
  }
  void TearDown() override { fs::remove_all(root_); }

  static void touch(const fs::path& path) { std::ofstream(path) << "x"; }

  fs::path root_;
  const std::vector<std::string> run_outputs_{"summary.json", "time_series.csv", "frames"};
};

TEST_F(OutputDirectoryTest, MissingDirectoryIsCreatedWithItsParents) {
  const fs::path directory = root_ / "out" / "demo";
  check_output_directory(directory, false);
  EXPECT_FALSE(fs::exists(directory));  // checking changes nothing
  prepare_output_directory(directory, false, run_outputs_);
  EXPECT_TRUE(fs::is_directory(directory));
}

TEST_F(OutputDirectoryTest, EmptyDirectoryIsUsed) {
  fs::create_directory(root_ / "empty");
  EXPECT_NO_THROW(prepare_output_directory(root_ / "empty", false, run_outputs_));
}

TEST_F(OutputDirectoryTest, NonEmptyDirectoryIsRefusedWithoutOverwrite) {
  fs::create_directory(root_ / "used");
  touch(root_ / "used" / "summary.json");
  for (const bool prepare : {false, true}) {
    try {
      if (prepare) {
        prepare_output_directory(root_ / "used", false, run_outputs_);
      } else {
        check_output_directory(root_ / "used", false);
      }
      FAIL() << "expected InputError";
    } catch (const InputError& error) {
      const std::string message = error.what();
      EXPECT_NE(message.find((root_ / "used").string()), std::string::npos) << message;
      EXPECT_NE(message.find("--overwrite"), std::string::npos) << message;
    }
  }
  EXPECT_TRUE(fs::exists(root_ / "used" / "summary.json"));
}

TEST_F(OutputDirectoryTest, OverwriteRemovesOnlyWhatARunWrites) {
  const fs::path directory = root_ / "used";
  fs::create_directories(directory / "frames");
  touch(directory / "frames" / "0001.vtp");
  touch(directory / "summary.json");
  touch(directory / "time_series.csv");
  touch(directory / "my_notes.txt");
  check_output_directory(directory, true);
  EXPECT_TRUE(fs::exists(directory / "summary.json"));  // checking changes nothing
  prepare_output_directory(directory, true, run_outputs_);
  EXPECT_FALSE(fs::exists(directory / "summary.json"));
  EXPECT_FALSE(fs::exists(directory / "time_series.csv"));
  EXPECT_FALSE(fs::exists(directory / "frames"));
  EXPECT_TRUE(fs::exists(directory / "my_notes.txt"));
}

// A user's own file inside an output folder survives --overwrite (it used to be removed
// with the folder); the folder stays, holding it.
TEST_F(OutputDirectoryTest, OverwriteKeepsAUsersFileInsideAnOutputFolder) {
  const fs::path directory = root_ / "used";
  fs::create_directories(directory / "frames");
  touch(directory / "frames" / "0001.vtp");
  touch(directory / "frames" / ".0002.vtp.tmp-17-1");  // left by a killed run
  touch(directory / "frames" / "view.pvsm");
  touch(directory / "summary.json");
  const std::vector<fs::path> kept = prepare_output_directory(directory, true, run_outputs_);
  EXPECT_FALSE(fs::exists(directory / "frames" / "0001.vtp"));
  EXPECT_FALSE(fs::exists(directory / "frames" / ".0002.vtp.tmp-17-1"));
  EXPECT_TRUE(fs::exists(directory / "frames" / "view.pvsm"));
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_EQ(kept[0].filename(), "view.pvsm");
}

TEST_F(OutputDirectoryTest, TheLockFileAloneLeavesADirectoryEmpty) {
  fs::create_directory(root_ / "locked");
  touch(root_ / "locked" / RunDirectoryLock::file_name);
  EXPECT_NO_THROW(check_output_directory(root_ / "locked", false));
}

TEST_F(OutputDirectoryTest, ALockedDirectoryIsRefusedNamingItsHolder) {
  const fs::path directory = root_ / "out" / "run";
  std::optional<RunDirectoryLock> first;
  first.emplace(directory, "regodem run first.yaml");
  EXPECT_TRUE(first->created_directory());
  try {
    RunDirectoryLock second(directory, "regodem run second.yaml");
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("in use by pid " + std::to_string(::getpid()) + " (regodem run first.yaml)"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find(directory.string()), std::string::npos) << message;
  }
  first.reset();  // released: the file goes, and the next process gets the lock
  EXPECT_FALSE(fs::exists(directory / RunDirectoryLock::file_name));
  EXPECT_NO_THROW(RunDirectoryLock(directory, "regodem run second.yaml"));
}

// A lock file left by a killed process (nobody holds its lock) does not block.
TEST_F(OutputDirectoryTest, AStaleLockFileDoesNotBlock) {
  fs::create_directory(root_ / "stale");
  std::ofstream(root_ / "stale" / RunDirectoryLock::file_name) << "pid 999999 (regodem run old.yaml)\n";
  EXPECT_NO_THROW(RunDirectoryLock(root_ / "stale", "regodem run new.yaml"));
}

TEST_F(OutputDirectoryTest, ARefusedRunRemovesTheDirectoryItsLockCreated) {
  RunDirectoryLock created(root_ / "new", "regodem run x.yaml");
  created.release_and_remove_created_directory();
  EXPECT_FALSE(fs::exists(root_ / "new"));
  fs::create_directory(root_ / "existing");
  RunDirectoryLock existing(root_ / "existing", "regodem run x.yaml");
  EXPECT_FALSE(existing.created_directory());
  existing.release_and_remove_created_directory();
  EXPECT_TRUE(fs::is_directory(root_ / "existing"));
}

TEST_F(OutputDirectoryTest, FileInTheWayIsRefused) {
  touch(root_ / "a_file");
  EXPECT_THROW(prepare_output_directory(root_ / "a_file", true, run_outputs_), InputError);
  EXPECT_THROW(prepare_output_directory(root_ / "a_file" / "below", false, run_outputs_), InputError);
}

// An input among a run's outputs is found however it is spelt: through "..", through a
// link to the output directory, or as a link that --overwrite would remove.
TEST_F(OutputDirectoryTest, InputsAmongTheOutputsAreRefusedByName) {
  const fs::path directory = root_ / "out";
  fs::create_directories(directory / "frames");
  touch(directory / "summary.json");
  touch(directory / "frames" / "bed.csv");
  touch(root_ / "scenario.yaml");
  touch(directory / "notes.csv");  // not a run's output: may be read
  fs::create_directory_symlink(directory, root_ / "link_to_out");
  fs::create_symlink(root_ / "scenario.yaml", directory / "time_series.csv");
  const auto refusal = [&](const fs::path& input) -> std::string {
    try {
      check_inputs_outside_outputs(directory, run_outputs_, {root_ / "scenario.yaml", input});
    } catch (const InputError& error) {
      return error.what();
    }
    return "";
  };
  EXPECT_EQ(refusal(directory / "notes.csv"), "");
  EXPECT_EQ(refusal(root_ / "scenario.yaml"), "");
  for (const fs::path& input : {directory / "summary.json", root_ / "out/../out/frames/bed.csv",
                                root_ / "link_to_out/summary.json", directory / "time_series.csv"}) {
    const std::string message = refusal(input);
    EXPECT_EQ(message.rfind(input.string() + ": ", 0), 0u) << input << ": " << message;
    EXPECT_NE(message.find("-o OUTDIR"), std::string::npos) << message;
  }
  EXPECT_TRUE(fs::exists(directory / "summary.json"));  // checking changes nothing
}

TEST_F(OutputDirectoryTest, DefaultDirectoryIsOutSlashAPathSafeScenarioName) {
  EXPECT_EQ(default_output_directory("demo"), fs::path("out/demo"));
  EXPECT_EQ(default_output_directory("matching-cell_W0.v2"), fs::path("out/matching-cell_W0.v2"));
  EXPECT_EQ(default_output_directory("my run/../x"), fs::path("out/my_run_.._x"));
  EXPECT_EQ(default_output_directory(".."), fs::path("out/scenario.."));
  EXPECT_EQ(default_output_directory(""), fs::path("out/scenario"));
}

}  // namespace
}  // namespace regodem
