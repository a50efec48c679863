#include "core/temperature_curve.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace regodem {

TemperatureCurve::TemperatureCurve(double value) : value_{value} {}

TemperatureCurve::TemperatureCurve(std::vector<double> temperature_K, std::vector<double> value)
    : temperature_K_(std::move(temperature_K)), value_(std::move(value)) {
  if (temperature_K_.empty() || temperature_K_.size() != value_.size())
    throw InputError(fmt::format("a temperature table needs as many values as temperatures and at least one row "
                                 "(got {} temperatures, {} values)",
                                 temperature_K_.size(), value_.size()));
  for (std::size_t k = 0; k < temperature_K_.size(); ++k) {
    if (!std::isfinite(temperature_K_[k]) || !std::isfinite(value_[k]))
      throw InputError(fmt::format("row {} of a temperature table is not finite", k + 1));
    if (k > 0 && !(temperature_K_[k] > temperature_K_[k - 1]))
      throw InputError(fmt::format("temperatures of a table must increase: row {} has {} K after {} K", k + 1,
                                   temperature_K_[k], temperature_K_[k - 1]));
  }
  if (temperature_K_.size() == 1) temperature_K_.clear();  // one row: a constant
  // The integral from 0 K: constant value_[0] below the first row, trapezoids between rows.
  integral_at_row_.resize(temperature_K_.size());
  for (std::size_t k = 0; k < temperature_K_.size(); ++k)
    integral_at_row_[k] = k == 0 ? value_[0] * temperature_K_[0]
                                 : integral_at_row_[k - 1] + 0.5 * (value_[k] + value_[k - 1]) *
                                                                 (temperature_K_[k] - temperature_K_[k - 1]);
}

double TemperatureCurve::min_value() const { return *std::min_element(value_.begin(), value_.end()); }
double TemperatureCurve::max_value() const { return *std::max_element(value_.begin(), value_.end()); }

std::size_t TemperatureCurve::segment(double t) const {
  const auto upper = std::upper_bound(temperature_K_.begin(), temperature_K_.end(), t);
  return static_cast<std::size_t>(upper - temperature_K_.begin()) - 1;  // valid for T_0 <= t < T_last
}

double TemperatureCurve::interpolate(double t) const {
  if (t <= temperature_K_.front()) return value_.front();
  if (t >= temperature_K_.back()) return value_.back();
  const std::size_t k = segment(t);
  const double s = (t - temperature_K_[k]) / (temperature_K_[k + 1] - temperature_K_[k]);
  return value_[k] + s * (value_[k + 1] - value_[k]);
}

double TemperatureCurve::integral_from_zero(double t) const {
  if (is_constant()) return at(t) * t;
  if (t <= temperature_K_.front()) return value_.front() * t;
  if (t >= temperature_K_.back()) return integral_at_row_.back() + value_.back() * (t - temperature_K_.back());
  const std::size_t k = segment(t);
  const double dt = t - temperature_K_[k];
  const double slope = (value_[k + 1] - value_[k]) / (temperature_K_[k + 1] - temperature_K_[k]);
  return integral_at_row_[k] + value_[k] * dt + 0.5 * slope * dt * dt;
}

double TemperatureCurve::inverse_integral(double h) const {
  if (is_constant()) return h / at(0.0);
  if (h <= integral_at_row_.front()) return h / value_.front();
  if (h >= integral_at_row_.back()) return temperature_K_.back() + (h - integral_at_row_.back()) / value_.back();
  const auto upper = std::upper_bound(integral_at_row_.begin(), integral_at_row_.end(), h);
  const std::size_t k = static_cast<std::size_t>(upper - integral_at_row_.begin()) - 1;
  // Solve c_k x + slope/2 x^2 = h - H_k for x in [0, T_{k+1} - T_k]; the form
  // 2r / (c + sqrt(c^2 + 2 slope r)) avoids cancellation when the slope is small.
  const double r = h - integral_at_row_[k];
  const double slope = (value_[k + 1] - value_[k]) / (temperature_K_[k + 1] - temperature_K_[k]);
  const double c = value_[k];
  const double x = 2.0 * r / (c + std::sqrt(std::max(c * c + 2.0 * slope * r, 0.0)));
  return temperature_K_[k] + x;
}

}  // namespace regodem
