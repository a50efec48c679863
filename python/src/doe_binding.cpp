// Designs, fits and solves on numpy arrays (docs/python.md, "Designs and fits"): the code
// behind `regodem doe ccd`, `regodem fit` and its --solve, without CSV files between.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "bindings.hpp"
#include "core/error.hpp"
#include "doe/central_composite_design.hpp"
#include "doe/polynomial_model.hpp"
#include "doe/response_surface_fit.hpp"
#include "doe/response_surface_solve.hpp"

namespace py = pybind11;

namespace regodem::python {
namespace {

using namespace regodem::doe;

py::array_t<double> matrix(const std::vector<std::vector<double>>& rows, std::size_t columns) {
  py::array_t<double> a({static_cast<py::ssize_t>(rows.size()), static_cast<py::ssize_t>(columns)});
  auto r = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (std::size_t j = 0; j < columns; ++j) r(static_cast<py::ssize_t>(i), static_cast<py::ssize_t>(j)) = rows[i][j];
  return a;
}

std::vector<std::vector<double>> rows_of(const py::array_t<double, py::array::forcecast>& x, std::size_t columns,
                                         const char* what) {
  if (x.ndim() != 2 || static_cast<std::size_t>(x.shape(1)) != columns)
    throw InputError(fmt::format("{} must be a 2-d array with one column per factor ({})", what, columns));
  const auto r = x.unchecked<2>();
  std::vector<std::vector<double>> rows(static_cast<std::size_t>(r.shape(0)), std::vector<double>(columns));
  for (py::ssize_t i = 0; i < r.shape(0); ++i)
    for (std::size_t j = 0; j < columns; ++j) rows[static_cast<std::size_t>(i)][j] = r(i, static_cast<py::ssize_t>(j));
  return rows;
}

std::size_t factor_index(const PolynomialModel& model, const std::string& name) {
  for (std::size_t f = 0; f < model.factor_names.size(); ++f)
    if (model.factor_names[f] == name) return f;
  throw InputError(fmt::format("the model has no factor '{}' (it has {})", name, fmt::join(model.factor_names, ", ")));
}

py::dict ccd(const std::vector<std::string>& names, const std::vector<double>& centres,
             const std::vector<double>& steps, const std::vector<std::string>& units, const std::string& alpha,
             int centre_points, bool half_fraction, bool random_order, std::uint64_t seed) {
  if (centres.size() != names.size() || steps.size() != names.size() || units.size() != names.size())
    throw InputError("ccd: give a centre, a step and a unit for every factor");
  std::vector<DesignFactor> factors;
  for (std::size_t f = 0; f < names.size(); ++f) factors.push_back({names[f], units[f], centres[f], steps[f]});
  CcdOptions options;
  if (alpha == "rotatable") {
    options.alpha_kind = AlphaKind::rotatable;
  } else if (alpha == "face") {
    options.alpha_kind = AlphaKind::face;
  } else {
    options.alpha_kind = AlphaKind::given;
    try {
      options.alpha = std::stod(alpha);
    } catch (const std::exception&) {
      throw InputError(fmt::format("ccd: alpha must be 'rotatable', 'face' or a number, got '{}'", alpha));
    }
  }
  options.centre_points = centre_points;
  options.half_fraction = half_fraction;
  options.order = random_order ? RunOrder::random : RunOrder::standard;
  options.seed = seed;
  const CentralCompositeDesign design = make_central_composite_design(factors, options);
  std::vector<std::vector<double>> coded, actual;
  std::vector<std::string> types;
  std::vector<int> standard_order;
  for (const DesignPoint& p : design.runs) {
    coded.push_back(p.coded);
    actual.push_back(p.actual);
    types.emplace_back(point_type_name(p.type));
    standard_order.push_back(p.standard_order);
  }
  py::dict d;
  d["factors"] = names;
  d["alpha"] = design.alpha;
  d["coded"] = matrix(coded, names.size());
  d["actual"] = matrix(actual, names.size());
  d["point_type"] = types;
  d["standard_order"] = standard_order;
  d["csv"] = design_csv(design);
  return d;
}

}  // namespace

void bind_doe(py::module_& m) {
  m.def("ccd", &ccd, py::arg("names"), py::arg("centres"), py::arg("steps"), py::arg("units"), py::arg("alpha"),
        py::arg("centre_points"), py::arg("half_fraction"), py::arg("random_order"), py::arg("seed"));

  py::class_<ResponseSurfaceFit>(m, "Fit", "A fitted response surface with its statistics (regodem fit)")
      .def_readonly("response", &ResponseSurfaceFit::response_name)
      .def_property_readonly("factors", [](const ResponseSurfaceFit& f) { return f.model.factor_names; })
      .def_property_readonly("terms",
                             [](const ResponseSurfaceFit& f) {
                               std::vector<std::string> names;
                               for (const Term& t : f.model.terms) names.push_back(term_name(t, f.model.factor_names));
                               return names;
                             })
      .def_property_readonly("coefficients", [](const ResponseSurfaceFit& f) { return f.model.coefficients; })
      .def_property_readonly("standard_errors",
                             [](const ResponseSurfaceFit& f) {
                               std::vector<double> e;
                               for (const CoefficientEstimate& c : f.coefficients) e.push_back(c.standard_error);
                               return e;
                             })
      .def_property_readonly("p_values",
                             [](const ResponseSurfaceFit& f) {
                               std::vector<double> p;
                               for (const CoefficientEstimate& c : f.coefficients) p.push_back(c.p_value);
                               return p;
                             })
      .def_readonly("runs", &ResponseSurfaceFit::runs)
      .def_readonly("r_squared", &ResponseSurfaceFit::r_squared)
      .def_readonly("adjusted_r_squared", &ResponseSurfaceFit::adjusted_r_squared)
      .def_readonly("predicted_r_squared", &ResponseSurfaceFit::predicted_r_squared)
      .def_readonly("press", &ResponseSurfaceFit::press)
      .def_readonly("residual_std_dev", &ResponseSurfaceFit::residual_std_dev)
      .def_readonly("fitted", &ResponseSurfaceFit::fitted)
      .def_readonly("leverage", &ResponseSurfaceFit::leverage)
      .def_property_readonly("anova",
                             [](const ResponseSurfaceFit& f) {
                               py::list rows;
                               for (const AnovaRow& r : f.anova) {
                                 py::dict d;
                                 d["source"] = r.source;
                                 d["sum_of_squares"] = r.sum_of_squares;
                                 d["degrees_of_freedom"] = r.degrees_of_freedom;
                                 d["mean_square"] = r.mean_square;
                                 d["f_value"] = r.f_value;
                                 d["p_value"] = r.p_value;
                                 rows.append(d);
                               }
                               return rows;
                             })
      .def(
          "equation", [](const ResponseSurfaceFit& f, int digits) { return f.model.equation(f.response_name, digits); },
          py::arg("digits") = 6)
      .def(
          "predict",
          [](const ResponseSurfaceFit& f, const py::array_t<double, py::array::forcecast>& x) {
            const std::vector<std::vector<double>> rows = rows_of(x, f.model.factor_names.size(), "x");
            std::vector<double> y;
            for (const std::vector<double>& row : rows) y.push_back(f.model.evaluate(row));
            return py::array_t<double>(static_cast<py::ssize_t>(y.size()), y.data());
          },
          py::arg("x"), "The surface at each row of x (actual units, one column per factor)")
      .def(
          "solve_for",
          [](const ResponseSurfaceFit& f, double target, const std::string& factor, const std::vector<double>& at) {
            if (at.size() != f.model.factor_names.size())
              throw InputError(fmt::format("solve_for: `at` gives {} values for {} factors", at.size(),
                                           f.model.factor_names.size()));
            return solve_for_one_factor(f.model, target, at, factor_index(f.model, factor));
          },
          py::arg("target"), py::arg("factor"), py::arg("at"),
          "Every real value of `factor` at which the surface reaches `target`, the others held at `at`");

  m.def(
      "fit",
      [](const py::array_t<double, py::array::forcecast>& x, const std::vector<double>& y,
         const std::vector<std::string>& factors, const std::string& terms, const std::string& response) {
        const std::vector<std::vector<double>> rows = rows_of(x, factors.size(), "x");
        if (rows.size() != y.size())
          throw InputError(fmt::format("fit: {} rows of x but {} responses", rows.size(), y.size()));
        const std::vector<Term> model_terms =
            terms.empty() ? full_quadratic_terms(factors.size()) : parse_terms(terms, factors);
        return fit_response_surface(rows, y, factors, model_terms, response);
      },
      py::arg("x"), py::arg("y"), py::arg("factors"), py::arg("terms"), py::arg("response"));

  m.def(
      "solve",
      [](const std::vector<const ResponseSurfaceFit*>& fits, const std::vector<double>& targets,
         const std::vector<double>& at, const std::vector<std::string>& free, const std::vector<double>& low,
         const std::vector<double>& high) {
        if (fits.empty() || fits.size() != targets.size() || fits.size() != free.size())
          throw InputError("solve: give as many targets and free factors as fits");
        const PolynomialModel& first = fits.front()->model;
        if (at.size() != first.factor_names.size() || low.size() != at.size() || high.size() != at.size())
          throw InputError(fmt::format("solve: `at`, `low` and `high` need one value per factor ({})",
                                       first.factor_names.size()));
        std::vector<const PolynomialModel*> models;
        std::vector<std::size_t> free_factors;
        for (std::size_t i = 0; i < fits.size(); ++i) {
          if (fits[i]->model.factor_names != first.factor_names)
            throw InputError("solve: every fit must be over the same factors");
          models.push_back(&fits[i]->model);
          free_factors.push_back(factor_index(first, free[i]));
        }
        std::vector<FactorRange> ranges;
        for (std::size_t f = 0; f < at.size(); ++f) ranges.push_back({low[f], high[f]});
        py::list out;
        for (const Solution& s : solve_simultaneously(models, targets, at, free_factors, ranges)) {
          py::dict d;
          d["factors"] = s.factors;
          d["outside"] = s.outside;
          d["inside"] = s.inside();
          out.append(d);
        }
        return out;
      },
      py::arg("fits"), py::arg("targets"), py::arg("at"), py::arg("free"), py::arg("low"), py::arg("high"));
}

}  // namespace regodem::python
