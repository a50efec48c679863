#include "doe/response_surface_solve.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/error.hpp"
#include "doe/eigen_dense.hpp"

namespace regodem::doe {
namespace {

double span(const FactorRange& range) { return std::max(range.high - range.low, 1e-300); }

/// Grid points per free factor: 31 starts for one, a few hundred for two, and a coarser
/// grid beyond so the count stays in the thousands.
int starts_per_factor(std::size_t free_count) {
  switch (free_count) {
    case 1: return 31;
    case 2: return 21;
    case 3: return 11;
    default: return 5;
  }
}

/// The starts cover the design range widened by one range-width on each side, so that
/// roots just outside it (which must be reported, flagged) are found too.
constexpr double start_margin_spans = 1.0;

/// Newton's method from `x` for models[i](x) = targets[i], moving only `free_factors`.
/// Returns false when it stalls (the line search finds no decrease) or wanders off.
bool newton(const std::vector<const PolynomialModel*>& models, const std::vector<double>& targets,
            std::vector<double>& x, const std::vector<std::size_t>& free_factors,
            const std::vector<FactorRange>& ranges) {
  const auto m = static_cast<Eigen::Index>(free_factors.size());
  constexpr int max_iterations = 200;
  // Residuals relative to the targets' size, so that one tolerance serves K and J/kg°C alike.
  Eigen::VectorXd residual_scale(m);
  for (Eigen::Index i = 0; i < m; ++i) residual_scale(i) = std::max(1.0, std::fabs(targets[static_cast<std::size_t>(i)]));
  auto residual = [&](const std::vector<double>& at) {
    Eigen::VectorXd r(m);
    for (Eigen::Index i = 0; i < m; ++i)
      r(i) = (models[static_cast<std::size_t>(i)]->evaluate(at) - targets[static_cast<std::size_t>(i)]) /
             residual_scale(i);
    return r;
  };
  Eigen::VectorXd r = residual(x);
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    if (r.cwiseAbs().maxCoeff() < 1e-13) return true;
    Eigen::MatrixXd jacobian(m, m);
    for (Eigen::Index i = 0; i < m; ++i)
      for (Eigen::Index j = 0; j < m; ++j)
        jacobian(i, j) = models[static_cast<std::size_t>(i)]->derivative(x, free_factors[static_cast<std::size_t>(j)]) /
                         residual_scale(i);
    const Eigen::VectorXd step = jacobian.colPivHouseholderQr().solve(-r);
    if (!step.allFinite()) return false;
    double length = 1.0;
    std::vector<double> trial = x;
    Eigen::VectorXd trial_r;
    while (true) {
      for (Eigen::Index j = 0; j < m; ++j) {
        const std::size_t f = free_factors[static_cast<std::size_t>(j)];
        trial[f] = x[f] + length * step(j);
      }
      trial_r = residual(trial);
      if (trial_r.squaredNorm() < r.squaredNorm()) break;
      length *= 0.5;
      if (length < 1e-6) return r.cwiseAbs().maxCoeff() < 1e-10;
    }
    x = trial;
    r = trial_r;
    for (const std::size_t f : free_factors)
      if (std::fabs(x[f] - ranges[f].low) > 1e3 * span(ranges[f])) return false;  // ran off to infinity
  }
  return r.cwiseAbs().maxCoeff() < 1e-10;
}

}  // namespace

std::vector<std::string> factors_outside(const std::vector<double>& x, const std::vector<FactorRange>& ranges,
                                         const std::vector<std::string>& names) {
  std::vector<std::string> outside;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double margin = 1e-9 * span(ranges[i]);
    if (x[i] < ranges[i].low - margin || x[i] > ranges[i].high + margin) outside.push_back(names[i]);
  }
  return outside;
}

std::vector<double> solve_for_one_factor(const PolynomialModel& model, double target, const std::vector<double>& x,
                                         std::size_t free_factor) {
  // The surface as a·t² + b·t + c in the free factor t: each term contributes its
  // coefficient times the other factors' part to the power of t it carries.
  double by_power[3] = {-target, 0.0, 0.0};
  std::vector<double> at = x;
  at[free_factor] = 1.0;
  for (std::size_t j = 0; j < model.terms.size(); ++j) {
    const int power = model.terms[j].powers[free_factor];
    by_power[power] += model.coefficients[j] * model.terms[j].value(at);
  }
  const double a = by_power[2], b = by_power[1], c = by_power[0];
  if (a == 0.0 && b == 0.0)
    throw InputError(fmt::format("the surface does not depend on {} at these settings: it cannot be solved for it",
                                 model.factor_names[free_factor]));
  std::vector<double> roots;
  if (a == 0.0) {
    // Beyond the largest double (y = 1e308 on a shallow line): no value a factor can take.
    if (std::isfinite(-c / b)) roots.push_back(-c / b);
    return roots;
  }
  const double discriminant = b * b - 4.0 * a * c;
  // Not finite: the target is so far out (y = 1e308) that b² − 4ac overflows, and both
  // roots would come out as ±inf and 0, the second one no root at all.
  if (discriminant < 0.0 || !std::isfinite(discriminant)) return roots;
  // q = −(b + sgn(b)·√D)/2; roots q/a and c/q: no subtraction of nearly equal numbers.
  const double q = -0.5 * (b + std::copysign(std::sqrt(discriminant), b));
  roots.push_back(q / a);
  if (q != 0.0 && discriminant > 0.0) roots.push_back(c / q);
  // A root so far out that the surface overflows there (A² past the largest double) is
  // not one a factor can take either.
  std::erase_if(roots, [&](double root) {
    std::vector<double> point = x;
    point[free_factor] = root;
    return !std::isfinite(model.evaluate(point));
  });
  std::sort(roots.begin(), roots.end());
  return roots;
}

std::vector<Solution> solve_sequentially(const std::vector<SolveStep>& steps, const std::vector<double>& start,
                                         const std::vector<FactorRange>& ranges) {
  if (steps.empty()) return {};
  std::vector<std::vector<double>> chains{start};
  for (const SolveStep& step : steps) {
    std::vector<std::vector<double>> next;
    for (const std::vector<double>& x : chains) {
      for (const double root : solve_for_one_factor(*step.model, step.target, x, step.free_factor)) {
        std::vector<double> solved = x;
        solved[step.free_factor] = root;
        next.push_back(std::move(solved));
      }
    }
    chains = std::move(next);
  }
  std::vector<Solution> solutions;
  for (std::vector<double>& x : chains) {
    Solution s{std::move(x), {}};
    s.outside = factors_outside(s.factors, ranges, steps.front().model->factor_names);
    solutions.push_back(std::move(s));
  }
  return solutions;
}

std::vector<Solution> solve_simultaneously(const std::vector<const PolynomialModel*>& models,
                                           const std::vector<double>& targets, const std::vector<double>& x,
                                           const std::vector<std::size_t>& free_factors,
                                           const std::vector<FactorRange>& ranges) {
  if (models.empty() || models.size() != targets.size() || models.size() != free_factors.size())
    throw InputError(fmt::format("{} targets for {} free factors: give as many targets as free factors",
                                 targets.size(), free_factors.size()));
  const std::size_t m = free_factors.size();
  const int per_factor = starts_per_factor(m);
  std::size_t start_count = 1;
  for (std::size_t i = 0; i < m; ++i) start_count *= static_cast<std::size_t>(per_factor);

  std::vector<std::vector<double>> roots;
  for (std::size_t counter = 0; counter < start_count; ++counter) {
    std::vector<double> start = x;
    std::size_t rest = counter;
    for (const std::size_t f : free_factors) {
      const auto index = static_cast<double>(rest % static_cast<std::size_t>(per_factor));
      rest /= static_cast<std::size_t>(per_factor);
      start[f] = ranges[f].low - start_margin_spans * span(ranges[f]) +
                 (1.0 + 2.0 * start_margin_spans) * span(ranges[f]) * index / (per_factor - 1);
    }
    if (!newton(models, targets, start, free_factors, ranges)) continue;
    const bool known = std::any_of(roots.begin(), roots.end(), [&](const std::vector<double>& root) {
      for (const std::size_t f : free_factors)
        if (std::fabs(root[f] - start[f]) > 1e-6 * span(ranges[f])) return false;
      return true;
    });
    if (!known) roots.push_back(start);
  }
  // A stable order: by the first free factor, then the next.
  std::sort(roots.begin(), roots.end(), [&](const std::vector<double>& p, const std::vector<double>& q) {
    for (const std::size_t f : free_factors)
      if (p[f] != q[f]) return p[f] < q[f];
    return false;
  });
  std::vector<Solution> solutions;
  for (std::vector<double>& root : roots) {
    Solution s{std::move(root), {}};
    s.outside = factors_outside(s.factors, ranges, models.front()->factor_names);
    solutions.push_back(std::move(s));
  }
  return solutions;
}

}  // namespace regodem::doe
