#include "core/temperature_curve.hpp"

#include <algorithm>
#include <cmath>

namespace regodem {

TemperatureCurve::TemperatureCurve(double value) : table_({0.0}, {value}, "temperatures", "K") {}

TemperatureCurve::TemperatureCurve(std::vector<double> temperature_K, std::vector<double> value)
    : table_(std::move(temperature_K), std::move(value), "temperatures", "K") {
  // The integral from 0 K: the first value below the first row, trapezoids between rows.
  const std::vector<double>& t = table_.xs();
  const std::vector<double>& c = table_.ys();
  integral_at_row_.resize(t.size());
  for (std::size_t k = 0; k < t.size(); ++k)
    integral_at_row_[k] =
        k == 0 ? c[0] * t[0] : integral_at_row_[k - 1] + 0.5 * (c[k] + c[k - 1]) * (t[k] - t[k - 1]);
}

double TemperatureCurve::integral_from_zero(double temperature) const {
  const std::vector<double>& t = table_.xs();
  const std::vector<double>& c = table_.ys();
  if (is_constant()) return c[0] * temperature;
  if (temperature <= t.front()) return c.front() * temperature;
  if (temperature >= t.back()) return integral_at_row_.back() + c.back() * (temperature - t.back());
  const std::size_t k = table_.segment(temperature);
  const double dt = temperature - t[k];
  const double slope = (c[k + 1] - c[k]) / (t[k + 1] - t[k]);
  return integral_at_row_[k] + c[k] * dt + 0.5 * slope * dt * dt;
}

double TemperatureCurve::inverse_integral(double h) const {
  const std::vector<double>& t = table_.xs();
  const std::vector<double>& c = table_.ys();
  if (is_constant()) return h / c[0];
  if (h <= integral_at_row_.front()) return h / c.front();
  if (h >= integral_at_row_.back()) return t.back() + (h - integral_at_row_.back()) / c.back();
  const auto upper = std::upper_bound(integral_at_row_.begin(), integral_at_row_.end(), h);
  const std::size_t k = static_cast<std::size_t>(upper - integral_at_row_.begin()) - 1;
  // Solve c_k x + slope/2 x^2 = h - H_k for x in [0, T_{k+1} - T_k]; the form
  // 2r / (c + sqrt(c^2 + 2 slope r)) avoids cancellation when the slope is small.
  const double r = h - integral_at_row_[k];
  const double slope = (c[k + 1] - c[k]) / (t[k + 1] - t[k]);
  const double x = 2.0 * r / (c[k] + std::sqrt(std::max(c[k] * c[k] + 2.0 * slope * r, 0.0)));
  return t[k] + x;
}

}  // namespace regodem
