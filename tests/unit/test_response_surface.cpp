// Least-squares response surfaces: recovery of a known quadratic (exact and with noise),
// every statistic against an independent computation on a published data set, and the
// refusals (too few runs, a singular design, a constant response).
#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "core/rng.hpp"
#include "doe/central_composite_design.hpp"
#include "doe/response_surface_fit.hpp"

namespace regodem::doe {
namespace {

const std::vector<std::string> names = {"C_wall", "lambda_wall"};

/// Runs of the paper's CCD (actual values), the whole design `replicates` times.
std::vector<std::vector<double>> paper_design_runs(int replicates, int centre_points) {
  CcdOptions options;
  options.centre_points = centre_points;
  const CentralCompositeDesign design =
      make_central_composite_design({{"C_wall", "", 1200, 600}, {"lambda_wall", "", 300, 200}}, options);
  std::vector<std::vector<double>> x;
  for (int r = 0; r < replicates; ++r)
    for (const DesignPoint& p : design.runs) x.push_back(p.actual);
  return x;
}

/// Full quadratic in (C, λ) in Design-Expert's order: 1, C, λ, Cλ, C², λ².
const std::vector<double> true_coefficients = {195.0, 0.0017, -0.88, 2.0e-6, -1.5e-6, 0.0011};

double true_surface(const std::vector<double>& x) {
  const double c = x[0], l = x[1];
  const auto& b = true_coefficients;
  return b[0] + b[1] * c + b[2] * l + b[3] * c * l + b[4] * c * c + b[5] * l * l;
}

TEST(ResponseSurfaceFit, RecoversAnExactQuadraticTo1e9) {
  const auto x = paper_design_runs(1, 3);
  std::vector<double> y;
  for (const auto& row : x) y.push_back(true_surface(row));
  const ResponseSurfaceFit fit = fit_response_surface(x, y, names, full_quadratic_terms(2), "T_d");
  ASSERT_EQ(fit.coefficients.size(), 6U);
  for (std::size_t j = 0; j < 6; ++j)
    EXPECT_NEAR(fit.coefficients[j].estimate, true_coefficients[j], 1e-9 * std::fabs(true_coefficients[j]))
        << fit.coefficients[j].term;
  EXPECT_NEAR(fit.r_squared, 1.0, 1e-12);
  for (std::size_t r = 0; r < x.size(); ++r) EXPECT_NEAR(fit.fitted[r], y[r], 1e-9);
}

TEST(ResponseSurfaceFit, RecoversAQuadraticUnderNoiseWithinThreeStandardErrors) {
  // The design twice over (22 runs, 16 residual df); Gaussian noise σ = 0.5 K by Box–Muller
  // from the project's generator with a fixed seed.
  const auto x = paper_design_runs(2, 3);
  Rng rng(2023);
  std::vector<double> y;
  for (const auto& row : x) {
    const double u1 = rng.uniform(), u2 = rng.uniform();
    const double normal = std::sqrt(-2.0 * std::log(1.0 - u1)) * std::cos(2.0 * std::numbers::pi * u2);
    y.push_back(true_surface(row) + 0.5 * normal);
  }
  const ResponseSurfaceFit fit = fit_response_surface(x, y, names, full_quadratic_terms(2), "T_d");
  EXPECT_EQ(fit.residual_degrees_of_freedom, 16);
  for (std::size_t j = 0; j < 6; ++j) {
    const CoefficientEstimate& c = fit.coefficients[j];
    EXPECT_GT(c.standard_error, 0.0);
    EXPECT_LT(std::fabs(c.estimate - true_coefficients[j]), 3.0 * c.standard_error) << c.term;
  }
  EXPECT_NEAR(fit.residual_std_dev, 0.5, 0.25);  // σ recovered roughly (16 df)
  EXPECT_TRUE(fit.has_lack_of_fit);              // 11 distinct settings, each run twice or more
}

// Montgomery, Design and Analysis of Experiments (8th ed.), Example 11.2: the chemical
// process yield on a rotatable CCD (α = 1.414) with five centre points, full quadratic in
// coded x1, x2. The book gives ŷ = 79.94 + 0.995 x1 + 0.515 x2 + 0.25 x1x2 − 1.376 x1² −
// 1.001 x2² and a lack-of-fit F of 1.79; the values below to full precision were computed
// once with /usr/bin/python3: numpy 1.24.2 (np.linalg.lstsq; inv(XᵀX) for the standard
// errors and hat matrix; PRESS = Σ (e_i/(1−h_ii))²) and scipy 1.10.1 (stats.t.sf, stats.f.sf
// for the p-values), pure error from the five centre runs.
TEST(ResponseSurfaceFit, MontgomeryExample11_2AgainstNumpyAndScipy) {
  const double a = 1.414;
  const std::vector<std::vector<double>> x = {{-1, -1}, {-1, 1}, {1, -1}, {1, 1}, {0, 0}, {0, 0}, {0, 0},
                                              {0, 0},   {0, 0},  {a, 0},  {-a, 0}, {0, a}, {0, -a}};
  const std::vector<double> y = {76.5, 77.0, 78.0, 79.5, 79.9, 80.3, 80.0, 79.7, 79.8, 78.4, 75.6, 78.5, 77.0};
  const ResponseSurfaceFit fit = fit_response_surface(x, y, {"x1", "x2"}, full_quadratic_terms(2), "yield");

  const std::vector<double> b = {79.93995460640018, 0.995050252588136, 0.5152027956221317,
                                 0.2500000000000145, -1.3764492825947632, -1.0013359983829324};
  const std::vector<double> se = {0.11908861952488015, 0.09415493095946637, 0.09415493095946637,
                                  0.13314512673152748, 0.10098416879564365, 0.10098416879564365};
  const std::vector<double> t = {671.2644325321029, 10.568222422854353, 5.471862072140716,
                                 1.8776503965038993, -13.630347202047197, -9.915772049471274};
  const std::vector<double> p = {4.3003000286179371e-18, 1.4844860078907256e-05, 9.3401053473334450e-04,
                                 1.0251919076543330e-01, 2.6929970779806860e-06, 2.2620440980805464e-05};
  const std::vector<std::string> term_names = {"1", "x1", "x2", "x1*x2", "x1^2", "x2^2"};
  for (std::size_t j = 0; j < 6; ++j) {
    const CoefficientEstimate& c = fit.coefficients[j];
    EXPECT_EQ(c.term, term_names[j]);
    EXPECT_NEAR(c.estimate, b[j], 1e-11);
    EXPECT_NEAR(c.standard_error / se[j], 1.0, 1e-10) << c.term;
    EXPECT_NEAR(c.t_value / t[j], 1.0, 1e-10) << c.term;
    EXPECT_NEAR(c.p_value / p[j], 1.0, 1e-8) << c.term;
  }
  EXPECT_NEAR(fit.r_squared, 0.9827306765050124, 1e-12);
  EXPECT_NEAR(fit.adjusted_r_squared, 0.9703954454371643, 1e-12);
  EXPECT_NEAR(fit.predicted_r_squared, 0.918120752924324, 1e-11);
  EXPECT_NEAR(fit.press, 2.3534614970997785, 1e-10);

  ASSERT_TRUE(fit.has_lack_of_fit);
  auto row = [&](const std::string& source) {
    for (const AnovaRow& r : fit.anova)
      if (r.source == source) return r;
    ADD_FAILURE() << "no ANOVA row " << source;
    return AnovaRow{};
  };
  EXPECT_NEAR(row("model").sum_of_squares, 28.246703429451028, 1e-10);
  EXPECT_EQ(row("model").degrees_of_freedom, 5);
  EXPECT_NEAR(row("model").f_value / 79.6686070248412, 1.0, 1e-10);
  EXPECT_NEAR(row("model").p_value / 5.147030431389909e-06, 1.0, 1e-8);
  EXPECT_NEAR(row("x1^2").sum_of_squares, 13.174203855405624, 1e-10);  // partial SS b²/(XᵀX)⁻¹_jj
  EXPECT_NEAR(row("x1^2").p_value / p[4], 1.0, 1e-8);                   // F = t²: the same p
  EXPECT_NEAR(row("residual").sum_of_squares, 0.4963734936259263, 1e-11);
  EXPECT_EQ(row("residual").degrees_of_freedom, 7);
  EXPECT_NEAR(row("lack of fit").sum_of_squares, 0.2843734936259294, 1e-11);
  EXPECT_EQ(row("lack of fit").degrees_of_freedom, 3);
  EXPECT_NEAR(row("lack of fit").f_value, 1.7885125385278837, 1e-10);
  EXPECT_NEAR(row("lack of fit").p_value, 0.2885639882336163, 1e-10);
  EXPECT_NEAR(row("pure error").sum_of_squares, 0.2119999999999969, 1e-12);
  EXPECT_EQ(row("pure error").degrees_of_freedom, 4);
  EXPECT_NEAR(row("total").sum_of_squares, 28.743076923076956, 1e-10);
  EXPECT_EQ(row("total").degrees_of_freedom, 12);
  EXPECT_TRUE(std::isnan(row("total").f_value));
}

TEST(ResponseSurfaceFit, AReducedTermListAsThePaperUsesForTin) {
  // Eq. 7 drops C² and the interaction: fit 1, C, λ, λ² to data made by Eq. 7 itself.
  const std::vector<Term> terms = parse_terms("C_wall, lambda_wall, lambda_wall^2", names);
  ASSERT_EQ(terms.size(), 4U);
  PolynomialModel eq7{names, terms, {539.60656, -0.041123, -0.383554, 0.000471}};
  const auto x = paper_design_runs(1, 3);
  std::vector<double> y;
  for (const auto& row : x) y.push_back(eq7.evaluate(row) + (row[0] > 1500 ? 0.03 : -0.01));  // not exact: a spread for the statistics
  const ResponseSurfaceFit fit = fit_response_surface(x, y, names, terms, "T_in");
  EXPECT_EQ(fit.parameters, 4);
  EXPECT_EQ(fit.residual_degrees_of_freedom, 7);
  EXPECT_EQ(fit.model.equation("T_in", 3).substr(0, 12), "T_in = 540 -");
}

TEST(ResponseSurfaceFit, ParsesTermLists) {
  EXPECT_EQ(parse_terms("A, B, A*B, B^2, A*A", {"A", "B"}).size(), 6U);
  EXPECT_EQ(term_name(parse_terms("B*A", {"A", "B"})[1], {"A", "B"}), "A*B");
  EXPECT_EQ(term_name(parse_terms("A*A", {"A", "B"})[1], {"A", "B"}), "A^2");
  EXPECT_THROW(parse_terms("A,C", {"A", "B"}), InputError);      // not a factor
  EXPECT_THROW(parse_terms("A^3", {"A", "B"}), InputError);      // beyond quadratic
  EXPECT_THROW(parse_terms("A^2*B", {"A", "B"}), InputError);    // degree 3
  EXPECT_THROW(parse_terms("A,A", {"A", "B"}), InputError);      // twice
  EXPECT_THROW(parse_terms("A,,B", {"A", "B"}), InputError);     // empty entry
}

TEST(ResponseSurfaceFit, RefusesTooFewRunsASingularDesignAndAConstantResponse) {
  const std::vector<std::vector<double>> square = {{-1, -1}, {1, -1}, {-1, 1}, {1, 1}};
  EXPECT_THROW(fit_response_surface(square, {1, 2, 3, 4}, {"A", "B"}, full_quadratic_terms(2), "y"), InputError);
  // A 2² factorial with centre points: A² and B² take the same values in every run.
  const std::vector<std::vector<double>> factorial = {{-1, -1}, {1, -1}, {-1, 1}, {1, 1}, {0, 0}, {0, 0}, {0, 0}};
  try {
    fit_response_surface(factorial, {1, 2, 3, 5, 2, 2.1, 1.9}, {"A", "B"}, full_quadratic_terms(2), "y");
    FAIL() << "a singular design was fitted";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("singular design"), std::string::npos) << message;
    EXPECT_NE(message.find("A^2"), std::string::npos) << message;
    EXPECT_NE(message.find("B^2"), std::string::npos) << message;
  }
  EXPECT_THROW(fit_response_surface(factorial, std::vector<double>(7, 3.0), {"A", "B"}, parse_terms("A,B", {"A", "B"}),
                                    "y"),
               InputError);
}

}  // namespace
}  // namespace regodem::doe
