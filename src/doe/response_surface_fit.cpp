#include "doe/response_surface_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "core/error.hpp"
#include "doe/distributions.hpp"
#include "doe/eigen_dense.hpp"

namespace regodem::doe {
namespace {

constexpr double not_applicable = std::numeric_limits<double>::quiet_NaN();

/// Relative singular-value threshold on the column-scaled model matrix: below it the design
/// cannot tell the terms apart (condition number above 1e10 after equilibration).
constexpr double rank_tolerance = 1e-10;

/// Runs at the same factor settings (within 1e-9 of each factor's spread) form one group.
std::vector<int> replicate_groups(const std::vector<std::vector<double>>& x, int& group_count) {
  const std::size_t n = x.size();
  const std::size_t k = n > 0 ? x[0].size() : 0;
  std::vector<double> tolerance(k, 0.0);
  for (std::size_t i = 0; i < k; ++i) {
    double lo = x[0][i], hi = x[0][i];
    for (const auto& row : x) lo = std::min(lo, row[i]), hi = std::max(hi, row[i]);
    tolerance[i] = 1e-9 * std::max(hi - lo, std::fabs(hi) + std::fabs(lo));
  }
  std::vector<int> group(n, -1);
  group_count = 0;
  for (std::size_t r = 0; r < n; ++r) {
    if (group[r] >= 0) continue;
    group[r] = group_count;
    for (std::size_t s = r + 1; s < n; ++s) {
      bool same = group[s] < 0;
      for (std::size_t i = 0; i < k && same; ++i) same = std::fabs(x[r][i] - x[s][i]) <= tolerance[i];
      if (same) group[s] = group_count;
    }
    ++group_count;
  }
  return group;
}

AnovaRow tested_row(std::string source, double ss, int df, double ms_error, int df_error) {
  AnovaRow row{std::move(source), ss, df, ss / df, not_applicable, not_applicable};
  if (df_error > 0) {
    row.f_value = row.mean_square / ms_error;  // ±inf or NaN when the error is exactly zero
    row.p_value = std::isnan(row.f_value) ? not_applicable : f_upper_tail(row.f_value, df, df_error);
  }
  return row;
}

void check_inputs(const std::vector<std::vector<double>>& x, const std::vector<double>& y,
                  const std::vector<std::string>& factor_names, const std::vector<Term>& terms,
                  const std::string& response_name) {
  if (x.size() != y.size())
    throw InputError(fmt::format("{} factor rows but {} responses", x.size(), y.size()));
  if (terms.empty() || !terms.front().is_intercept())
    throw InputError("the model's first term must be the intercept");
  for (const auto& row : x)
    if (row.size() != factor_names.size())
      throw InputError(fmt::format("a run has {} factor values for {} factors", row.size(), factor_names.size()));
  for (const Term& term : terms)
    if (term.powers.size() != factor_names.size()) throw InputError("a term does not match the factor count");
  for (std::size_t r = 0; r < y.size(); ++r) {
    if (!std::isfinite(y[r]))
      throw InputError(fmt::format("response '{}': run {} is not a finite number", response_name, r + 1));
    for (double v : x[r])
      if (!std::isfinite(v)) throw InputError(fmt::format("run {}: a factor value is not a finite number", r + 1));
  }
  // Residual degrees of freedom are needed for every statistic beyond the coefficients.
  if (y.size() <= terms.size())
    throw InputError(fmt::format("response '{}': {} runs for {} terms; a fit with statistics needs at least {} runs "
                                 "(drop terms with --terms, or add runs)",
                                 response_name, y.size(), terms.size(), terms.size() + 1));
}

}  // namespace

ResponseSurfaceFit fit_response_surface(const std::vector<std::vector<double>>& x, const std::vector<double>& y,
                                        const std::vector<std::string>& factor_names, const std::vector<Term>& terms,
                                        const std::string& response_name) {
  check_inputs(x, y, factor_names, terms, response_name);
  const auto n = static_cast<Eigen::Index>(y.size());
  const auto p = static_cast<Eigen::Index>(terms.size());

  // Model matrix with unit-norm columns: C_wall² (~1e6) and the intercept (1) would
  // otherwise differ by six orders of magnitude, and the rank test would see scale, not design.
  Eigen::MatrixXd design(n, p);
  for (Eigen::Index r = 0; r < n; ++r)
    for (Eigen::Index j = 0; j < p; ++j) design(r, j) = terms[static_cast<std::size_t>(j)].value(x[static_cast<std::size_t>(r)]);
  Eigen::VectorXd scale = design.colwise().norm().transpose();
  for (Eigen::Index j = 0; j < p; ++j) {
    if (!(scale(j) > 0.0))
      throw InputError(fmt::format("singular design for '{}': the term {} is zero in every run", response_name,
                                   term_name(terms[static_cast<std::size_t>(j)], factor_names)));
    design.col(j) /= scale(j);
  }
  const Eigen::VectorXd response = Eigen::Map<const Eigen::VectorXd>(y.data(), n);

  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(design, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd sigma = svd.singularValues();  // descending
  if (sigma(p - 1) <= rank_tolerance * sigma(0)) {
    // The right singular vector of the smallest singular value is the combination of
    // terms the runs cannot see: name the terms that take part in it.
    const Eigen::VectorXd null = svd.matrixV().col(p - 1);
    std::string aliased;
    for (Eigen::Index j = 0; j < p; ++j)
      if (std::fabs(null(j)) > 0.1)
        aliased += (aliased.empty() ? "" : ", ") + term_name(terms[static_cast<std::size_t>(j)], factor_names);
    throw InputError(fmt::format("singular design for '{}': the runs cannot separate the terms {} (condition number "
                                 "{:.3g}); add runs at other settings or drop one of these terms with --terms",
                                 response_name, aliased, sigma(0) / sigma(p - 1)));
  }
  const Eigen::MatrixXd& u = svd.matrixU();
  const Eigen::MatrixXd& v = svd.matrixV();
  const Eigen::VectorXd inverse_sigma = sigma.cwiseInverse();
  const Eigen::VectorXd scaled_beta = v * (inverse_sigma.asDiagonal() * (u.transpose() * response));
  const Eigen::VectorXd beta = scaled_beta.cwiseQuotient(scale);
  // (XᵀX)⁻¹ in the scaled columns is V Σ⁻² Vᵀ; only its diagonal is needed.
  const Eigen::VectorXd unscaled_variance =
      (v * inverse_sigma.cwiseAbs2().asDiagonal() * v.transpose()).diagonal().cwiseQuotient(scale.cwiseAbs2());

  const Eigen::VectorXd fitted = design * scaled_beta;
  const Eigen::VectorXd residual = response - fitted;
  const Eigen::VectorXd leverage = u.rowwise().squaredNorm();  // h_ii = ‖row i of U‖²

  ResponseSurfaceFit fit;
  fit.response_name = response_name;
  fit.model.factor_names = factor_names;
  fit.model.terms = terms;
  fit.model.coefficients.assign(beta.data(), beta.data() + p);
  fit.runs = static_cast<int>(n);
  fit.parameters = static_cast<int>(p);
  fit.residual_degrees_of_freedom = static_cast<int>(n - p);
  fit.fitted.assign(fitted.data(), fitted.data() + n);
  fit.leverage.assign(leverage.data(), leverage.data() + n);

  const double mean = response.mean();
  const double ss_total = (response.array() - mean).square().sum();
  if (!(ss_total > 0.0))
    throw InputError(fmt::format("response '{}' has the same value in every run: there is nothing to fit",
                                 response_name));
  const double ss_residual = residual.squaredNorm();
  const double ss_model = (fitted.array() - mean).square().sum();
  const int df_model = static_cast<int>(p - 1);
  const int df_residual = fit.residual_degrees_of_freedom;
  const int df_total = static_cast<int>(n - 1);
  const double ms_residual = ss_residual / df_residual;
  fit.response_mean = mean;
  fit.residual_std_dev = std::sqrt(ms_residual);

  // Coefficient tests: se_j = sqrt(MS_res (XᵀX)⁻¹_jj), t = b/se, two-sided p on n − p df.
  for (Eigen::Index j = 0; j < p; ++j) {
    CoefficientEstimate c;
    c.term = term_name(terms[static_cast<std::size_t>(j)], factor_names);
    c.estimate = beta(j);
    c.standard_error = std::sqrt(ms_residual * unscaled_variance(j));
    c.t_value = c.estimate / c.standard_error;
    c.p_value = std::isnan(c.t_value) ? not_applicable : student_t_two_sided_p(c.t_value, df_residual);
    fit.coefficients.push_back(c);
  }

  // R² = 1 − SS_res/SS_tot; adjusted R² = 1 − (SS_res/(n−p)) / (SS_tot/(n−1));
  // predicted R² = 1 − PRESS/SS_tot with PRESS = Σ (e_i / (1 − h_ii))² (Montgomery 10.4,
  // Myers et al. 2.7): the leave-one-out residuals without refitting.
  fit.r_squared = 1.0 - ss_residual / ss_total;
  fit.adjusted_r_squared = 1.0 - (ss_residual / df_residual) / (ss_total / df_total);
  double press = 0.0;
  for (Eigen::Index r = 0; r < n; ++r) {
    const double one_minus_h = 1.0 - leverage(r);
    if (one_minus_h < 1e-10) {
      press = not_applicable;  // the run decides its own fitted value: no leave-one-out residual
      break;
    }
    press += (residual(r) / one_minus_h) * (residual(r) / one_minus_h);
  }
  fit.press = press;
  fit.predicted_r_squared = 1.0 - press / ss_total;

  // ANOVA. The model row is SS_R = Σ(ŷ − ȳ)² on p − 1 df; each term row is its partial
  // (type III) sum of squares b_j² / (XᵀX)⁻¹_jj on 1 df, whose F equals t².
  fit.anova.push_back(tested_row("model", ss_model, df_model, ms_residual, df_residual));
  for (Eigen::Index j = 1; j < p; ++j)
    fit.anova.push_back(tested_row(fit.coefficients[static_cast<std::size_t>(j)].term,
                                   beta(j) * beta(j) / unscaled_variance(j), 1, ms_residual, df_residual));
  fit.anova.push_back(AnovaRow{"residual", ss_residual, df_residual, ms_residual, not_applicable, not_applicable});

  // Lack of fit (Montgomery 6.8): pure error from the spread within groups of replicated
  // runs, SS_PE on n − m df (m distinct settings); lack of fit is the rest of the residual,
  // on m − p df. Tested only when both have degrees of freedom.
  int groups = 0;
  const std::vector<int> group = replicate_groups(x, groups);
  const int df_pure_error = static_cast<int>(n) - groups;
  const int df_lack_of_fit = groups - static_cast<int>(p);
  if (df_pure_error > 0 && df_lack_of_fit > 0) {
    std::vector<double> sum(static_cast<std::size_t>(groups), 0.0), count(static_cast<std::size_t>(groups), 0.0);
    for (Eigen::Index r = 0; r < n; ++r) {
      sum[static_cast<std::size_t>(group[static_cast<std::size_t>(r)])] += response(r);
      count[static_cast<std::size_t>(group[static_cast<std::size_t>(r)])] += 1.0;
    }
    double ss_pure_error = 0.0;
    for (Eigen::Index r = 0; r < n; ++r) {
      const auto g = static_cast<std::size_t>(group[static_cast<std::size_t>(r)]);
      const double deviation = response(r) - sum[g] / count[g];
      ss_pure_error += deviation * deviation;
    }
    const double ss_lack_of_fit = std::max(0.0, ss_residual - ss_pure_error);
    const double ms_pure_error = ss_pure_error / df_pure_error;
    fit.anova.push_back(tested_row("lack of fit", ss_lack_of_fit, df_lack_of_fit, ms_pure_error, df_pure_error));
    fit.anova.push_back(
        AnovaRow{"pure error", ss_pure_error, df_pure_error, ms_pure_error, not_applicable, not_applicable});
    fit.has_lack_of_fit = true;
  }
  fit.anova.push_back(AnovaRow{"total", ss_total, df_total, not_applicable, not_applicable, not_applicable});
  return fit;
}

}  // namespace regodem::doe
