// `regodem resume OUTDIR`: finds the run's newest checkpoint that reads (a corrupt or
// truncated one is reported and the one before it used), checks that the scenario is
// the one the run was started with, and runs on from there into the same OUTDIR (none
// while another process holds the directory).
#include <filesystem>

#include <fmt/format.h>

#include "checkpoint_keeper.hpp"
#include "commands.hpp"
#include "core/error.hpp"
#include "io/run_directory_lock.hpp"
#include "sim/run_checkpoint.hpp"

namespace regodem::app {

int resume_run(const ResumeOptions& options) {
  namespace fs = std::filesystem;
  const fs::path directory(options.run_directory);
  if (!fs::is_directory(directory)) {
    fmt::print(stderr, "regodem: error: '{}' is not a run's output directory\n", options.run_directory);
    return exit_status::bad_input;
  }
  try {
    // A live run there comes first: its checkpoints are still being written. The
    // continued run takes the lock for good once it has read the checkpoint.
    const RunDirectoryLock probe(directory, fmt::format("regodem resume {}", options.run_directory));
  } catch (const InputError& error) {
    fmt::print(stderr, "regodem: error: {}\n", error.what());
    return exit_status::bad_input;
  }
  const std::vector<fs::path> files = checkpoint_files_newest_first(directory);
  if (files.empty()) {
    fmt::print(stderr,
               "regodem: error: '{}' holds no checkpoint ({}/checkpoint_NNNNNN.rgck); a run writes one at the end of "
               "each stage, every --checkpoint-every and on Ctrl-C\n",
               options.run_directory, CheckpointKeeper::folder);
    return exit_status::bad_input;
  }
  ResumePoint point;
  RunIdentity identity;
  for (const fs::path& file : files) {
    try {
      point.checkpoint = read_checkpoint_file(file);
      identity = read_identity(point.checkpoint);
      point.file = file.string();
      if (run_completed(point.checkpoint) && file == files.front()) {
        fmt::print("regodem: the run in {} has completed: its last checkpoint, {}, is the end of its last stage; "
                   "nothing to resume (a new scenario can start from it with initial_state)\n",
                   options.run_directory, point.file);
        return exit_status::success;
      }
      break;
    } catch (const CheckpointError& error) {
      fmt::print(stderr, "regodem: {}\n", error.what());
      point.skipped.push_back(fmt::format("skipped an unusable checkpoint: {}", error.what()));
    }
  }
  if (point.file.empty()) {
    fmt::print(stderr, "regodem: error: no checkpoint in '{}' can be used (see above)\n", options.run_directory);
    return exit_status::bad_input;
  }
  if (!point.skipped.empty()) fmt::print(stderr, "regodem: resuming from the previous checkpoint, {}\n", point.file);

  RunOptions run;
  run.scenario_path = identity.scenario_path;
  run.overrides = identity.overrides;
  run.output_directory = options.run_directory;
  run.threads = options.threads > 0 ? options.threads : identity.threads;
  run.checkpoint_every_s = options.checkpoint_every_s;
  if (run.threads != identity.threads)
    fmt::print(stderr, "regodem: note: the run used {} threads, this resume {} (the results do not depend on it)\n",
               identity.threads, run.threads);
  if (!fs::is_regular_file(run.scenario_path)) {
    fmt::print(stderr, "regodem: error: the run's scenario '{}' is gone; the checkpoint needs it to continue\n",
               run.scenario_path);
    return exit_status::bad_input;
  }
  return continue_run(run, point);
}

}  // namespace regodem::app
