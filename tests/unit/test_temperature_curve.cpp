// Properties over temperature (core/temperature_curve.hpp) and values over time
// (thermal/time_table.hpp): interpolation, the enthalpy integral and its inverse,
// and clear errors for bad tables.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "core/temperature_curve.hpp"
#include "thermal/time_table.hpp"

namespace regodem {
namespace {

// Regolith-like specific heat, roughly tripling from 100 K to 350 K.
TemperatureCurve regolith_specific_heat() { return TemperatureCurve({100.0, 200.0, 350.0}, {300.0, 600.0, 900.0}); }

TEST(TemperatureCurve, InterpolatesLinearlyAndHoldsTheEndValues) {
  const TemperatureCurve c = regolith_specific_heat();
  EXPECT_DOUBLE_EQ(c.at(50.0), 300.0);
  EXPECT_DOUBLE_EQ(c.at(150.0), 450.0);
  EXPECT_DOUBLE_EQ(c.at(275.0), 750.0);
  EXPECT_DOUBLE_EQ(c.at(1000.0), 900.0);
  EXPECT_FALSE(c.is_constant());
  EXPECT_TRUE(TemperatureCurve(800.0).is_constant());
  EXPECT_TRUE(TemperatureCurve({300.0}, {5.0}).is_constant());  // one row: a constant
  EXPECT_DOUBLE_EQ(TemperatureCurve({300.0}, {5.0}).at(10.0), 5.0);
}

// The integral from 0 K is exact for the piecewise-linear curve (1e-12 relative):
// 300 x 100 below the table, trapezoids inside, the last value above.
TEST(TemperatureCurve, IntegralFromZeroIsExactForThePiecewiseLinearCurve) {
  const TemperatureCurve c = regolith_specific_heat();
  EXPECT_NEAR(c.integral_from_zero(100.0), 30000.0, 1e-12 * 30000.0);
  EXPECT_NEAR(c.integral_from_zero(150.0), 30000.0 + 50.0 * (300.0 + 450.0) / 2.0, 1e-9);
  EXPECT_NEAR(c.integral_from_zero(350.0), 30000.0 + 45000.0 + 112500.0, 1e-9);
  EXPECT_NEAR(c.integral_from_zero(400.0), 187500.0 + 45000.0, 1e-9);
  EXPECT_NEAR(TemperatureCurve(800.0).integral_from_zero(77.15), 800.0 * 77.15, 1e-9);
}

// T = h^-1(h(T)) to 1e-12 K across and beyond the table, so enthalpy stepping
// conserves energy without drifting the temperature.
TEST(TemperatureCurve, InverseIntegralRoundTrips) {
  const TemperatureCurve c = regolith_specific_heat();
  for (double t = 1.0; t < 500.0; t += 3.7) EXPECT_NEAR(c.inverse_integral(c.integral_from_zero(t)), t, 1e-12 * t);
  // A flat segment (zero slope) and a falling one invert too.
  const TemperatureCurve flat({100.0, 200.0, 300.0}, {500.0, 500.0, 200.0});
  for (double t = 10.0; t < 400.0; t += 7.3) EXPECT_NEAR(flat.inverse_integral(flat.integral_from_zero(t)), t, 1e-10);
}

TEST(TemperatureCurve, BadTablesAreRefused) {
  EXPECT_THROW(TemperatureCurve({100.0, 100.0}, {1.0, 2.0}), InputError);
  EXPECT_THROW(TemperatureCurve({200.0, 100.0}, {1.0, 2.0}), InputError);
  EXPECT_THROW(TemperatureCurve({100.0, 200.0}, {1.0}), InputError);
  EXPECT_THROW(TemperatureCurve({}, {}), InputError);
  EXPECT_THROW(TemperatureCurve({100.0, NAN}, {1.0, 2.0}), InputError);
}

TEST(TimeTable, InterpolatesAndHoldsAndRefusesBadTables) {
  const TimeTable t({0.0, 10.0, 20.0}, {77.0, 973.0, 500.0});
  EXPECT_DOUBLE_EQ(t.at(-1.0), 77.0);
  EXPECT_DOUBLE_EQ(t.at(5.0), 525.0);
  EXPECT_DOUBLE_EQ(t.at(15.0), 736.5);
  EXPECT_DOUBLE_EQ(t.at(30.0), 500.0);
  EXPECT_DOUBLE_EQ(TimeTable(300.0).at(1e6), 300.0);
  EXPECT_THROW(TimeTable({0.0, 0.0}, {1.0, 2.0}), InputError);
  EXPECT_THROW(TimeTable({0.0, 1.0}, {1.0}), InputError);
  EXPECT_THROW(TimeTable({0.0, 1.0}, {1.0, INFINITY}), InputError);
}

}  // namespace
}  // namespace regodem
