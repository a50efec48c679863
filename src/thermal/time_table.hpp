#pragma once
// A value prescribed over time: a constant, or rows (time, value) interpolated linearly
// and held at the first and last value outside the table (a fixed-temperature wall).
#include <vector>

namespace regodem {

class TimeTable {
 public:
  TimeTable() = default;
  explicit TimeTable(double constant) : time_s_{0.0}, value_{constant} {}
  /// Throws InputError unless times strictly increase, values are finite and there is a row.
  TimeTable(std::vector<double> time_s, std::vector<double> value);

  double at(double time_s) const;
  bool empty() const { return value_.empty(); }
  const std::vector<double>& times_s() const { return time_s_; }
  const std::vector<double>& values() const { return value_; }

 private:
  std::vector<double> time_s_;
  std::vector<double> value_;
};

}  // namespace regodem
