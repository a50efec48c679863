#include "thermal/time_table.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace regodem {

TimeTable::TimeTable(std::vector<double> time_s, std::vector<double> value)
    : time_s_(std::move(time_s)), value_(std::move(value)) {
  if (time_s_.empty() || time_s_.size() != value_.size())
    throw InputError(fmt::format("a time table needs as many values as times and at least one row (got {} times, "
                                 "{} values)",
                                 time_s_.size(), value_.size()));
  for (std::size_t k = 0; k < time_s_.size(); ++k) {
    if (!std::isfinite(time_s_[k]) || !std::isfinite(value_[k]))
      throw InputError(fmt::format("row {} of a time table is not finite", k + 1));
    if (k > 0 && !(time_s_[k] > time_s_[k - 1]))
      throw InputError(fmt::format("times of a table must increase: row {} has {} s after {} s", k + 1, time_s_[k],
                                   time_s_[k - 1]));
  }
}

double TimeTable::at(double t) const {
  if (value_.empty()) return 0.0;
  if (t <= time_s_.front()) return value_.front();
  if (t >= time_s_.back()) return value_.back();
  const auto upper = std::upper_bound(time_s_.begin(), time_s_.end(), t);
  const std::size_t k = static_cast<std::size_t>(upper - time_s_.begin()) - 1;
  const double s = (t - time_s_[k]) / (time_s_[k + 1] - time_s_[k]);
  return value_[k] + s * (value_[k + 1] - value_[k]);
}

}  // namespace regodem
