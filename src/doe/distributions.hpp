#pragma once
// The distribution functions that regression statistics need: the regularized incomplete
// beta function (DLMF §8.17) and, from it, the CDFs of Student's t and Fisher's F
// (Abramowitz & Stegun 26.5.27, 26.6.2, 26.7.1). p-values are computed from the
// upper tail directly, so a tiny p is not lost to cancellation in 1 - CDF.
namespace regodem::doe {

/// I_x(a, b), the regularized incomplete beta function, for a, b > 0 and 0 <= x <= 1.
/// Throws std::domain_error outside that domain. Relative accuracy about 1e-14.
double regularized_incomplete_beta(double a, double b, double x);

/// P(T <= t) for Student's t with `degrees_of_freedom` > 0 (not necessarily whole).
double student_t_cdf(double t, double degrees_of_freedom);
/// P(|T| >= |t|): the two-sided p-value of a t statistic.
double student_t_two_sided_p(double t, double degrees_of_freedom);

/// P(F <= f) for Fisher's F with (d1, d2) degrees of freedom; 0 for f <= 0.
double f_cdf(double f, double d1, double d2);
/// P(F >= f): the upper tail, the p-value of an F statistic; 1 for f <= 0.
double f_upper_tail(double f, double d1, double d2);

}  // namespace regodem::doe
