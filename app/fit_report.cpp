// The fit report of `regodem fit`, also written by `regodem calibrate` (fit.txt, fit.json).
#include "fit_report.hpp"

#include <cmath>

#include <fmt/format.h>

namespace regodem::app {

using nlohmann::json;

std::string format_number(double value, int digits) {
  if (std::isnan(value)) return "n/a";
  return fmt::format("{:.{}g}", value, digits);
}

namespace {

std::string p_text(double p) {
  if (std::isnan(p)) return "";
  return p < 1e-4 ? "< 0.0001" : fmt::format("{:.4f}", p);
}

}  // namespace

std::string fit_report_text(const doe::ResponseSurfaceFit& fit, const std::string& unit) {
  std::string text;
  const std::string title = unit.empty() ? fit.response_name : fmt::format("{} [{}]", fit.response_name, unit);
  text += fmt::format("Response {}: {} runs, {} terms, {} residual degrees of freedom\n", title, fit.runs,
                      fit.parameters, fit.residual_degrees_of_freedom);
  text += fmt::format("  {}\n\n", fit.model.equation(fit.response_name));
  text +=
      fmt::format("  {:<24} {:>14} {:>12} {:>10} {:>10}\n", "term", "coefficient", "std error", "t value", "p value");
  for (const auto& c : fit.coefficients)
    text += fmt::format("  {:<24} {:>14} {:>12} {:>10} {:>10}\n", c.term, format_number(c.estimate),
                        format_number(c.standard_error, 4), format_number(c.t_value, 4), p_text(c.p_value));
  text += fmt::format("\n  R² {:.4f}   adjusted R² {:.4f}   predicted R² {}   std dev {}   mean {}   PRESS {}\n\n",
                      fit.r_squared, fit.adjusted_r_squared,
                      std::isnan(fit.predicted_r_squared) ? "n/a (a run has leverage 1)"
                                                          : fmt::format("{:.4f}", fit.predicted_r_squared),
                      format_number(fit.residual_std_dev, 4), format_number(fit.response_mean),
                      format_number(fit.press, 4));
  text += fmt::format("  ANOVA (terms: partial sums of squares)\n");
  text += fmt::format("  {:<24} {:>14} {:>4} {:>14} {:>10} {:>10}\n", "source", "sum of squares", "df", "mean square",
                      "F value", "p value");
  for (const auto& row : fit.anova) {
    const bool term_row = row.source != "model" && row.source != "residual" && row.source != "lack of fit" &&
                          row.source != "pure error" && row.source != "total";
    const bool sub_row = row.source == "lack of fit" || row.source == "pure error";
    const std::string source = (term_row || sub_row ? "  " : "") + row.source;
    text += fmt::format("  {:<24} {:>14} {:>4} {:>14} {:>10} {:>10}\n", source, format_number(row.sum_of_squares),
                        row.degrees_of_freedom, std::isnan(row.mean_square) ? "" : format_number(row.mean_square),
                        std::isnan(row.f_value) ? "" : format_number(row.f_value, 4), p_text(row.p_value));
  }
  if (!fit.has_lack_of_fit)
    text += fmt::format("  (no lack-of-fit test: it needs replicated runs and more distinct settings than terms)\n");
  text += "\n";
  return text;
}

json fit_json(const doe::ResponseSurfaceFit& fit, const std::string& unit) {
  json j;
  j["name"] = fit.response_name;
  j["unit"] = unit;
  j["runs"] = fit.runs;
  j["equation"] = fit.model.equation(fit.response_name, 17);
  j["coefficients"] = json::array();
  for (const auto& c : fit.coefficients)
    j["coefficients"].push_back({{"term", c.term},
                                 {"estimate", c.estimate},
                                 {"standard_error", c.standard_error},
                                 {"t_value", c.t_value},
                                 {"p_value", c.p_value}});
  j["r_squared"] = fit.r_squared;
  j["adjusted_r_squared"] = fit.adjusted_r_squared;
  j["predicted_r_squared"] = fit.predicted_r_squared;  // NaN is written as null
  j["press"] = fit.press;
  j["residual_std_dev"] = fit.residual_std_dev;
  j["residual_degrees_of_freedom"] = fit.residual_degrees_of_freedom;
  j["mean"] = fit.response_mean;
  j["anova"] = json::array();
  for (const auto& row : fit.anova)
    j["anova"].push_back({{"source", row.source},
                          {"sum_of_squares", row.sum_of_squares},
                          {"df", row.degrees_of_freedom},
                          {"mean_square", row.mean_square},
                          {"f_value", row.f_value},
                          {"p_value", row.p_value}});
  return j;
}

std::string solution_text(const doe::Solution& solution, const std::vector<std::string>& factor_names,
                          const std::vector<doe::ResponseSurfaceFit>& fits) {
  std::string values, responses;
  for (std::size_t f = 0; f < solution.factors.size(); ++f)
    values +=
        fmt::format("{}{} = {}", values.empty() ? "" : ", ", factor_names[f], format_number(solution.factors[f], 8));
  for (const auto& fit : fits)
    responses += fmt::format("{}{} = {}", responses.empty() ? "" : ", ", fit.response_name,
                             format_number(fit.model.evaluate(solution.factors), 8));
  return fmt::format("{}   (fitted: {})", values, responses);
}

json solution_json(const doe::Solution& solution, const std::vector<std::string>& factor_names,
                   const std::vector<doe::ResponseSurfaceFit>& fits) {
  json jf = json::object(), jr = json::object();
  for (std::size_t f = 0; f < solution.factors.size(); ++f) jf[factor_names[f]] = solution.factors[f];
  for (const auto& fit : fits) jr[fit.response_name] = fit.model.evaluate(solution.factors);
  return {
      {"factors", jf}, {"responses", jr}, {"inside_design_range", solution.inside()}, {"outside", solution.outside}};
}

}  // namespace regodem::app
