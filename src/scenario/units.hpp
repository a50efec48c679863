#pragma once
// Quantities with units, as scenario files write them: "0.6 mm", "-196 degC", "200 rpm",
// "3000 kg/m^3", "9.81 m/s^2". A plain number is SI (kelvin for temperature, radians for
// angles). Everything inside RegoDEM is SI, so this is the only place units exist.
#include <string>
#include <string_view>

namespace regodem {

/// What a quantity measures; parse_quantity refuses a unit of another dimension.
enum class Dimension {
  dimensionless,
  length,
  area,
  volume,
  time,
  mass,
  velocity,
  acceleration,
  angle,             // radians
  angular_velocity,  // rad/s
  rate,              // 1/s: events (particles) per second
  pressure,          // also elastic moduli and stresses
  density,
  temperature,       // kelvin
  energy,
  force,
  power,
  thermal_conductivity,  // W/(m K)
  specific_heat,         // J/(kg K)
  heat_transfer_coefficient,  // W/(m^2 K)
  areal_density,              // kg/m^2
  temperature_gradient,       // K/m
  stiffness_per_area,         // N/m^3: a bond's stiffness per unit area
};

/// "a length", "an angular velocity": for error messages.
std::string dimension_description(Dimension dimension);

/// A value in the file's notation that would be accepted, e.g. "0.6 mm".
std::string_view dimension_example(Dimension dimension);

/// Parses "number [unit]" into SI. Units combine with '*', '/', spaces, '^n' and
/// parentheses ("W/(m K)", "kg/m^3", "/s"); SI prefixes n, u (µ), m, c, k, M, G apply to
/// m, g, s, K, Pa, J, N, W, Hz and rad. degC and degF stand alone and only for
/// temperatures. Throws InputError ("expected a length (e.g. 0.6 mm), got '0.6 kg',
/// which is a mass") on a wrong, unknown or malformed unit, a non-number, a non-finite
/// value or a temperature below absolute zero.
double parse_quantity(const std::string& text, Dimension expected);

}  // namespace regodem
