#include "doe/polynomial_model.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <fmt/format.h>

#include "core/error.hpp"

namespace regodem::doe {
namespace {

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  const auto last = text.find_last_not_of(" \t");
  return text.substr(first, last - first + 1);
}

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t at = text.find(separator, start);
    parts.push_back(trimmed(text.substr(start, at == std::string::npos ? std::string::npos : at - start)));
    if (at == std::string::npos) return parts;
    start = at + 1;
  }
}

std::string listed(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

Term parse_term(const std::string& item, const std::vector<std::string>& factor_names) {
  Term term{std::vector<int>(factor_names.size(), 0)};
  if (item == "1" || item == "intercept") return term;
  for (const std::string& factor : split(item, '*')) {
    std::string name = factor;
    int power = 1;
    if (const auto caret = factor.find('^'); caret != std::string::npos) {
      name = trimmed(factor.substr(0, caret));
      const std::string exponent = trimmed(factor.substr(caret + 1));
      if (exponent == "1") power = 1;
      else if (exponent == "2") power = 2;
      else
        throw InputError(fmt::format("term '{}': only powers 1 and 2 are supported (a quadratic surface)", item));
    }
    const auto found = std::find(factor_names.begin(), factor_names.end(), name);
    if (found == factor_names.end())
      throw InputError(fmt::format("term '{}': '{}' is not a factor (the factors are {})", item, name,
                                   listed(factor_names)));
    term.powers[static_cast<std::size_t>(found - factor_names.begin())] += power;
  }
  if (term.degree() > 2)
    throw InputError(fmt::format("term '{}' has degree {}; a response surface here is quadratic at most "
                                 "(linear, squares, two-factor interactions)",
                                 item, term.degree()));
  return term;
}

/// Shortest-round-trip text with `digits` significant digits, without a '+' sign.
std::string number(double value, int digits) { return fmt::format("{:.{}g}", value, digits); }

}  // namespace

int Term::degree() const { return std::accumulate(powers.begin(), powers.end(), 0); }

double Term::value(const std::vector<double>& x) const {
  double product = 1.0;
  for (std::size_t i = 0; i < powers.size(); ++i)
    for (int p = 0; p < powers[i]; ++p) product *= x[i];
  return product;
}

double Term::derivative(const std::vector<double>& x, std::size_t factor) const {
  if (powers[factor] == 0) return 0.0;
  Term reduced = *this;
  reduced.powers[factor] -= 1;
  return static_cast<double>(powers[factor]) * reduced.value(x);
}

std::string term_name(const Term& term, const std::vector<std::string>& factor_names) {
  std::string name;
  for (std::size_t i = 0; i < term.powers.size(); ++i) {
    if (term.powers[i] == 0) continue;
    if (!name.empty()) name += "*";
    name += factor_names[i];
    if (term.powers[i] > 1) name += fmt::format("^{}", term.powers[i]);
  }
  return name.empty() ? "1" : name;
}

std::vector<Term> full_quadratic_terms(std::size_t factor_count) {
  std::vector<Term> terms;
  terms.push_back(Term{std::vector<int>(factor_count, 0)});
  for (std::size_t i = 0; i < factor_count; ++i) {
    Term t{std::vector<int>(factor_count, 0)};
    t.powers[i] = 1;
    terms.push_back(t);
  }
  for (std::size_t i = 0; i < factor_count; ++i)
    for (std::size_t j = i + 1; j < factor_count; ++j) {
      Term t{std::vector<int>(factor_count, 0)};
      t.powers[i] = t.powers[j] = 1;
      terms.push_back(t);
    }
  for (std::size_t i = 0; i < factor_count; ++i) {
    Term t{std::vector<int>(factor_count, 0)};
    t.powers[i] = 2;
    terms.push_back(t);
  }
  return terms;
}

std::vector<Term> parse_terms(const std::string& spec, const std::vector<std::string>& factor_names) {
  std::vector<Term> terms{Term{std::vector<int>(factor_names.size(), 0)}};
  for (const std::string& item : split(spec, ',')) {
    if (item.empty()) throw InputError(fmt::format("term list '{}' has an empty entry", spec));
    const Term term = parse_term(item, factor_names);
    if (term.is_intercept()) continue;
    if (std::find(terms.begin(), terms.end(), term) != terms.end())
      throw InputError(fmt::format("term list '{}' names {} twice", spec, term_name(term, factor_names)));
    terms.push_back(term);
  }
  return terms;
}

double PolynomialModel::evaluate(const std::vector<double>& x) const {
  double sum = 0.0;
  for (std::size_t j = 0; j < terms.size(); ++j) sum += coefficients[j] * terms[j].value(x);
  return sum;
}

double PolynomialModel::derivative(const std::vector<double>& x, std::size_t factor) const {
  double sum = 0.0;
  for (std::size_t j = 0; j < terms.size(); ++j) sum += coefficients[j] * terms[j].derivative(x, factor);
  return sum;
}

std::string PolynomialModel::equation(const std::string& response_name, int digits) const {
  std::string text = response_name + " =";
  bool first = true;
  for (std::size_t j = 0; j < terms.size(); ++j) {
    const double c = coefficients[j];
    const std::string magnitude = number(first ? c : std::fabs(c), digits);
    const std::string sign = first ? " " : (c < 0.0 ? " - " : " + ");
    text += sign + magnitude;
    if (!terms[j].is_intercept()) text += "*" + term_name(terms[j], factor_names);
    first = false;
  }
  return text;
}

}  // namespace regodem::doe
