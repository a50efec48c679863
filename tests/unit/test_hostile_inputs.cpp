// The catalogue of hostile inputs, tests/data/hostile/cases.yaml: every case runs the
// real binary in a scratch copy of that folder, as a user would, and must end with its
// stated exit status and message, never in an internal error, a traceback or a signal.
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "regodem_process.hpp"

namespace regodem {
namespace {

namespace fs = std::filesystem;

using test::contains;

TEST(HostileInputs, EveryCaseEndsWithItsExitStatusAndMessage) {
  const fs::path source = fs::path(REGODEM_SOURCE_DIR) / "tests/data/hostile";
  const fs::path scratch = fs::temp_directory_path() / ("regodem_hostile_" + std::to_string(::getpid()));
  fs::remove_all(scratch);
  fs::copy(source, scratch, fs::copy_options::recursive);
  const YAML::Node cases = YAML::LoadFile((source / "cases.yaml").string());
  ASSERT_GE(cases.size(), 20u);
  for (const YAML::Node& c : cases) {
    const std::string name = c["name"].as<std::string>();
    const std::vector<std::string> arguments = c["args"].as<std::vector<std::string>>();
    const test::Finished finished = test::run_regodem(arguments, scratch);
    SCOPED_TRACE(name);
    EXPECT_EQ(finished.exit_code, c["exit"].as<int>()) << finished.output;
    EXPECT_TRUE(contains(finished.output, c["message"].as<std::string>())) << finished.output;
    if (c["absent"]) {
      for (const std::string& absent : c["absent"].as<std::vector<std::string>>()) {
        EXPECT_FALSE(contains(finished.output, absent)) << "'" << absent << "' in\n" << finished.output;
      }
    }
    EXPECT_FALSE(contains(finished.output, "internal error")) << finished.output;
    EXPECT_FALSE(contains(finished.output, "Traceback")) << finished.output;
  }
  fs::remove_all(scratch);
}

}  // namespace
}  // namespace regodem
