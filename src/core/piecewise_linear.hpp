#pragma once
// y(x) given by rows (x_k, y_k): linear between rows, held at the first and last value
// outside them. The one table behind properties over temperature (TemperatureCurve)
// and values over time (TimeTable).
#include <cstddef>
#include <string>
#include <vector>

namespace regodem {

class PiecewiseLinear {
 public:
  PiecewiseLinear() = default;
  /// Throws InputError unless there is a row, as many ys as xs, every entry finite and
  /// the xs strictly increasing; `abscissa` and `unit` name the xs in messages
  /// ("temperatures", "K").
  PiecewiseLinear(std::vector<double> x, std::vector<double> y, const std::string& abscissa,
                  const std::string& unit);

  bool empty() const { return y_.empty(); }
  std::size_t rows() const { return y_.size(); }
  double at(double x) const;
  /// Index k of the row with x_k <= x < x_{k+1}; valid for x_0 <= x < x_last.
  std::size_t segment(double x) const;
  const std::vector<double>& xs() const { return x_; }
  const std::vector<double>& ys() const { return y_; }

 private:
  std::vector<double> x_, y_;
};

}  // namespace regodem
