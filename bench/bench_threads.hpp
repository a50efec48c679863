#pragma once
// The thread counts a benchmark is registered for: 1 and 2 (this project's 2-core
// machine), or the list in REGODEM_BENCH_THREADS (e.g. "1,2,4,8,16") on a larger one.
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

namespace regodem::bench {

inline std::vector<std::int64_t> bench_thread_counts() {
  std::vector<std::int64_t> counts;
  if (const char* given = std::getenv("REGODEM_BENCH_THREADS")) {
    std::stringstream list(given);
    std::string item;
    while (std::getline(list, item, ','))
      if (const long n = std::strtol(item.c_str(), nullptr, 10); n > 0) counts.push_back(n);
  }
  if (counts.empty()) counts = {1, 2};
  return counts;
}

}  // namespace regodem::bench
