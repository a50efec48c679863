#pragma once
// A value prescribed over time: a constant, or rows (time, value) interpolated linearly
// and held at the first and last value outside the table (a fixed-temperature wall).
#include <vector>

#include "core/piecewise_linear.hpp"

namespace regodem {

class TimeTable {
 public:
  TimeTable() = default;
  explicit TimeTable(double constant) : table_({0.0}, {constant}, "times", "s") {}
  /// Throws InputError unless times strictly increase, values are finite and there is a row.
  TimeTable(std::vector<double> time_s, std::vector<double> value)
      : table_(std::move(time_s), std::move(value), "times", "s") {}

  double at(double time_s) const { return table_.at(time_s); }
  bool empty() const { return table_.empty(); }
  const std::vector<double>& times_s() const { return table_.xs(); }
  const std::vector<double>& values() const { return table_.ys(); }

 private:
  PiecewiseLinear table_;
};

}  // namespace regodem
