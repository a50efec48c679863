#pragma once
// The regodem binary of this build (REGODEM_BINARY) run as a child process, as a user
// runs it, for the command-line tests: started in a folder with its output to a log,
// waited for, or signalled while it runs.
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

extern char** environ;

namespace regodem::test {

struct Finished {
  int exit_code = -1;  // 128 + signal when a signal ended it
  std::string output;  // stdout and stderr
};

inline std::string read_file(const std::filesystem::path& path) {
  std::ifstream input(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(input), std::istreambuf_iterator<char>()};
}

/// A new, empty folder `prefix`_PID in the temporary directory, holding a copy of
/// tests/data/scenarios/checkpoint_small.yaml as small.yaml: the small run the
/// command-line tests start, signal and resume.
inline std::filesystem::path folder_with_the_small_run(const std::string& prefix) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / (prefix + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::filesystem::copy_file(std::filesystem::path(REGODEM_SOURCE_DIR) / "tests/data/scenarios/checkpoint_small.yaml",
                             dir / "small.yaml");
  return dir;
}

inline std::size_t line_count(const std::filesystem::path& path) {
  const std::string text = read_file(path);
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

inline bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

/// Starts regodem with `arguments` in `directory`, stdout and stderr to `log`.
inline pid_t start_regodem(const std::vector<std::string>& arguments, const std::filesystem::path& directory,
                           const std::filesystem::path& log) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addchdir_np(&actions, directory.c_str());
  std::vector<std::string> all{REGODEM_BINARY};
  all.insert(all.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = -1;
  const int error = posix_spawn(&pid, REGODEM_BINARY, &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  EXPECT_EQ(error, 0);
  return pid;
}

inline Finished wait_for(pid_t pid, const std::filesystem::path& log) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status), read_file(log)};
}

/// Runs regodem to its end; the log is `directory`/regodem.log.
inline Finished run_regodem(const std::vector<std::string>& arguments, const std::filesystem::path& directory) {
  const std::filesystem::path log = directory / "regodem.log";
  return wait_for(start_regodem(arguments, directory, log), log);
}

}  // namespace regodem::test
