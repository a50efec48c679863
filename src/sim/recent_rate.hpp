#pragma once
// Steps per wall-clock second over the last stretch of a run, for the progress line's
// time left: a stage's average since its start stays high when the machine gets
// loaded later (a run that began alone and then shared its cores with builds showed
// "~300 s left" for 25 minutes, ~7x short).
#include <cstdint>
#include <deque>
#include <utility>

namespace regodem {

class RecentRate {
 public:
  /// `window_s` of wall time is averaged over.
  explicit RecentRate(double window_s = 60.0) : window_s_(window_s) {}

  /// Records that `done` steps were done at `wall_s` seconds (both increasing).
  void add(double wall_s, std::uint64_t done) {
    samples_.emplace_back(wall_s, done);
    // Keep one sample at or before the window's start, so the window is always spanned.
    while (samples_.size() > 2 && samples_[1].first <= wall_s - window_s_) samples_.pop_front();
  }

  /// Steps per second over the window; 0 before two samples.
  double steps_per_s() const {
    if (samples_.size() < 2) return 0.0;
    const auto& [first_s, first_done] = samples_.front();
    const auto& [last_s, last_done] = samples_.back();
    return last_s > first_s ? static_cast<double>(last_done - first_done) / (last_s - first_s) : 0.0;
  }

 private:
  double window_s_;
  std::deque<std::pair<double, std::uint64_t>> samples_;
};

}  // namespace regodem
