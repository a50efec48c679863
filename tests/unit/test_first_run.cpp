// The README's first command, as a newcomer runs it (issue 22, "The first run"): it builds
// only the `regodem` program, runs the demo, which writes ParaView snapshots, and draws its
// figures, the section among them; what `regodem plot` needs beside the program is there
// once that one target is built.
#include <unistd.h>

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "regodem_process.hpp"

namespace {

namespace fs = std::filesystem;
using regodem::test::read_file;

/// The first line of the README's first ```sh block.
std::string first_command() {
  const std::string readme = read_file(fs::path(REGODEM_SOURCE_DIR) / "README.md");
  const std::size_t block = readme.find("```sh\n");
  if (block == std::string::npos) return {};
  const std::size_t begin = block + 6;
  return readme.substr(begin, readme.find('\n', begin) - begin);
}

TEST(FirstRun, TheReadmesFirstCommandBuildsOnlyRegodemThenRunsAndPlotsTheDemo) {
  const std::string command = first_command();
  ASSERT_FALSE(command.empty()) << "no ```sh block in README.md";
  // Not every test and benchmark (167 targets, 14 minutes on two busy cores).
  const std::size_t build = command.find("cmake --build --preset release");
  ASSERT_NE(build, std::string::npos) << command;
  const std::string build_step = command.substr(build, command.find("&&", build) - build);
  EXPECT_NE((build_step + " ").find(" --target regodem "), std::string::npos) << build_step;
  const std::size_t run = command.find("build/release/regodem run scenarios/demo.yaml");
  const std::size_t plot = command.find("build/release/regodem plot out/demo --section");
  EXPECT_NE(run, std::string::npos) << command;
  ASSERT_NE(plot, std::string::npos) << command;
  EXPECT_LT(run, plot) << command;
}

TEST(FirstRun, ThePlotScriptIsBesideTheProgramOnceItIsBuilt) {
  // `regodem plot` runs regodem_plot.py from beside the executable in a build tree; CMake
  // copies it there when it configures, so building the one target is enough.
  const fs::path beside = fs::path(REGODEM_BINARY).parent_path() / "regodem_plot.py";
  ASSERT_TRUE(fs::is_regular_file(beside)) << beside;
  EXPECT_EQ(read_file(beside), read_file(fs::path(REGODEM_SOURCE_DIR) / "scripts" / "regodem_plot.py"))
      << "the copy in the build tree is stale: re-run cmake";
}

TEST(FirstRun, TheDemoWritesParaViewSnapshots) {
  const fs::path dir = fs::temp_directory_path() / ("regodem_first_run_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const regodem::test::Finished done =
      regodem::test::run_regodem({"validate", std::string(REGODEM_SOURCE_DIR) + "/scenarios/demo.yaml"}, dir);
  fs::remove_all(dir);
  ASSERT_EQ(done.exit_code, 0) << done.output;
  EXPECT_NE(done.output.find("snapshots (ParaView) every"), std::string::npos) << done.output;
}

}  // namespace
