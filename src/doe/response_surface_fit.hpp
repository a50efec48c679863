#pragma once
// Least-squares response surfaces with the statistics a designed experiment is judged by:
// coefficients with standard errors, t and p values; R², adjusted R², predicted R² (from
// PRESS); the ANOVA table with lack of fit against pure error where runs are replicated.
// Formulas: Montgomery, Design and Analysis of Experiments, 8th ed., sections 10.3–10.4
// (regression ANOVA, t tests, R², PRESS) and 6.8 / 11.3 (lack of fit); Myers, Montgomery &
// Anderson-Cook, Response Surface Methodology, 3rd ed., section 2.7 (PRESS, predicted R²).
#include <string>
#include <vector>

#include "doe/polynomial_model.hpp"

namespace regodem::doe {

struct CoefficientEstimate {
  std::string term;
  double estimate = 0.0;
  double standard_error = 0.0;
  double t_value = 0.0;
  double p_value = 0.0;  // two-sided, residual degrees of freedom
};

/// One row of the ANOVA table; NaN where a cell does not apply (total: no MS, F or p).
struct AnovaRow {
  std::string source;  // "model", a term (its partial, type III, sum of squares), "residual",
                       // "lack of fit", "pure error", "total"
  double sum_of_squares = 0.0;
  int degrees_of_freedom = 0;
  double mean_square = 0.0;
  double f_value = 0.0;
  double p_value = 0.0;
};

struct ResponseSurfaceFit {
  std::string response_name;
  PolynomialModel model;
  std::vector<CoefficientEstimate> coefficients;  // in the model's term order
  int runs = 0;
  int parameters = 0;
  int residual_degrees_of_freedom = 0;
  double residual_std_dev = 0.0;  // sqrt(MS_residual)
  double response_mean = 0.0;
  double r_squared = 0.0;
  double adjusted_r_squared = 0.0;
  double predicted_r_squared = 0.0;  // NaN when a run has leverage 1 (PRESS undefined)
  double press = 0.0;
  bool has_lack_of_fit = false;      // replicated runs leave degrees of freedom for pure error
  std::vector<AnovaRow> anova;       // model, its terms, residual, [lack of fit, pure error], total
  std::vector<double> fitted;        // per run
  std::vector<double> leverage;      // diagonal of the hat matrix, per run
};

/// Fits `terms` (the first must be the intercept) to the responses `y` at the factor
/// settings `x` (one row per run, one value per factor) by least squares through a
/// singular value decomposition of the column-scaled model matrix (no normal equations).
/// Throws InputError when there are no more runs than terms, when the design cannot
/// separate the terms (singular), or when the response does not vary.
ResponseSurfaceFit fit_response_surface(const std::vector<std::vector<double>>& x, const std::vector<double>& y,
                                        const std::vector<std::string>& factor_names, const std::vector<Term>& terms,
                                        const std::string& response_name);

}  // namespace regodem::doe
