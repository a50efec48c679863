#pragma once
// The report of a fitted response surface, as text and as JSON, shared by `regodem fit`
// and `regodem calibrate` (docs/calibration.md, "regodem fit").
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "doe/response_surface_fit.hpp"
#include "doe/response_surface_solve.hpp"

namespace regodem::app {

/// `digits` significant digits; "n/a" for NaN.
std::string format_number(double value, int digits = 6);

/// Equation, coefficients with standard errors, t and p values, R² (adjusted,
/// predicted), and the ANOVA table; ends with a blank line.
std::string fit_report_text(const doe::ResponseSurfaceFit& fit, const std::string& unit);

/// The same as JSON (17 digits in the equation).
nlohmann::json fit_json(const doe::ResponseSurfaceFit& fit, const std::string& unit);

/// "A = 1.2, B = 3.4   (fitted: Y = 5.6, Z = 7.8)": a root and every fitted response there.
std::string solution_text(const doe::Solution& solution, const std::vector<std::string>& factor_names,
                          const std::vector<doe::ResponseSurfaceFit>& fits);

/// {factors: {A: …}, responses: {Y: …}, inside_design_range, outside: [...]}.
nlohmann::json solution_json(const doe::Solution& solution, const std::vector<std::string>& factor_names,
                             const std::vector<doe::ResponseSurfaceFit>& fits);

}  // namespace regodem::app
