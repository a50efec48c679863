#pragma once
// When a run takes snapshots (ParaView files): every so much simulated time, every so
// many steps, or every so much depth of a feeding wall (a drill), plus at the end of
// each stage. The stage runner asks due() once per step and tells taken() when the
// observer has written one.
#include <cmath>
#include <cstdint>
#include <limits>

namespace regodem {

struct SnapshotSchedule {
  enum class Trigger { none, time, steps, depth };
  Trigger trigger = Trigger::none;
  double interval_s = 0.0;        // Trigger::time
  std::uint64_t every_steps = 0;  // Trigger::steps: steps of any kind (mechanical or static-bed heat steps)
  double depth_interval_m = 0.0;  // Trigger::depth: of wall body depth_body (WallBody::depth_m)
  int depth_body = -1;
  bool at_stage_end = true;       // also one at the end of every stage (the final state is always there)

  bool enabled() const { return trigger != Trigger::none; }
};

/// The running state of a schedule over a run.
class SnapshotClock {
 public:
  explicit SnapshotClock(const SnapshotSchedule& schedule) : schedule_(schedule) {}

  /// Whether a snapshot is due at `time_s` (and, for a depth trigger, the wall's
  /// `depth_m`); `half_step_s` absorbs round-off in the sum of steps. The first call of
  /// a run is always due (the initial state).
  bool due(double time_s, double half_step_s, double depth_m = 0.0) const {
    if (!schedule_.enabled()) return false;
    if (!taken_any_) return true;
    if (time_s == last_time_s_) return false;  // never two at one time: ParaView would show one
    if (schedule_.trigger == SnapshotSchedule::Trigger::time) return time_s + half_step_s >= next_time_s_;
    if (schedule_.trigger == SnapshotSchedule::Trigger::depth)
      return depth_m >= next_depth_m_ - 1e-9 * schedule_.depth_interval_m;
    return steps_since_ >= schedule_.every_steps;
  }
  /// Whether the stage that just ended should add one (not already taken at this time).
  bool due_at_stage_end(double time_s) const {
    return schedule_.enabled() && schedule_.at_stage_end && (!taken_any_ || time_s != last_time_s_);
  }
  /// `half_step_s` as given to due(): a snapshot taken half a step early counts as the
  /// one due at the grid time.
  void taken(double time_s, double half_step_s, double depth_m = 0.0) {
    if (schedule_.trigger == SnapshotSchedule::Trigger::depth) {
      // On the grid of depth intervals from the first snapshot's depth.
      if (!taken_any_) next_depth_m_ = depth_m;
      const double tolerance = 1e-9 * schedule_.depth_interval_m;
      while (next_depth_m_ <= depth_m + tolerance) next_depth_m_ += schedule_.depth_interval_m;
    }
    if (schedule_.trigger == SnapshotSchedule::Trigger::time) {
      // The next one on the grid of intervals, not interval after this one: snapshots
      // at stage ends do not shift the regular ones.
      if (!taken_any_) next_time_s_ = time_s;
      while (next_time_s_ <= time_s + half_step_s) next_time_s_ += schedule_.interval_s;
    }
    taken_any_ = true;
    last_time_s_ = time_s;
    steps_since_ = 0;
  }
  void count_step() { ++steps_since_; }

  /// The running state, for checkpoints.
  struct State {
    bool taken_any = false;
    double last_time_s = 0.0, next_time_s = 0.0, next_depth_m = 0.0;
    std::uint64_t steps_since = 0;
  };
  State state() const { return {taken_any_, last_time_s_, next_time_s_, next_depth_m_, steps_since_}; }
  void restore(const State& s) {
    taken_any_ = s.taken_any;
    last_time_s_ = s.last_time_s;
    next_time_s_ = s.next_time_s;
    next_depth_m_ = s.next_depth_m;
    steps_since_ = s.steps_since;
  }

 private:
  SnapshotSchedule schedule_;
  bool taken_any_ = false;
  double last_time_s_ = std::numeric_limits<double>::quiet_NaN();
  double next_time_s_ = 0.0;
  double next_depth_m_ = 0.0;
  std::uint64_t steps_since_ = 0;
};

}  // namespace regodem
