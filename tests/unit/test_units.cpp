// Quantities with units: every unit the scenario format documents, whitespace and
// exponent forms, and the errors for wrong, unknown or malformed units.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "core/error.hpp"
#include "scenario/units.hpp"

namespace regodem {
namespace {

constexpr double kPi = std::numbers::pi;

// Conversions multiply a few doubles: a relative tolerance of 1e-12 is round-off.
void expect_si(const std::string& text, Dimension dimension, double expected_si) {
  SCOPED_TRACE(text);
  const double parsed = parse_quantity(text, dimension);
  EXPECT_NEAR(parsed, expected_si, 1e-12 * std::abs(expected_si)) << text;
}

std::string error_of(const std::string& text, Dimension dimension) {
  try {
    const double value = parse_quantity(text, dimension);
    return "no error; parsed " + std::to_string(value);
  } catch (const InputError& error) {
    return error.what();
  }
}

TEST(Units, PlainNumbersAreSi) {
  expect_si("0.0006", Dimension::length, 0.0006);
  expect_si("3000", Dimension::density, 3000.0);
  expect_si("77", Dimension::temperature, 77.0);  // kelvin
  expect_si("0.5", Dimension::angle, 0.5);        // radians
  expect_si("20.9", Dimension::angular_velocity, 20.9);
  expect_si("0.25", Dimension::dimensionless, 0.25);
}

TEST(Units, Lengths) {
  expect_si("0.6 mm", Dimension::length, 0.6e-3);
  expect_si("2 cm", Dimension::length, 0.02);
  expect_si("1.5 m", Dimension::length, 1.5);
  expect_si("3 km", Dimension::length, 3000.0);
  expect_si("50 um", Dimension::length, 50e-6);
  expect_si("50 \u00b5m", Dimension::length, 50e-6);  // micro sign
  expect_si("50 \u03bcm", Dimension::length, 50e-6);  // Greek mu
  expect_si("200 nm", Dimension::length, 200e-9);
}

TEST(Units, Times) {
  expect_si("1e-3 s", Dimension::time, 1e-3);
  expect_si("10 ms", Dimension::time, 0.01);
  expect_si("5 us", Dimension::time, 5e-6);
  expect_si("5 min", Dimension::time, 300.0);
  expect_si("1 h", Dimension::time, 3600.0);
}

TEST(Units, MassesAndDensities) {
  expect_si("2 kg", Dimension::mass, 2.0);
  expect_si("2 g", Dimension::mass, 2e-3);
  expect_si("3 mg", Dimension::mass, 3e-6);
  expect_si("3000 kg/m^3", Dimension::density, 3000.0);
  expect_si("2.5 g/cm^3", Dimension::density, 2500.0);
}

TEST(Units, VelocitiesAndAccelerations) {
  expect_si("0.5 mm/s", Dimension::velocity, 0.5e-3);
  expect_si("3 m/s", Dimension::velocity, 3.0);
  expect_si("9.81 m/s^2", Dimension::acceleration, 9.81);
  expect_si("-1.62 m/s^2", Dimension::acceleration, -1.62);
}

TEST(Units, AnglesAndAngularVelocities) {
  expect_si("30 deg", Dimension::angle, kPi / 6.0);
  expect_si("30\u00b0", Dimension::angle, kPi / 6.0);
  expect_si("2 rad", Dimension::angle, 2.0);
  expect_si("0.5 rev", Dimension::angle, kPi);
  expect_si("200 rpm", Dimension::angular_velocity, 200.0 * 2.0 * kPi / 60.0);
  expect_si("3 rad/s", Dimension::angular_velocity, 3.0);
  expect_si("90 deg/s", Dimension::angular_velocity, kPi / 2.0);
}

TEST(Units, PressuresAndModuli) {
  expect_si("3e9 Pa", Dimension::pressure, 3e9);
  expect_si("3 GPa", Dimension::pressure, 3e9);
  expect_si("120 MPa", Dimension::pressure, 1.2e8);
  expect_si("101.3 kPa", Dimension::pressure, 101300.0);
  expect_si("1 N/m^2", Dimension::pressure, 1.0);
}

TEST(Units, Temperatures) {
  expect_si("77 K", Dimension::temperature, 77.0);
  expect_si("-196 degC", Dimension::temperature, 77.15);
  expect_si("700 \u00b0C", Dimension::temperature, 973.15);
  expect_si("32 degF", Dimension::temperature, 273.15);
  expect_si("500 mK", Dimension::temperature, 0.5);
}

TEST(Units, EnergyForcePowerAndThermalProperties) {
  expect_si("1 J", Dimension::energy, 1.0);
  expect_si("1 mJ", Dimension::energy, 1e-3);
  expect_si("1e-12 J", Dimension::energy, 1e-12);
  expect_si("2 N", Dimension::force, 2.0);
  expect_si("3 kN", Dimension::force, 3000.0);
  expect_si("1 kg m/s^2", Dimension::force, 1.0);
  expect_si("5 W", Dimension::power, 5.0);
  expect_si("14.76 W/m/K", Dimension::thermal_conductivity, 14.76);
  expect_si("14.76 W/(m K)", Dimension::thermal_conductivity, 14.76);
  expect_si("14.76 W/(m*K)", Dimension::thermal_conductivity, 14.76);
  expect_si("800 J/(kg K)", Dimension::specific_heat, 800.0);
  expect_si("0.8 kJ/(kg K)", Dimension::specific_heat, 800.0);
}

TEST(Units, HeatTransferCoefficientArealDensityAndTemperatureGradient) {
  expect_si("5e4 W/(m^2 K)", Dimension::heat_transfer_coefficient, 5e4);
  expect_si("5 kW/m^2/K", Dimension::heat_transfer_coefficient, 5e3);
  expect_si("7.8 kg/m^2", Dimension::areal_density, 7.8);
  expect_si("0.78 g/cm^2", Dimension::areal_density, 7.8);
  expect_si("-50 K/m", Dimension::temperature_gradient, -50.0);
  expect_si("2 K/mm", Dimension::temperature_gradient, 2000.0);
  // A gradient is a difference per length: no absolute-zero check, and degC stays alone.
  EXPECT_NE(error_of("2 degC/mm", Dimension::temperature_gradient).find("can only stand alone"),
            std::string::npos);
  EXPECT_NE(error_of("14.76 W/(m K)", Dimension::heat_transfer_coefficient)
                .find("which is a thermal conductivity"),
            std::string::npos);
}

TEST(Units, RatesAndPercentages) {
  expect_si("20000 /s", Dimension::rate, 20000.0);
  expect_si("20000/s", Dimension::rate, 20000.0);
  expect_si("50 1/s", Dimension::rate, 50.0);
  expect_si("10 Hz", Dimension::rate, 10.0);
  expect_si("60 %", Dimension::dimensionless, 0.6);
}

TEST(Units, WhitespaceIsFlexible) {
  expect_si("0.6mm", Dimension::length, 0.6e-3);
  expect_si("  0.6 mm  ", Dimension::length, 0.6e-3);
  expect_si("0.6\tmm", Dimension::length, 0.6e-3);
  expect_si("3000 kg / m^3", Dimension::density, 3000.0);
  expect_si("3000 kg/m ^ 3", Dimension::density, 3000.0);
}

TEST(Units, ExponentForms) {
  expect_si("1E3 mm", Dimension::length, 1.0);
  expect_si("2.5e+2 Pa", Dimension::pressure, 250.0);
  expect_si("+3 mm", Dimension::length, 3e-3);
  expect_si(".5 mm", Dimension::length, 0.5e-3);
  expect_si("2 mm^2", Dimension::area, 2e-6);
  expect_si("2 m**3", Dimension::volume, 2.0);
  expect_si("2 cm\u00b3", Dimension::volume, 2e-6);
  expect_si("4 s^-1", Dimension::rate, 4.0);
  expect_si("3000 kg m^-3", Dimension::density, 3000.0);
}

TEST(Units, WrongDimensionNamesBoth) {
  const std::string message = error_of("0.6 kg", Dimension::length);
  EXPECT_NE(message.find("expected a length"), std::string::npos) << message;
  EXPECT_NE(message.find("'0.6 kg'"), std::string::npos) << message;
  EXPECT_NE(message.find("a mass"), std::string::npos) << message;
}

TEST(Units, AngularVelocityNeedsAnAngle) {
  // "/s" alone is a rate: refusing it keeps "20 /s" from silently meaning 20 rad/s.
  EXPECT_NE(error_of("20 /s", Dimension::angular_velocity).find("a rate"), std::string::npos);
  EXPECT_NE(error_of("20 rpm", Dimension::rate).find("an angular velocity"), std::string::npos);
}

TEST(Units, UnknownUnitIsNamed) {
  const std::string message = error_of("0.6 parsec", Dimension::length);
  EXPECT_NE(message.find("unknown unit 'parsec'"), std::string::npos) << message;
  EXPECT_NE(error_of("5 hrs", Dimension::time).find("unknown unit 'hrs'"), std::string::npos);
}

TEST(Units, NotANumber) {
  for (const std::string text : {"abc", "", "mm", "heavy"}) {
    const std::string message = error_of(text, Dimension::density);
    EXPECT_NE(message.find("not a number"), std::string::npos) << text << ": " << message;
  }
  for (const std::string text : {"nan", "inf", "-inf mm"}) {
    const std::string message = error_of(text, Dimension::length);
    EXPECT_NE(message.find("not a finite number"), std::string::npos) << text << ": " << message;
  }
}

TEST(Units, MalformedUnitExpressions) {
  EXPECT_NE(error_of("5 mm 3", Dimension::length).find("unexpected '3'"), std::string::npos);
  EXPECT_NE(error_of("5 mm)", Dimension::length).find("unexpected ')'"), std::string::npos);
  EXPECT_NE(error_of("5 W/(m K", Dimension::thermal_conductivity).find("missing ')'"),
            std::string::npos);
  EXPECT_NE(error_of("5 m^x", Dimension::area).find("integer exponent"), std::string::npos);
  EXPECT_NE(error_of("5 m/", Dimension::velocity).find("ends too early"), std::string::npos);
}

TEST(Units, OffsetTemperaturesStandAlone) {
  EXPECT_NE(error_of("5 degC/s", Dimension::temperature).find("can only stand alone"),
            std::string::npos);
  EXPECT_NE(error_of("20 degC", Dimension::length).find("a temperature"), std::string::npos);
}

TEST(Units, NothingIsColderThanAbsoluteZero) {
  EXPECT_NE(error_of("-300 degC", Dimension::temperature).find("below absolute zero"),
            std::string::npos);
  EXPECT_NE(error_of("-1 K", Dimension::temperature).find("below absolute zero"),
            std::string::npos);
  EXPECT_NE(error_of("-1", Dimension::temperature).find("below absolute zero"),
            std::string::npos);
  EXPECT_NEAR(parse_quantity("-273.15 degC", Dimension::temperature), 0.0, 1e-12);
}

TEST(Units, DimensionsDescribeThemselves) {
  EXPECT_EQ(dimension_description(Dimension::length), "a length");
  EXPECT_EQ(dimension_description(Dimension::angular_velocity), "an angular velocity");
  // Every documented example parses as its own dimension.
  for (const Dimension dimension :
       {Dimension::dimensionless, Dimension::length, Dimension::area, Dimension::volume,
        Dimension::time, Dimension::mass, Dimension::velocity, Dimension::acceleration,
        Dimension::angle, Dimension::angular_velocity, Dimension::rate, Dimension::pressure,
        Dimension::density, Dimension::temperature, Dimension::energy, Dimension::force,
        Dimension::power, Dimension::thermal_conductivity, Dimension::specific_heat,
        Dimension::heat_transfer_coefficient, Dimension::areal_density,
        Dimension::temperature_gradient}) {
    const std::string example(dimension_example(dimension));
    EXPECT_NO_THROW(parse_quantity(example, dimension)) << example;
  }
}

}  // namespace
}  // namespace regodem
