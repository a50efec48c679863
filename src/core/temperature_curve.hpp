#pragma once
// A material property as a function of temperature: a constant, or a table of
// (temperature, value) rows interpolated linearly and held constant outside the table.
// Regolith's specific heat roughly triples between 100 K and 350 K, so the heat
// capacity may not be taken as constant (DESIGN.md section 2, "Conduction").
//
// For specific heat the curve also gives the specific enthalpy h(T) = integral of c
// from 0 K (piecewise quadratic) and its inverse: temperatures then advance by adding
// energy, h += Q dt / m, and energy is conserved however strongly c varies.
#include <vector>

#include "core/piecewise_linear.hpp"

namespace regodem {

class TemperatureCurve {
 public:
  TemperatureCurve() : TemperatureCurve(0.0) {}
  /// A constant value.
  explicit TemperatureCurve(double value);
  /// A table; throws InputError unless temperatures strictly increase and every
  /// entry is finite. At least one row; one row is a constant.
  TemperatureCurve(std::vector<double> temperature_K, std::vector<double> value);

  bool is_constant() const { return table_.rows() <= 1; }
  /// Value at T (the constant, or the table interpolated; clamped at the ends).
  double at(double temperature_K) const { return table_.at(temperature_K); }
  const std::vector<double>& table_temperatures_K() const { return table_.xs(); }
  const std::vector<double>& table_values() const { return table_.ys(); }

  /// Integral of the curve from 0 K to T (for a specific heat: J/kg).
  double integral_from_zero(double temperature_K) const;
  /// The T at which integral_from_zero(T) == h; the curve must be positive everywhere.
  double inverse_integral(double integral) const;

 private:
  PiecewiseLinear table_;
  std::vector<double> integral_at_row_;  // integral_from_zero at each table temperature
};

}  // namespace regodem
