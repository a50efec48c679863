#include "doe/central_composite_design.hpp"

#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "core/error.hpp"
#include "core/rng.hpp"

namespace regodem::doe {
namespace {

constexpr int max_factors = 12;  // 2^12 factorial runs: far beyond a DEM calibration already

void check_inputs(const std::vector<DesignFactor>& factors, const CcdOptions& options) {
  const std::size_t k = factors.size();
  if (k == 0) throw InputError("a central composite design needs at least one factor");
  if (k > max_factors) throw InputError(fmt::format("{} factors: at most {} are supported", k, max_factors));
  for (std::size_t i = 0; i < k; ++i) {
    const DesignFactor& f = factors[i];
    if (f.name.empty()) throw InputError(fmt::format("factor {} has no name", i + 1));
    if (!std::isfinite(f.centre) || !std::isfinite(f.step) || !(f.step > 0.0))
      throw InputError(fmt::format("factor '{}': the centre must be finite and the step > 0 (centre {}, step {})",
                                   f.name, f.centre, f.step));
    for (std::size_t j = 0; j < i; ++j)
      if (factors[j].name == f.name) throw InputError(fmt::format("factor '{}' is named twice", f.name));
  }
  if (options.centre_points < 0) throw InputError("the number of centre points cannot be negative");
  if (options.alpha_kind == AlphaKind::given && !(options.alpha > 0.0 && std::isfinite(options.alpha)))
    throw InputError(fmt::format("α must be a number > 0 (given {})", options.alpha));
  // A half fraction of fewer than five factors has resolution IV or lower: two-factor
  // interactions alias each other (or main effects), and the quadratic model cannot be fitted.
  if (options.half_fraction && k < 5)
    throw InputError(fmt::format("a half-fraction factorial part needs at least 5 factors (resolution V); "
                                 "with {} use the full factorial",
                                 k));
}

DesignPoint make_point(const std::vector<DesignFactor>& factors, PointType type, std::vector<double> coded) {
  DesignPoint point;
  point.type = type;
  point.actual.resize(coded.size());
  for (std::size_t i = 0; i < coded.size(); ++i) point.actual[i] = factors[i].actual(coded[i]);
  point.coded = std::move(coded);
  return point;
}

}  // namespace

const char* point_type_name(PointType type) {
  switch (type) {
    case PointType::factorial: return "factorial";
    case PointType::axial: return "axial";
    case PointType::centre: return "centre";
  }
  return "?";
}

double rotatable_alpha(int factorial_points) { return std::pow(static_cast<double>(factorial_points), 0.25); }

CentralCompositeDesign make_central_composite_design(const std::vector<DesignFactor>& factors,
                                                     const CcdOptions& options) {
  check_inputs(factors, options);
  const std::size_t k = factors.size();
  CentralCompositeDesign design;
  design.factors = factors;

  // Factorial part in Yates order: bit i of the counter gives factor i (0: −1, 1: +1). For a
  // half fraction the first k−1 factors run through their full factorial and the last is
  // their product (generator K = AB…J, defining relation I = AB…K).
  const std::size_t free_factors = options.half_fraction ? k - 1 : k;
  const std::size_t factorial_count = std::size_t{1} << free_factors;
  for (std::size_t counter = 0; counter < factorial_count; ++counter) {
    std::vector<double> coded(k);
    double product = 1.0;
    for (std::size_t i = 0; i < free_factors; ++i) {
      coded[i] = ((counter >> i) & 1U) != 0 ? 1.0 : -1.0;
      product *= coded[i];
    }
    if (options.half_fraction) coded[k - 1] = product;
    design.runs.push_back(make_point(factors, PointType::factorial, std::move(coded)));
  }
  design.factorial_points = static_cast<int>(factorial_count);

  switch (options.alpha_kind) {
    case AlphaKind::rotatable: design.alpha = rotatable_alpha(design.factorial_points); break;
    case AlphaKind::face: design.alpha = 1.0; break;
    case AlphaKind::given: design.alpha = options.alpha; break;
  }

  for (std::size_t i = 0; i < k; ++i) {
    for (const double sign : {-1.0, 1.0}) {
      std::vector<double> coded(k, 0.0);
      coded[i] = sign * design.alpha;
      design.runs.push_back(make_point(factors, PointType::axial, std::move(coded)));
    }
  }
  design.axial_points = static_cast<int>(2 * k);

  for (int c = 0; c < options.centre_points; ++c)
    design.runs.push_back(make_point(factors, PointType::centre, std::vector<double>(k, 0.0)));
  design.centre_points = options.centre_points;

  // CENTRE ± α STEP can overflow although both are finite (1e308 + 1.4e308): a design
  // with inf in it would be written and run.
  for (const DesignPoint& point : design.runs)
    for (std::size_t i = 0; i < k; ++i)
      if (!std::isfinite(point.actual[i]))
        throw InputError(fmt::format("factor '{}': its value at coded {:.6g} is not a finite number (centre {:.6g}, "
                                     "step {:.6g}); choose a smaller centre or step",
                                     factors[i].name, point.coded[i], factors[i].centre, factors[i].step));

  for (std::size_t r = 0; r < design.runs.size(); ++r) design.runs[r].standard_order = static_cast<int>(r + 1);

  if (options.order == RunOrder::random) {
    // Fisher–Yates (Knuth, TAOCP vol. 2, Algorithm 3.4.2P) with our own RNG: the same order
    // for a seed everywhere. floor(u·r) with u in [0, 1) is uniform on 0..r−1.
    Rng rng(options.seed);
    for (std::size_t r = design.runs.size(); r > 1; --r) {
      const auto j = static_cast<std::size_t>(rng.uniform() * static_cast<double>(r));
      std::swap(design.runs[r - 1], design.runs[j < r ? j : r - 1]);
    }
  }
  return design;
}

std::string header_name(const DesignFactor& factor) {
  return factor.unit.empty() ? factor.name : fmt::format("{} [{}]", factor.name, factor.unit);
}

std::string design_csv(const CentralCompositeDesign& design) {
  std::string text = "run,std_order,point_type";
  for (const auto& factor : design.factors) text += fmt::format(",{}_coded", factor.name);
  for (const auto& factor : design.factors) text += "," + header_name(factor);
  text += "\n";
  for (std::size_t r = 0; r < design.runs.size(); ++r) {
    const DesignPoint& point = design.runs[r];
    text += fmt::format("{},{},{}", r + 1, point.standard_order, point_type_name(point.type));
    for (const double v : point.coded) text += fmt::format(",{}", v);  // shortest text that reads back exactly
    for (const double v : point.actual) text += fmt::format(",{}", v);
    text += "\n";
  }
  return text;
}

}  // namespace regodem::doe
