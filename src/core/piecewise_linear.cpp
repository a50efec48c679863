#include "core/piecewise_linear.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace regodem {

PiecewiseLinear::PiecewiseLinear(std::vector<double> x, std::vector<double> y, const std::string& abscissa,
                                 const std::string& unit)
    : x_(std::move(x)), y_(std::move(y)) {
  if (x_.empty() || x_.size() != y_.size())
    throw InputError(fmt::format("a table over {} needs as many values as {} and at least one row (got {} {}, {} "
                                 "values)",
                                 abscissa, abscissa, x_.size(), abscissa, y_.size()));
  for (std::size_t k = 0; k < x_.size(); ++k) {
    if (!std::isfinite(x_[k]) || !std::isfinite(y_[k]))
      throw InputError(fmt::format("row {} of a table over {} is not finite", k + 1, abscissa));
    if (k > 0 && !(x_[k] > x_[k - 1]))
      throw InputError(fmt::format("the {} of a table must increase: row {} has {} {} after {} {}", abscissa, k + 1,
                                   x_[k], unit, x_[k - 1], unit));
  }
}

std::size_t PiecewiseLinear::segment(double x) const {
  return static_cast<std::size_t>(std::upper_bound(x_.begin(), x_.end(), x) - x_.begin()) - 1;
}

double PiecewiseLinear::at(double x) const {
  if (y_.empty()) return 0.0;
  if (x <= x_.front()) return y_.front();
  if (x >= x_.back()) return y_.back();
  const std::size_t k = segment(x);
  const double s = (x - x_[k]) / (x_[k + 1] - x_[k]);
  return y_[k] + s * (y_[k + 1] - y_[k]);
}

}  // namespace regodem
