// `regodem fit`: response surfaces fitted to a CSV table of runs (src/doe/), reported as
// text and JSON, and optionally solved for the factor values that reach given targets.
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "fit_report.hpp"
#include "core/error.hpp"
#include "doe/polynomial_model.hpp"
#include "doe/response_surface_fit.hpp"
#include "doe/response_surface_solve.hpp"
#include "io/atomic_file.hpp"
#include "io/csv_table_reader.hpp"
#include "option_values.hpp"

namespace regodem::app {
namespace {

using nlohmann::json;

struct Target {
  std::string response;
  double value = 0.0;
  std::string factor;  // --then only: the factor to solve for ("" = the default)
};

struct FitInputs {
  CsvTable table;
  std::vector<std::string> factor_names;
  std::vector<std::string> factor_units;
  std::vector<std::vector<double>> x;  // per run
  std::vector<doe::FactorRange> ranges;
};

FitInputs read_inputs(const FitOptions& options) {
  FitInputs in{read_csv_table(options.runs_path), {}, {}, {}, {}};
  in.factor_names = split_list(options.factors, "--factors");
  for (std::size_t i = 0; i < in.factor_names.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (in.factor_names[i] == in.factor_names[j])
        throw InputError(fmt::format("--factors names '{}' twice", in.factor_names[i]));
  in.x.assign(in.table.rows.size(), std::vector<double>(in.factor_names.size()));
  for (std::size_t i = 0; i < in.factor_names.size(); ++i) {
    in.factor_units.push_back(in.table.units[in.table.column(in.factor_names[i])]);
    const std::vector<double> values = in.table.numbers(in.factor_names[i]);
    if (values.empty()) throw InputError(fmt::format("{}: the file has no runs", options.runs_path));
    for (std::size_t r = 0; r < values.size(); ++r) in.x[r][i] = values[r];
    const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
    in.ranges.push_back({*lo, *hi});
  }
  return in;
}

/// The term list for `response`: its own `RESPONSE=...` entry, else the shared one, else
/// the full quadratic.
std::vector<doe::Term> terms_for(const FitOptions& options, const std::string& response,
                                 const std::vector<std::string>& factor_names) {
  std::optional<std::string> shared, own;
  for (const std::string& spec : options.terms) {
    if (const auto equals = spec.find('='); equals != std::string::npos) {
      if (trimmed(spec.substr(0, equals)) == response) own = spec.substr(equals + 1);
    } else {
      if (shared) throw InputError("--terms: give one term list for every response, or RESPONSE=TERMS for each");
      shared = spec;
    }
  }
  if (own) return doe::parse_terms(*own, factor_names);
  if (shared) return doe::parse_terms(*shared, factor_names);
  return doe::full_quadratic_terms(factor_names.size());
}

std::vector<Target> parse_targets(const std::string& text, const std::string& option, bool allow_factor) {
  std::vector<Target> targets;
  for (const std::string& item : split_list(text, option)) {
    const std::string form = allow_factor ? "RESPONSE=TARGET[:FACTOR]" : "RESPONSE=TARGET";
    auto [response, value] = split_name_value(item, option, form);
    Target t{response, 0.0, ""};
    if (const auto colon = value.find(':'); allow_factor && colon != std::string::npos) {
      t.factor = trimmed(value.substr(colon + 1));
      value = value.substr(0, colon);
    }
    t.value = parse_number(value, option + " " + response);
    targets.push_back(t);
  }
  return targets;
}

struct SolveRequest {
  std::vector<Target> first;  // --solve
  std::vector<Target> then;   // --then, in order
  std::vector<std::pair<std::size_t, double>> fixed;
};

std::size_t factor_index(const std::vector<std::string>& names, const std::string& name, const std::string& option) {
  const auto found = std::find(names.begin(), names.end(), name);
  if (found == names.end()) {
    std::string known;
    for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
    throw InputError(fmt::format("{}: '{}' is not one of the factors ({})", option, name, known));
  }
  return static_cast<std::size_t>(found - names.begin());
}

const doe::ResponseSurfaceFit& fit_of(const std::vector<doe::ResponseSurfaceFit>& fits, const std::string& response,
                                      const std::string& option) {
  for (const auto& fit : fits)
    if (fit.response_name == response) return fit;
  throw InputError(fmt::format("{}: '{}' is not a fitted response (name it with --response)", option, response));
}

std::string describe_ranges(const std::vector<std::string>& outside, const FitInputs& in) {
  std::string text;
  for (const std::string& name : outside) {
    const auto& range = in.ranges[factor_index(in.factor_names, name, "")];
    text += fmt::format("{}{} outside {} to {}", text.empty() ? "" : "; ", name, format_number(range.low),
                        format_number(range.high));
  }
  return text;
}

json solve_and_report(const FitOptions& options, const FitInputs& in, const std::vector<doe::ResponseSurfaceFit>& fits) {
  SolveRequest request;
  for (const std::string& text : options.solve)
    for (const Target& t : parse_targets(text, "--solve", false)) request.first.push_back(t);
  for (const std::string& text : options.then)
    for (const Target& t : parse_targets(text, "--then", true)) request.then.push_back(t);
  std::vector<double> x(in.factor_names.size(), 0.0);
  std::vector<bool> is_fixed(in.factor_names.size(), false);
  for (const std::string& text : options.fix) {
    for (const std::string& item : split_list(text, "--fix")) {
      const auto [name, value] = split_name_value(item, "--fix", "FACTOR=VALUE");
      const std::size_t f = factor_index(in.factor_names, name, "--fix");
      if (is_fixed[f]) throw InputError(fmt::format("--fix names '{}' twice", name));
      x[f] = parse_number(value, "--fix " + name);
      is_fixed[f] = true;
    }
  }
  for (const Target& t : request.first) fit_of(fits, t.response, "--solve");
  for (const Target& t : request.then) fit_of(fits, t.response, "--then");

  std::vector<std::size_t> free_factors;
  for (std::size_t f = 0; f < x.size(); ++f)
    if (!is_fixed[f]) free_factors.push_back(f);
  // Free factors start at the centre of their range (only the solvers' starting guess).
  for (const std::size_t f : free_factors) x[f] = 0.5 * (in.ranges[f].low + in.ranges[f].high);

  std::string fixed_text;
  for (std::size_t f = 0; f < x.size(); ++f)
    if (is_fixed[f]) fixed_text += fmt::format("{}{} = {}", fixed_text.empty() ? "" : ", ", in.factor_names[f], format_number(x[f]));

  json j;
  std::vector<doe::Solution> solutions;
  if (request.first.size() == 1) {
    // One equation, one unknown, then the --then steps: the closed-form sequential solve.
    if (free_factors.size() != 1)
      throw InputError(fmt::format("--solve {}: one target needs exactly one free factor, and {} are free; hold the "
                                   "others with --fix FACTOR=VALUE (or give as many targets as free factors)",
                                   request.first[0].response, free_factors.size()));
    std::vector<doe::SolveStep> steps{{&fit_of(fits, request.first[0].response, "--solve").model,
                                       request.first[0].value, free_factors[0]}};
    std::vector<bool> solved(x.size(), false);
    solved[free_factors[0]] = true;
    for (const Target& t : request.then) {
      std::size_t f = 0;
      if (!t.factor.empty()) {
        f = factor_index(in.factor_names, t.factor, "--then");
      } else {
        // Default: the one --fix factor that no earlier step has solved (the paper's order).
        std::vector<std::size_t> candidates;
        for (std::size_t g = 0; g < x.size(); ++g)
          if (is_fixed[g] && !solved[g]) candidates.push_back(g);
        if (candidates.size() != 1)
          throw InputError(fmt::format("--then {}: name the factor to solve for, as {}={}:FACTOR", t.response,
                                       t.response, format_number(t.value, 17)));
        f = candidates[0];
      }
      steps.push_back({&fit_of(fits, t.response, "--then").model, t.value, f});
      solved[f] = true;
    }
    fmt::print("Solve {} = {} for {}{}", request.first[0].response, format_number(request.first[0].value, 10),
               in.factor_names[free_factors[0]], fixed_text.empty() ? "" : ", with " + fixed_text);
    for (std::size_t s = 1; s < steps.size(); ++s)
      fmt::print("; then {} = {} for {}", request.then[s - 1].response, format_number(steps[s].target, 10),
                 in.factor_names[steps[s].free_factor]);
    fmt::print(" (closed form, each step quadratic in its factor):\n");
    solutions = doe::solve_sequentially(steps, x, in.ranges);
    j["mode"] = "sequential";
    j["steps"] = json::array();
    for (std::size_t s = 0; s < steps.size(); ++s)
      j["steps"].push_back({{"response", s == 0 ? request.first[0].response : request.then[s - 1].response},
                            {"target", steps[s].target},
                            {"factor", in.factor_names[steps[s].free_factor]}});
  } else {
    if (!request.then.empty())
      throw InputError("--then follows a one-target --solve; with several targets they are solved together");
    if (request.first.size() != free_factors.size())
      throw InputError(fmt::format("--solve gives {} targets, and {} factors are free: give as many targets as free "
                                   "factors (hold the others with --fix FACTOR=VALUE)",
                                   request.first.size(), free_factors.size()));
    std::vector<const doe::PolynomialModel*> models;
    std::vector<double> targets;
    std::string names;
    for (const Target& t : request.first) {
      for (const auto* m : models)
        if (m == &fit_of(fits, t.response, "--solve").model)
          throw InputError(fmt::format("--solve names '{}' twice", t.response));
      models.push_back(&fit_of(fits, t.response, "--solve").model);
      targets.push_back(t.value);
      names += fmt::format("{}{} = {}", names.empty() ? "" : ", ", t.response, format_number(t.value, 10));
    }
    std::string free_names;
    for (const std::size_t f : free_factors) free_names += (free_names.empty() ? "" : ", ") + in.factor_names[f];
    fmt::print("Solve {} together for {}{} (Newton from a grid of starts around the design range):\n", names,
               free_names, fixed_text.empty() ? "" : ", with " + fixed_text);
    solutions = doe::solve_simultaneously(models, targets, x, free_factors, in.ranges);
    j["mode"] = "simultaneous";
    j["targets"] = json::array();
    for (const Target& t : request.first) j["targets"].push_back({{"response", t.response}, {"target", t.value}});
  }

  j["solutions"] = json::array();
  if (solutions.empty()) fmt::print("  no real root: the surfaces do not reach these targets\n");
  for (std::size_t s = 0; s < solutions.size(); ++s) {
    const doe::Solution& solution = solutions[s];
    fmt::print("  {}. {}{}\n", s + 1, solution_text(solution, in.factor_names, fits),
               solution.inside() ? "" : "   OUTSIDE the design range");
    if (!solution.inside())
      fmt::print(stderr, "regodem: warning: root {} lies outside the design range ({}): the surface is extrapolated "
                         "there\n",
                 s + 1, describe_ranges(solution.outside, in));
    j["solutions"].push_back(solution_json(solution, in.factor_names, fits));
  }
  return j;
}

}  // namespace

CLI::App* add_fit_command(CLI::App& app, FitOptions& options) {
  CLI::App* fit = app.add_subcommand(
      "fit", "Fit response surfaces to a CSV table of runs (coefficients, R², ANOVA), and solve them for targets");
  fit->add_option("RUNS", options.runs_path, "CSV file of runs: a header of `name [unit]` or `name`, one run a line")
      ->required()
      ->check(CLI::ExistingFile);
  fit->add_option("--factors", options.factors, "The factor columns, comma-separated")
      ->type_name("A,B,...")
      ->required();
  fit->add_option("--response", options.responses, "A response column; repeatable")
      ->type_name("NAME")
      ->required()
      ->allow_extra_args(false);
  fit->add_option("--terms", options.terms,
                  "Model terms besides the intercept, e.g. \"A,B,B^2,A*B\" (default: full quadratic); "
                  "RESPONSE=TERMS for one response only; repeatable")
      ->type_name("TERMS")
      ->allow_extra_args(false);
  fit->add_option("--json", options.json_path, "Also write the fits (and solutions) as JSON to this file")
      ->type_name("FILE");
  fit->add_option("--solve", options.solve,
                  "Targets: RESPONSE=VALUE (one, with one free factor) or RESPONSE=VALUE,RESPONSE=VALUE,... (as many "
                  "as free factors, solved together)")
      ->type_name("RESPONSE=VALUE[,...]")
      ->allow_extra_args(false);
  fit->add_option("--fix", options.fix, "Hold a factor at a value while solving; repeatable")
      ->type_name("FACTOR=VALUE")
      ->allow_extra_args(false);
  fit->add_option("--then", options.then,
                  "After a one-target --solve, solve RESPONSE for FACTOR (default: the --fix factor not solved yet) "
                  "with the factors solved so far at their roots; repeatable, in order")
      ->type_name("RESPONSE=VALUE[:FACTOR]")
      ->allow_extra_args(false);
  fit->footer(
      "Prints, per response, the fitted equation in actual units, coefficients with standard errors, t and p values,\n"
      "R², adjusted and predicted R², and the ANOVA table (lack of fit and pure error where runs are replicated).\n"
      "Solutions outside the design range (each factor's smallest to largest value in RUNS) are marked and warned\n"
      "about. See docs/calibration.md.");
  return fit;
}

int run_fit(const FitOptions& options) {
  try {
    if (options.solve.empty() && (!options.fix.empty() || !options.then.empty()))
      throw InputError("--fix and --then go with --solve");
    const FitInputs in = read_inputs(options);
    std::vector<doe::ResponseSurfaceFit> fits;
    json j;
    j["runs_file"] = options.runs_path;
    j["factors"] = json::array();
    for (std::size_t i = 0; i < in.factor_names.size(); ++i)
      j["factors"].push_back({{"name", in.factor_names[i]},
                              {"unit", in.factor_units[i]},
                              {"low", in.ranges[i].low},
                              {"high", in.ranges[i].high}});
    for (const std::string& spec : options.terms) {
      if (const auto equals = spec.find('='); equals != std::string::npos) {
        const std::string response = trimmed(spec.substr(0, equals));
        if (std::find(options.responses.begin(), options.responses.end(), response) == options.responses.end())
          throw InputError(fmt::format("--terms {}: '{}' is not a fitted response (name it with --response)", spec,
                                       response));
      }
    }
    j["responses"] = json::array();
    for (const std::string& response : options.responses) {
      for (const auto& fit : fits)
        if (fit.response_name == response) throw InputError(fmt::format("--response names '{}' twice", response));
      if (std::find(in.factor_names.begin(), in.factor_names.end(), response) != in.factor_names.end())
        throw InputError(fmt::format("'{}' is named both as a factor and as a response", response));
      const std::vector<double> y = in.table.numbers(response);
      const std::string unit = in.table.units[in.table.column(response)];
      fits.push_back(
          doe::fit_response_surface(in.x, y, in.factor_names, terms_for(options, response, in.factor_names), response));
      fmt::print("{}", fit_report_text(fits.back(), unit));
      j["responses"].push_back(fit_json(fits.back(), unit));
    }
    if (!options.solve.empty()) j["solve"] = solve_and_report(options, in, fits);
    if (!options.json_path.empty()) {
      try {
        write_file_atomically(options.json_path, j.dump(2) + "\n");
      } catch (const std::system_error& error) {
        throw InputError(fmt::format("cannot write the JSON file: {}", error.what()));
      }
    }
  } catch (const InputError& error) {
    fmt::print(stderr, "regodem: error: {}\n", error.what());
    return exit_status::bad_input;
  }
  return exit_status::success;
}

}  // namespace regodem::app
