#pragma once
// Inverse use of fitted response surfaces: the factor values at which one or several
// responses reach given targets. Every real root is reported; a root outside the design
// range (the region the runs covered, ±α for a central composite design) is flagged, since
// the surface there is an extrapolation.
#include <string>
#include <vector>

#include "doe/polynomial_model.hpp"

namespace regodem::doe {

/// The region the runs covered, per factor.
struct FactorRange {
  double low = 0.0;
  double high = 0.0;
};

struct Solution {
  std::vector<double> factors;       // every factor's value, the fixed ones included
  std::vector<std::string> outside;  // factors whose value lies outside their design range
  bool inside() const { return outside.empty(); }
};

/// Names the factors of `x` outside `ranges` (with a margin of 1e-9 of each range).
std::vector<std::string> factors_outside(const std::vector<double>& x, const std::vector<FactorRange>& ranges,
                                         const std::vector<std::string>& names);

/// (a) One response, one free factor, the others held at `x` (the free entry is ignored):
/// the surface is a polynomial of degree ≤ 2 in the free factor, so the roots come in closed
/// form (the cancellation-free quadratic formula, Press et al., Numerical Recipes, 3rd ed.,
/// §5.6). Returns the real roots in increasing order (none when the target is out of reach).
/// Throws InputError when the response does not depend on the free factor.
std::vector<double> solve_for_one_factor(const PolynomialModel& model, double target, const std::vector<double>& x,
                                         std::size_t free_factor);

/// One step of a sequential solve: `model` reaches `target` through `free_factor`.
struct SolveStep {
  const PolynomialModel* model = nullptr;
  double target = 0.0;
  std::size_t free_factor = 0;
};

/// (c) The paper's way (Zhao et al. 2023, section 4): solve the first step with the other
/// factors at `start`, then each following step with the factors solved so far held at
/// their roots. Every root of every step is followed, so the result is every chain.
std::vector<Solution> solve_sequentially(const std::vector<SolveStep>& steps, const std::vector<double>& start,
                                         const std::vector<FactorRange>& ranges);

/// (b) Several responses at once, as many as free factors: Newton's method with a
/// backtracking line search on ‖residual‖² from a grid of starts over the design range of
/// the free factors widened by one range-width on each side; converged roots are
/// de-duplicated (1e-6 of each range apart). Roots far beyond the design range may be missed.
/// `models[i]` must reach `targets[i]`; factors not in `free_factors` stay at `x`.
std::vector<Solution> solve_simultaneously(const std::vector<const PolynomialModel*>& models,
                                           const std::vector<double>& targets, const std::vector<double>& x,
                                           const std::vector<std::size_t>& free_factors,
                                           const std::vector<FactorRange>& ranges);

}  // namespace regodem::doe
