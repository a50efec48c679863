#pragma once
// Where the drilling window's checkpoint is (bench/make_drilling_window.sh), for
// bench_drilling_window and bench_drilling_window_ranks.
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace regodem::bench {

/// The steps a window times.
inline constexpr std::uint64_t kWindowSteps = 1500;

/// The checkpoint file: REGODEM_DRILLING_WINDOW, else the one make_drilling_window.sh
/// named in the cache; empty when there is none.
inline std::string window_checkpoint_path() {
  if (const char* given = std::getenv("REGODEM_DRILLING_WINDOW")) return given;
  const char* cache = std::getenv("REGODEM_BENCH_CACHE");
  const std::filesystem::path pointer =
      std::filesystem::path(cache ? cache : ".") / "drilling-window" / "window-checkpoint.txt";
  std::ifstream in(pointer);
  std::string path;
  std::getline(in, path);
  return path;
}

/// The reduced sieve model the window belongs to: REGODEM_SOURCE_DIR's, else this tree's.
inline std::string window_scenario_path(const char* this_source_dir) {
  const char* source = std::getenv("REGODEM_SOURCE_DIR");
  return std::string(source ? source : this_source_dir) + "/scenarios/paper/drill-sieve-reduced.yaml";
}

}  // namespace regodem::bench
