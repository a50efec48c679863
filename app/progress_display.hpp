#pragma once
// Progress of a run on stderr. On a terminal: one status line redrawn in place.
// Otherwise (a log file, a pipe, CI): plain lines at a fixed wall-clock interval, so
// logs stay readable and small.
#include <cstdio>
#include <string>

#include "sim/run_observer.hpp"
#include "sim/time_scale.hpp"

namespace regodem::app {

class ProgressDisplay {
 public:
  /// A null `stream` shows nothing (a quiet run from Python). `redraw_in_place`: the stream is a terminal. `plain_interval_s`: wall seconds
  /// between plain lines when it is not.
  ProgressDisplay(std::FILE* stream, bool redraw_in_place, double plain_interval_s);
  ProgressDisplay(const ProgressDisplay&) = delete;
  ProgressDisplay& operator=(const ProgressDisplay&) = delete;
  ~ProgressDisplay();

  /// heat.time_scale_factor S: with S != 1 the times shown also give their real-time
  /// equivalent (x S), "t = 2.067 s (165.4 s real, S = 80)".
  void set_time_scale(TimeScale scale) { scale_ = scale; }

  void stage_started(const StageInfo& stage);
  void update(const ProgressSnapshot& snapshot);
  void stage_finished(const StageInfo& stage, StageResult result);
  /// A message for the user, kept on its own line.
  void notice(const std::string& message);
  /// Removes the in-place line so that what follows starts on a clean line.
  void finish();

 private:
  void print_permanent_line(const std::string& line);
  void redraw(const std::string& line);
  int terminal_width() const;

  std::FILE* stream_;
  TimeScale scale_;
  bool redraw_in_place_;
  double plain_interval_s_;
  double last_shown_wall_s_ = -1.0;
  bool line_drawn_ = false;
};

}  // namespace regodem::app
