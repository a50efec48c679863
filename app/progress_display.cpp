#include "progress_display.hpp"

#include <sys/ioctl.h>
#include <unistd.h>

#include <cmath>

#include <fmt/format.h>

#include "human_format.hpp"

namespace regodem::app {
namespace {

// Redrawing faster than this only costs time; the eye cannot follow it.
constexpr double terminal_redraw_interval_s = 0.2;
constexpr const char* clear_to_end_of_line = "\x1b[K";

std::string stage_label(const StageInfo& stage) {
  return fmt::format("stage {}/{} '{}'", stage.index + 1, stage.count, stage.name);
}

std::string stage_goal(const StageInfo& stage) {
  if (stage.ends_when_settled) {
    if (std::isfinite(stage.planned_end_time_s)) {
      return fmt::format("until settled, at most to {}",
                         format_simulated_time(stage.planned_end_time_s));
    }
    return "until settled";
  }
  if (std::isfinite(stage.planned_end_time_s)) {
    return fmt::format("to {}", format_simulated_time(stage.planned_end_time_s));
  }
  return "";
}

/// The stage's start and planned end in real time, where S != 1.
std::string stage_real_times(const StageInfo& stage, const TimeScale& scale) {
  return std::isfinite(stage.planned_end_time_s)
             ? real_time_note(scale.factor, {stage.start_time_s, stage.planned_end_time_s}, " to ")
             : real_time_note(scale.factor, {stage.start_time_s});
}

std::string describe_snapshot(const ProgressSnapshot& snapshot, const TimeScale& scale) {
  const StageInfo& stage = snapshot.stage;
  std::string line = fmt::format("{}  t = {}", stage_label(stage), format_simulated_time(snapshot.time_s));
  if (!stage.ends_when_settled && std::isfinite(stage.planned_end_time_s)) {
    line += fmt::format(" / {}{}", format_simulated_time(stage.planned_end_time_s),
                        real_time_note(scale.factor, {snapshot.time_s, stage.planned_end_time_s}));
  } else {
    line += real_time_note(scale.factor, {snapshot.time_s});
  }
  line += fmt::format("  {} steps/s  {} particles", format_compact(snapshot.steps_per_s),
                      snapshot.particles);
  if (stage.ends_when_settled) {
    line += fmt::format("  KE {:.3g} J/particle", snapshot.kinetic_energy_per_particle_J);
  }
  if (snapshot.estimated_remaining_s >= 0.0) {
    line += fmt::format("  ~{} left", format_wall_duration(snapshot.estimated_remaining_s));
  }
  return line;
}

}  // namespace

ProgressDisplay::ProgressDisplay(std::FILE* stream, bool redraw_in_place, double plain_interval_s)
    : stream_(stream), redraw_in_place_(redraw_in_place), plain_interval_s_(plain_interval_s) {}

ProgressDisplay::~ProgressDisplay() { finish(); }

void ProgressDisplay::stage_started(const StageInfo& stage) {
  const std::string goal = stage_goal(stage);
  print_permanent_line(fmt::format("{} started at t = {}{}{}{}", stage_label(stage),
                                   format_simulated_time(stage.start_time_s),
                                   goal.empty() ? "" : ", runs ", goal, stage_real_times(stage, scale_)));
  // Show the first snapshot of the stage at once, then at the interval.
  last_shown_wall_s_ = -1.0;
}

void ProgressDisplay::update(const ProgressSnapshot& snapshot) {
  const double interval_s = redraw_in_place_ ? terminal_redraw_interval_s : plain_interval_s_;
  if (last_shown_wall_s_ >= 0.0 && snapshot.wall_s - last_shown_wall_s_ < interval_s) return;
  last_shown_wall_s_ = snapshot.wall_s;
  const std::string line = describe_snapshot(snapshot, scale_);
  if (redraw_in_place_) {
    redraw(line);
  } else {
    print_permanent_line(line);
  }
}

void ProgressDisplay::stage_finished(const StageInfo& stage, StageResult result) {
  std::string line = fmt::format("{} ", stage_label(stage));
  switch (result) {
    case StageResult::finished: line += "finished"; break;
    case StageResult::failed: line += "failed"; break;
    case StageResult::interrupted: line += "interrupted"; break;
  }
  print_permanent_line(line);
}

void ProgressDisplay::notice(const std::string& message) {
  print_permanent_line(fmt::format("note: {}", message));
}

void ProgressDisplay::finish() {
  if (line_drawn_) {
    fmt::print(stream_, "\r{}", clear_to_end_of_line);
    std::fflush(stream_);
    line_drawn_ = false;
  }
}

void ProgressDisplay::print_permanent_line(const std::string& line) {
  if (stream_ == nullptr) return;
  finish();
  fmt::print(stream_, "{}\n", line);
  std::fflush(stream_);
}

void ProgressDisplay::redraw(const std::string& line) {
  if (stream_ == nullptr) return;
  // A line wider than the terminal wraps, and \r then returns only to the start of
  // its last row: the display would scroll instead of redrawing.
  const int width = terminal_width();
  std::string shown = line;
  if (width > 1 && shown.size() >= static_cast<std::size_t>(width)) {
    shown.resize(static_cast<std::size_t>(width - 1));
  }
  fmt::print(stream_, "\r{}{}", shown, clear_to_end_of_line);
  std::fflush(stream_);
  line_drawn_ = true;
}

int ProgressDisplay::terminal_width() const {
  winsize size{};
  if (::ioctl(fileno(stream_), TIOCGWINSZ, &size) == 0 && size.ws_col > 0) return size.ws_col;
  return 0;
}

}  // namespace regodem::app
