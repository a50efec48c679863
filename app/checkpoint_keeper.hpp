#pragma once
// Where a run keeps its checkpoints (OUTDIR/checkpoints/checkpoint_NNNNNN.rgck, the two
// newest kept) and when it writes one: every so much wall-clock time (--checkpoint-every),
// at each stage's end and on Ctrl-C. Also the run's identity section ("RUNI": scenario,
// --set values, content hash, threads) that `regodem resume` checks before it goes on.
#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "io/checkpoint_file.hpp"

namespace regodem::app {

struct RunIdentity {
  std::string scenario_path;  // absolute
  std::vector<std::string> overrides;
  std::string content_hash;   // scenario_content_hash of the file and overrides
  int threads = 1;
};

void save_identity(Checkpoint& checkpoint, const RunIdentity& identity);
RunIdentity read_identity(const Checkpoint& checkpoint);

/// The run's checkpoint files, newest (highest number) first.
std::vector<std::filesystem::path> checkpoint_files_newest_first(const std::filesystem::path& run_directory);

class CheckpointKeeper {
 public:
  static constexpr const char* folder = "checkpoints";

  /// every_wall_s: wall-clock interval of periodic checkpoints, 0 for none. Numbering
  /// goes on after the files already in the folder (a resumed run).
  CheckpointKeeper(std::filesystem::path run_directory, double every_wall_s);

  /// Whether a periodic checkpoint is due.
  bool due() const;
  /// Writes the next checkpoint whole (temporary file, then rename), then removes all
  /// but the two newest: a crash while writing leaves the previous ones intact.
  std::filesystem::path write(const Checkpoint& checkpoint);
  /// The file written last in this session, if any.
  const std::optional<std::filesystem::path>& latest() const { return latest_; }

 private:
  using Clock = std::chrono::steady_clock;
  std::filesystem::path folder_;
  double every_wall_s_ = 0.0;
  Clock::time_point last_written_;
  unsigned next_number_ = 1;
  std::optional<std::filesystem::path> latest_;
};

}  // namespace regodem::app
