// `regodem resume OUTDIR`: finds the run's newest checkpoint that reads (a corrupt or
// truncated one is reported and the one before it used), checks that the scenario is
// the one the run was started with, and runs on from there into the same OUTDIR (none
// while another process holds the directory).
#include <filesystem>
#include <functional>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "checkpoint_keeper.hpp"
#include "commands.hpp"
#include "core/error.hpp"
#include "io/run_directory_lock.hpp"
#include "run_ranks.hpp"
#include "sim/run_checkpoint.hpp"

namespace regodem::app {

ResumeChoice choose_resume(const ResumeOptions& options, const std::function<void(const std::string&)>& note) {
  std::vector<std::string> reasons;  // why checkpoints could not be used
  const auto tell = [&](const std::string& text) {
    if (note) note(text);
  };
  namespace fs = std::filesystem;
  const fs::path directory(options.run_directory);
  if (!fs::is_directory(directory))
    throw InputError(fmt::format("'{}' is not a run's output directory", options.run_directory));
  if (launcher_rank() == 0) {  // under mpirun, rank 0 stands for all
    // A live run there comes first: its checkpoints are still being written. The
    // continued run takes the lock for good once it has read the checkpoint.
    const RunDirectoryLock probe(directory, fmt::format("regodem resume {}", options.run_directory));
  }
  const std::vector<fs::path> files = checkpoint_files_newest_first(directory);
  if (files.empty())
    throw InputError(fmt::format(
        "'{}' holds no checkpoint ({}/checkpoint_NNNNNN.rgck); a run writes one at the end of each stage, every "
        "--checkpoint-every and on Ctrl-C",
        options.run_directory, CheckpointKeeper::folder));
  ResumeChoice choice;
  ResumePoint& point = choice.point;
  RunIdentity identity;
  for (const fs::path& file : files) {
    try {
      point.checkpoint = read_checkpoint_file(file);
      identity = read_identity(point.checkpoint);
      point.file = file.string();
      if (run_completed(point.checkpoint) && file == files.front()) {
        choice.completed = true;
        choice.completed_message = fmt::format(
            "the run in {} has completed: its last checkpoint, {}, is the end of its last stage; nothing to resume (a "
            "new scenario can start from it with initial_state)",
            options.run_directory, point.file);
        return choice;
      }
      break;
    } catch (const CheckpointError& error) {
      tell(error.what());
      reasons.emplace_back(error.what());
      point.skipped.push_back(fmt::format("skipped an unusable checkpoint: {}", error.what()));
    }
  }
  if (point.file.empty())
    throw InputError(note ? fmt::format("no checkpoint in '{}' can be used (see above)", options.run_directory)
                          : fmt::format("no checkpoint in '{}' can be used: {}", options.run_directory,
                                        fmt::join(reasons, "; ")));
  if (!point.skipped.empty()) tell(fmt::format("resuming from the previous checkpoint, {}", point.file));

  RunOptions& run = choice.run;
  run.scenario_path = identity.scenario_path;
  run.overrides = identity.overrides;
  run.output_directory = options.run_directory;
  run.threads = options.threads > 0 ? options.threads : identity.threads;
  run.checkpoint_every_s = options.checkpoint_every_s;
  if (run.threads != identity.threads)
    tell(fmt::format("note: the run used {} threads, this resume {} (the results do not depend on it)",
                     identity.threads, run.threads));
  if (!fs::is_regular_file(run.scenario_path))
    throw InputError(
        fmt::format("the run's scenario '{}' is gone; the checkpoint needs it to continue", run.scenario_path));
  return choice;
}

int resume_run(const ResumeOptions& options) {
  ResumeChoice choice;
  try {
    choice = choose_resume(options, [](const std::string& text) {
      if (launcher_rank() == 0) fmt::print(stderr, "regodem: {}\n", text);
    });
  } catch (const InputError& error) {
    if (launcher_rank() == 0) fmt::print(stderr, "regodem: error: {}\n", error.what());
    return exit_status::bad_input;
  }
  if (choice.completed) {
    if (launcher_rank() == 0) fmt::print("regodem: {}\n", choice.completed_message);
    return exit_status::success;
  }
  return continue_run(choice.run, choice.point);
}

}  // namespace regodem::app
