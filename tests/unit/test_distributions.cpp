// The regularized incomplete beta function and the t and F distributions built on it,
// against closed forms that hold for particular degrees of freedom, symmetry identities,
// and a few values from SciPy 1.10 (scipy.special.betainc, scipy.stats.t.sf / f.sf).
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "doe/distributions.hpp"

namespace regodem::doe {
namespace {

constexpr double tight = 1e-13;

TEST(IncompleteBeta, ClosedFormsForSmallParameters) {
  for (const double x : {1e-6, 0.01, 0.2, 0.5, 0.73, 0.99, 1.0 - 1e-9}) {
    EXPECT_NEAR(regularized_incomplete_beta(1.0, 1.0, x), x, tight);
    EXPECT_NEAR(regularized_incomplete_beta(3.0, 1.0, x), x * x * x, tight);            // I_x(a,1) = x^a
    EXPECT_NEAR(regularized_incomplete_beta(1.0, 4.0, x), 1.0 - std::pow(1.0 - x, 4.0), tight);  // 1 − (1−x)^b
    // I_x(1/2, 1/2) = (2/π) asin √x (the arcsine distribution); near x = 1 the reference is
    // taken as 1 − (2/π) asin √(1−x), since asin is ill-conditioned near 1.
    const double arcsine = x < 0.5 ? 2.0 / std::numbers::pi * std::asin(std::sqrt(x))
                                   : 1.0 - 2.0 / std::numbers::pi * std::asin(std::sqrt(1.0 - x));
    EXPECT_NEAR(regularized_incomplete_beta(0.5, 0.5, x), arcsine, tight);
  }
  EXPECT_EQ(regularized_incomplete_beta(2.0, 3.0, 0.0), 0.0);
  EXPECT_EQ(regularized_incomplete_beta(2.0, 3.0, 1.0), 1.0);
}

TEST(IncompleteBeta, SymmetryAndLargeParameters) {
  for (const double a : {0.3, 2.5, 17.0, 500.0})
    for (const double b : {0.7, 4.0, 60.0})
      for (const double x : {0.05, 0.4, 0.8})
        EXPECT_NEAR(regularized_incomplete_beta(a, b, x) + regularized_incomplete_beta(b, a, 1.0 - x), 1.0, 1e-12)
            << a << " " << b << " " << x;
  // I_{1/2}(a, a) = 1/2 for any a: the continued fraction at large parameters.
  for (const double a : {0.5, 10.0, 1000.0}) EXPECT_NEAR(regularized_incomplete_beta(a, a, 0.5), 0.5, 1e-12);
  EXPECT_NEAR(regularized_incomplete_beta(2.5, 7.5, 0.3), 0.6789434858661818, 1e-13);   // SciPy betainc
  EXPECT_NEAR(regularized_incomplete_beta(50.0, 60.0, 0.45), 0.4642352914306064, 1e-12);  // SciPy betainc
}

TEST(IncompleteBeta, RefusesOutsideItsDomain) {
  EXPECT_THROW(regularized_incomplete_beta(0.0, 1.0, 0.5), std::domain_error);
  EXPECT_THROW(regularized_incomplete_beta(1.0, 1.0, 1.5), std::domain_error);
  EXPECT_THROW(regularized_incomplete_beta(1.0, 1.0, std::nan("")), std::domain_error);
}

TEST(StudentT, CauchyAndTwoDegreesOfFreedom) {
  for (const double t : {-30.0, -2.0, -0.3, 0.0, 0.7, 1.0, 5.0, 1e3}) {
    // ν = 1 is the Cauchy distribution: 1/2 + atan(t)/π.
    EXPECT_NEAR(student_t_cdf(t, 1.0), 0.5 + std::atan(t) / std::numbers::pi, tight) << t;
    // ν = 2: 1/2 + t / (2 √(2 + t²)).
    EXPECT_NEAR(student_t_cdf(t, 2.0), 0.5 + t / (2.0 * std::sqrt(2.0 + t * t)), tight) << t;
    EXPECT_NEAR(student_t_cdf(t, 7.0) + student_t_cdf(-t, 7.0), 1.0, tight) << t;  // symmetry
  }
  EXPECT_NEAR(student_t_two_sided_p(2.0, 5.0), 0.10193947882985828, 1e-13);  // SciPy 2*t.sf(2, 5)
  // A far tail keeps its relative accuracy: ν = 1, P(|T| ≥ t) = 1 − (2/π) atan t = (2/π) atan(1/t).
  EXPECT_NEAR(student_t_two_sided_p(1e6, 1.0) / (2.0 / std::numbers::pi * std::atan(1e-6)), 1.0, 1e-12);
}

TEST(FisherF, TwoNumeratorOrDenominatorDegreesOfFreedom) {
  for (const double d2 : {1.0, 3.0, 10.0, 55.0})
    for (const double x : {0.01, 0.5, 1.0, 4.0, 30.0}) {
      // F(2, d2): P(F ≤ x) = 1 − (1 + 2x/d2)^(−d2/2).
      const double upper = std::pow(1.0 + 2.0 * x / d2, -d2 / 2.0);
      EXPECT_NEAR(f_cdf(x, 2.0, d2), 1.0 - upper, tight) << d2 << " " << x;
      EXPECT_NEAR(f_upper_tail(x, 2.0, d2) / upper, 1.0, 1e-12) << d2 << " " << x;  // relative: tails matter
      // F(d1, 2): P(F ≤ x) = (d1 x / (d1 x + 2))^(d1/2).
      EXPECT_NEAR(f_cdf(x, d2, 2.0), std::pow(d2 * x / (d2 * x + 2.0), d2 / 2.0), tight) << d2 << " " << x;
    }
  // A tiny p-value is computed, not lost to 1 − CDF: (1 + 2·1000/10)^(−5) = 3.05e-12.
  EXPECT_NEAR(f_upper_tail(1000.0, 2.0, 10.0) / std::pow(201.0, -5.0), 1.0, 1e-12);
  EXPECT_NEAR(f_upper_tail(3.5, 3.0, 7.0), 0.0781185150009158, 1e-13);  // SciPy f.sf(3.5, 3, 7)
  EXPECT_EQ(f_cdf(0.0, 3.0, 4.0), 0.0);
  EXPECT_EQ(f_upper_tail(-1.0, 3.0, 4.0), 1.0);
  // 1/F has the F(d2, d1) distribution.
  EXPECT_NEAR(f_cdf(2.5, 3.0, 8.0), f_upper_tail(1.0 / 2.5, 8.0, 3.0), tight);
}

}  // namespace
}  // namespace regodem::doe
