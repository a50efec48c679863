#pragma once
// The measurements a run takes besides its time series (the scenario's `measurements`
// section): region statistics, bands beside a wall (the paper's T_in, T_out, T_d) and
// temperature profiles, each on its own schedule. The schedules reuse the snapshots'
// trigger logic (SnapshotClock): every so much time, steps or depth of a drill, or at
// listed times or depths.
#include <cstddef>
#include <string>
#include <cstdint>
#include <vector>

#include "measure/measure_region.hpp"
#include "measure/temperature_profile.hpp"
#include "sim/snapshot_schedule.hpp"

namespace regodem {

struct MeasurementSchedule {
  // A periodic trigger (time, steps, depth of wall body `depth_body`), plus one at the
  // end of each stage if `at_stage_end`. With no trigger and no list: at every
  // time-series sample.
  SnapshotSchedule periodic;
  std::vector<double> at_times_s;   // increasing: on the first step at or past each
  std::vector<double> at_depths_m;  // increasing, of wall body depth_body (WallBody::depth_m)

  bool with_time_series() const { return !periodic.enabled() && at_times_s.empty() && at_depths_m.empty(); }
};

enum class MeasurementKind { region, band, profile };

struct Measurement {
  std::string name;
  MeasurementKind kind = MeasurementKind::region;
  MeasureRegion region;             // region
  MeasureRegion band_in, band_out;  // band: T_in's side and T_out's
  ProfileGeometry profile;          // profile
  int follow_body = -1;  // >= 0: the geometry moves with this wall body's translation
  int depth_body = -1;   // >= 0: this wall body's depth is a column (and may trigger samples)
  MeasurementSchedule schedule;
};

/// What a stage may wait for (`until: {measurement, quantity, rises_to | falls_to}`):
/// a region's mean, min or max temperature, or a band's T_in, T_out or T_d.
enum class MeasuredQuantity { mean, min, max, T_in, T_out, T_d };

struct MeasurementTarget {
  std::size_t measurement = 0;  // index into MeasurementPlan::items
  MeasuredQuantity quantity = MeasuredQuantity::mean;
  bool rising = true;           // ends once the value is >= value_K (falling: <=)
  double value_K = 0.0;
};

struct MeasurementPlan {
  std::vector<Measurement> items;
  bool empty() const { return items.empty(); }
};

/// Runs a schedule: SnapshotClock for the periodic triggers, the lists on their own.
class MeasurementClock {
 public:
  explicit MeasurementClock(const MeasurementSchedule& schedule)
      : schedule_(&schedule), periodic_(schedule.periodic) {}

  bool due(double time_s, double half_step_s, double depth_m) const {
    if (schedule_->periodic.enabled()) return periodic_.due(time_s, half_step_s, depth_m);
    if (!schedule_->at_times_s.empty())
      return next_ < schedule_->at_times_s.size() && time_s + half_step_s >= schedule_->at_times_s[next_];
    if (!schedule_->at_depths_m.empty())
      return next_ < schedule_->at_depths_m.size() && depth_m >= schedule_->at_depths_m[next_] * (1.0 - 1e-12);
    return false;
  }
  bool due_at_stage_end(double time_s) const { return periodic_.due_at_stage_end(time_s); }
  void taken(double time_s, double half_step_s, double depth_m) {
    periodic_.taken(time_s, half_step_s, depth_m);
    // A step past several listed instants takes one sample for all of them.
    const std::vector<double>& times = schedule_->at_times_s;
    while (next_ < times.size() && time_s + half_step_s >= times[next_]) ++next_;
    const std::vector<double>& depths = schedule_->at_depths_m;
    while (next_ < depths.size() && depth_m >= depths[next_] * (1.0 - 1e-12)) ++next_;
  }
  void count_step() { periodic_.count_step(); }

  /// The running state, for checkpoints.
  struct State {
    SnapshotClock::State periodic;
    std::uint64_t next = 0;  // the next listed time or depth
  };
  State state() const { return {periodic_.state(), next_}; }
  void restore(const State& s) {
    periodic_.restore(s.periodic);
    next_ = static_cast<std::size_t>(s.next);
  }

 private:
  const MeasurementSchedule* schedule_;
  SnapshotClock periodic_;
  std::size_t next_ = 0;
};

}  // namespace regodem
