#include "doe/distributions.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

namespace regodem::doe {
namespace {

/// ln B(a, b) = ln Γ(a) + ln Γ(b) − ln Γ(a + b).
double log_beta(double a, double b) { return std::lgamma(a) + std::lgamma(b) - std::lgamma(a + b); }

/// The continued fraction of DLMF §8.17(v),
///   I_x(a,b) = x^a (1−x)^b / (a B(a,b)) · 1 / (1 + d1/(1 + d2/(1 + ...))),
///   d_{2m+1} = −(a+m)(a+b+m) x / ((a+2m)(a+2m+1)),   d_{2m} = m(b−m) x / ((a+2m−1)(a+2m)),
/// evaluated front to back by the modified Lentz method (Thompson & Barnett 1986,
/// J. Comput. Phys. 64, 490). It converges fast for x < (a+1)/(a+b+2); the caller
/// uses the symmetry I_x(a,b) = 1 − I_{1−x}(b,a) beyond that.
double beta_continued_fraction(double a, double b, double x) {
  constexpr double tiny = 1e-300;  // stands in for a zero denominator (Lentz's rule)
  constexpr double tolerance = 1e-15;
  constexpr int max_terms = 10000;
  double f = 1.0;  // b0 = 1
  double c = f;
  double d = 0.0;
  for (int j = 1; j <= max_terms; ++j) {
    const int m = j / 2;
    const double dm = static_cast<double>(m);
    const double numerator = (j % 2 == 1)
                                 ? -(a + dm) * (a + b + dm) * x / ((a + 2.0 * dm) * (a + 2.0 * dm + 1.0))
                                 : dm * (b - dm) * x / ((a + 2.0 * dm - 1.0) * (a + 2.0 * dm));
    d = 1.0 + numerator * d;
    if (std::fabs(d) < tiny) d = tiny;
    c = 1.0 + numerator / c;
    if (std::fabs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double delta = c * d;
    f *= delta;
    if (std::fabs(delta - 1.0) < tolerance) return f;
  }
  throw std::runtime_error(
      fmt::format("incomplete beta: the continued fraction did not converge (a = {}, b = {}, x = {})", a, b, x));
}

/// I_x(a,b) for x below the switch point, where the continued fraction converges fast.
double incomplete_beta_lower(double a, double b, double x) {
  if (x <= 0.0) return 0.0;
  const double log_front = a * std::log(x) + b * std::log1p(-x) - log_beta(a, b);
  return std::exp(log_front) / (a * beta_continued_fraction(a, b, x));
}

}  // namespace

double regularized_incomplete_beta(double a, double b, double x) {
  if (!(a > 0.0) || !(b > 0.0) || !(x >= 0.0) || !(x <= 1.0))
    throw std::domain_error(fmt::format("incomplete beta needs a, b > 0 and 0 <= x <= 1 (a = {}, b = {}, x = {})", a,
                                        b, x));
  if (x == 0.0) return 0.0;
  if (x == 1.0) return 1.0;
  if (x < (a + 1.0) / (a + b + 2.0)) return incomplete_beta_lower(a, b, x);
  return 1.0 - incomplete_beta_lower(b, a, 1.0 - x);
}

// P(|T| >= |t|) = I_{ν/(ν+t²)}(ν/2, 1/2)  (Abramowitz & Stegun 26.7.1 with 26.5.27).
double student_t_two_sided_p(double t, double degrees_of_freedom) {
  if (!(degrees_of_freedom > 0.0)) throw std::domain_error("Student's t needs degrees of freedom > 0");
  if (std::isnan(t)) return std::numeric_limits<double>::quiet_NaN();
  if (std::isinf(t)) return 0.0;
  const double nu = degrees_of_freedom;
  return regularized_incomplete_beta(nu / 2.0, 0.5, nu / (nu + t * t));
}

double student_t_cdf(double t, double degrees_of_freedom) {
  const double tail = 0.5 * student_t_two_sided_p(t, degrees_of_freedom);  // P(T >= |t|)
  return t < 0.0 ? tail : 1.0 - tail;
}

// P(F <= f) = I_{d1 f/(d1 f + d2)}(d1/2, d2/2)  (Abramowitz & Stegun 26.6.2); the upper
// tail is the same with the arguments swapped, so it is not formed as 1 − CDF.
double f_cdf(double f, double d1, double d2) {
  if (!(d1 > 0.0) || !(d2 > 0.0)) throw std::domain_error("Fisher's F needs degrees of freedom > 0");
  if (std::isnan(f)) return std::numeric_limits<double>::quiet_NaN();
  if (f <= 0.0) return 0.0;
  if (std::isinf(f)) return 1.0;
  return regularized_incomplete_beta(d1 / 2.0, d2 / 2.0, d1 * f / (d1 * f + d2));
}

double f_upper_tail(double f, double d1, double d2) {
  if (!(d1 > 0.0) || !(d2 > 0.0)) throw std::domain_error("Fisher's F needs degrees of freedom > 0");
  if (std::isnan(f)) return std::numeric_limits<double>::quiet_NaN();
  if (f <= 0.0) return 1.0;
  if (std::isinf(f)) return 0.0;
  return regularized_incomplete_beta(d2 / 2.0, d1 / 2.0, d2 / (d2 + d1 * f));
}

}  // namespace regodem::doe
