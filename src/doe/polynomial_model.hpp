#pragma once
// A response surface as a polynomial in the factors, of degree two at most: the
// intercept, linear terms, squares and two-factor interactions (Box & Draper, Response
// Surfaces, Mixtures, and Ridge Analyses, 2nd ed., ch. 7). Coefficients are in actual
// (not coded) units, as the paper's Eq. 6 and 7 are written.
#include <string>
#include <vector>

namespace regodem::doe {

/// One monomial: the power of each factor (all zero: the intercept).
struct Term {
  std::vector<int> powers;

  int degree() const;
  bool is_intercept() const { return degree() == 0; }
  double value(const std::vector<double>& x) const;
  /// ∂(term)/∂x_factor.
  double derivative(const std::vector<double>& x, std::size_t factor) const;
  bool operator==(const Term&) const = default;
};

/// "1" for the intercept, "A", "A^2", "A*B".
std::string term_name(const Term& term, const std::vector<std::string>& factor_names);

/// Intercept, linear terms, two-factor interactions, squares (Design-Expert's order).
std::vector<Term> full_quadratic_terms(std::size_t factor_count);

/// Parses a comma-separated term list such as "A,B,B^2,A*B" (A*A is A^2). The intercept
/// is always part of the model, listed or not ("1" may be written). Throws InputError
/// for an unknown factor, a term of degree above two, or a term listed twice.
std::vector<Term> parse_terms(const std::string& spec, const std::vector<std::string>& factor_names);

struct PolynomialModel {
  std::vector<std::string> factor_names;
  std::vector<Term> terms;
  std::vector<double> coefficients;  // one per term

  double evaluate(const std::vector<double>& x) const;
  double derivative(const std::vector<double>& x, std::size_t factor) const;
  /// "T_d = 195.03 + 0.001741*C_wall - ..." with `digits` significant digits.
  std::string equation(const std::string& response_name, int digits = 6) const;
};

}  // namespace regodem::doe
