// `regodem calibrate`: the whole calibration loop of the paper's Sections 3-4 in one
// command. The reference run gives the targets; the central composite design's points
// are run as child processes (`regodem run`), several at once; response surfaces are
// fitted and solved for the targets; a last run at the solution checks the answer.
// Every run keeps its own output directory, and a run already completed with the same
// inputs is not run again, so an interrupted calibration continues where it stopped.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "design_runs.hpp"
#include "core/error.hpp"
#include "doe/central_composite_design.hpp"
#include "doe/response_surface_fit.hpp"
#include "doe/response_surface_solve.hpp"
#include "fit_report.hpp"
#include "human_format.hpp"
#include "io/atomic_file.hpp"
#include "io/json_path.hpp"
#include "io/run_directory_lock.hpp"
#include "scenario/calibration_reader.hpp"
#include "scenario/content_hash.hpp"
#include "scenario/scenario_builder.hpp"
#include "scenario/scenario_reader.hpp"
#include "signal_handling.hpp"

namespace regodem::app {
namespace {

namespace fs = std::filesystem;
using doe::CalibrationSpec;
using nlohmann::json;
using nlohmann::ordered_json;

/// The values the reference gives: targets and pass_on --set texts.
struct ReferenceValues {
  std::vector<double> targets;  // per response
  std::vector<std::string> pass_on_set;
  ordered_json pass_on_json = ordered_json::array();
};

ReferenceValues reference_values(const CalibrationSpec& spec, const ordered_json& summary) {
  ReferenceValues values;
  for (const auto& response : spec.responses)
    values.targets.push_back(
        response.target_value ? *response.target_value
                              : summary_number(summary, *response.target_reference_path, response.where, "reference"));
  for (const doe::PassOn& p : spec.reference.pass_on) {
    ordered_json value;
    try {
      value = json_at_path(summary, p.from_json_path);
    } catch (const InputError& problem) {
      throw InputError(fmt::format("{}: in runs/reference/summary.json: {}", p.where, problem.what()));
    }
    std::string text;
    if (value.is_number()) {
      text = set_text(p.set_path, value.get<double>(), p.unit);
    } else if (value.is_string() || value.is_boolean()) {
      text = fmt::format("{}={}", p.set_path, value.is_string() ? value.get<std::string>() : value.dump());
    } else {
      throw InputError(fmt::format("{}: '{}' in runs/reference/summary.json is {}, not a value to pass on", p.where,
                                   p.from_json_path, value.dump()));
    }
    values.pass_on_set.push_back(text);
    values.pass_on_json.push_back({{"from", p.from_json_path}, {"value", value}, {"set", text}});
  }
  return values;
}

std::vector<std::string> factor_names(const CalibrationSpec& spec) {
  std::vector<std::string> names;
  for (const auto& f : spec.factors) names.push_back(f.design.name);
  return names;
}

std::vector<std::string> factor_sets(const CalibrationSpec& spec, const std::vector<double>& x) {
  std::vector<std::string> sets;
  for (std::size_t f = 0; f < spec.factors.size(); ++f)
    sets.push_back(factor_set_text(spec.factors[f], x[f]));
  return sets;
}

std::string factor_description(const CalibrationSpec& spec, const std::vector<double>& x) {
  std::string text;
  for (std::size_t f = 0; f < spec.factors.size(); ++f)
    text += fmt::format("{}{} = {:.6g}{}", text.empty() ? "" : ", ", spec.factors[f].design.name, x[f],
                        spec.factors[f].design.unit.empty() ? "" : " " + spec.factors[f].design.unit);
  return text;
}

/// Bad input found before anything runs: the scenarios read and built (as `regodem
/// validate` does) with the --set values they will get; pass_on values are not known
/// yet and are left out.
void check_scenarios(const CalibrationSpec& spec, const doe::CentralCompositeDesign& design) {
  std::vector<std::string> reference_set = spec.set;
  reference_set.insert(reference_set.end(), spec.reference.set.begin(), spec.reference.set.end());
  std::vector<std::string> point_set = spec.set;
  const auto factors = factor_sets(spec, design.runs.front().actual);
  point_set.insert(point_set.end(), factors.begin(), factors.end());
  for (const auto& [scenario, set, what] : {std::tuple{spec.reference.scenario, reference_set, "the reference"},
                                            std::tuple{spec.scenario, point_set, "the design points"}}) {
    try {
      PreparedRun::build(read_scenario_file(scenario, set), 1);
    } catch (const InputError& problem) {
      throw InputError(fmt::format("{}: the scenario of {} does not read with the calibration's --set values:\n{}",
                                   spec.file, what, problem.what()));
    }
  }
}

std::size_t index_of(const std::vector<std::string>& names, const std::string& name) {
  return static_cast<std::size_t>(std::find(names.begin(), names.end(), name) - names.begin());
}

struct SolveOutcome {
  std::vector<doe::Solution> solutions;
  ordered_json description;  // mode and steps or targets
  std::string text;          // "T_d = 92.4 for lambda_wall, then ..."
};

SolveOutcome solve(const CalibrationSpec& spec, const std::vector<doe::ResponseSurfaceFit>& fits,
                   const std::vector<double>& targets, const std::vector<doe::FactorRange>& ranges) {
  const std::vector<std::string> names = factor_names(spec);
  std::vector<std::string> responses;
  for (const auto& r : spec.responses) responses.push_back(r.name);
  std::vector<double> x;
  for (const auto& f : spec.factors) x.push_back(f.design.centre);
  std::vector<bool> fixed(names.size(), false);
  ordered_json fixed_json = ordered_json::object();
  for (const auto& [name, value] : spec.solve.fixed) {
    x[index_of(names, name)] = value;
    fixed[index_of(names, name)] = true;
    fixed_json[name] = value;
  }
  SolveOutcome outcome;
  outcome.description["fixed"] = fixed_json;
  if (spec.solve.mode == doe::CalibrationSolveMode::sequential) {
    std::vector<doe::SolveStep> steps;
    outcome.description["mode"] = "sequential";
    outcome.description["steps"] = ordered_json::array();
    for (const auto& step : spec.solve.steps) {
      const std::size_t r = index_of(responses, step.response);
      steps.push_back({&fits[r].model, targets[r], index_of(names, step.factor)});
      outcome.description["steps"].push_back(
          {{"response", step.response}, {"target", targets[r]}, {"factor", step.factor}});
      outcome.text += fmt::format("{}{} = {} for {}", outcome.text.empty() ? "" : ", then ", step.response,
                                  format_number(targets[r], 10), step.factor);
    }
    outcome.solutions = doe::solve_sequentially(steps, x, ranges);
    return outcome;
  }
  std::vector<const doe::PolynomialModel*> models;
  std::vector<std::size_t> free_factors;
  outcome.description["mode"] = "simultaneous";
  outcome.description["targets"] = ordered_json::array();
  for (std::size_t r = 0; r < fits.size(); ++r) {
    models.push_back(&fits[r].model);
    outcome.description["targets"].push_back({{"response", responses[r]}, {"target", targets[r]}});
    outcome.text +=
        fmt::format("{}{} = {}", outcome.text.empty() ? "" : ", ", responses[r], format_number(targets[r], 10));
  }
  for (std::size_t f = 0; f < names.size(); ++f)
    if (!fixed[f]) free_factors.push_back(f);
  outcome.text += " together";
  outcome.solutions = doe::solve_simultaneously(models, targets, x, free_factors, ranges);
  return outcome;
}

/// The roots in the order they are preferred for verification: inside the design range
/// before outside it, then nearest the design centre in coded units (the surfaces are best
/// known there).
std::vector<std::size_t> preferred_roots(const CalibrationSpec& spec, const std::vector<doe::Solution>& solutions) {
  std::vector<std::pair<bool, double>> keys;
  for (const doe::Solution& solution : solutions) {
    double distance2 = 0.0;
    for (std::size_t f = 0; f < spec.factors.size(); ++f) {
      const auto& d = spec.factors[f].design;
      distance2 += std::pow((solution.factors[f] - d.centre) / d.step, 2);
    }
    keys.emplace_back(!solution.inside(), distance2);
  }
  std::vector<std::size_t> order(solutions.size());
  for (std::size_t s = 0; s < order.size(); ++s) order[s] = s;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return keys[a] < keys[b]; });
  return order;
}

std::string interrupted_line(const CalibrateOptions& options, const fs::path& output, int finished, int total) {
  return fmt::format(
      "regodem: calibration interrupted with {} of {} runs finished; they are kept and will not run again, the "
      "stopped ones start over. Continue with: regodem calibrate {} -o {}",
      finished, total, options.calibration_path, output.string());
}

int calibrate(const CalibrateOptions& options) {
  const CalibrationSpec spec = read_calibration_file(options.calibration_path);
  const RunLauncher launcher =
      RunLauncher::from(options.ranks_per_run > 0 ? options.ranks_per_run : spec.ranks_per_run, options.mpirun);
  const int processes = launcher.processes(options.processes, spec.processes, spec.threads_per_run);
  const fs::path output =
      fs::absolute(options.output_directory.empty() ? fs::path("out") / fs::path(options.calibration_path).stem()
                                                    : fs::path(options.output_directory))
          .lexically_normal();
  std::vector<doe::DesignFactor> design_factors;
  for (const auto& f : spec.factors) design_factors.push_back(f.design);
  const doe::CentralCompositeDesign design = doe::make_central_composite_design(design_factors, spec.design);
  check_scenarios(spec, design);

  // One calibration per directory; each of its runs also locks its own.
  const RunDirectoryLock lock(output, fmt::format("regodem calibrate {}", options.calibration_path));
  std::error_code error;
  fs::create_directories(output / "runs", error);
  if (error)
    throw InputError(fmt::format("cannot create the output directory {}: {}", output.string(), error.message()));
  write_file_atomically(output / "design.csv", doe::design_csv(design));
  const int total = static_cast<int>(design.runs.size()) + 2;
  RunBatches::say(
      fmt::format("calibration {}: {} design points ({} factors, α = {:.6g}) + reference + verification = "
                  "{} runs, {} at once, {} thread{} each{}; outputs in {}",
                  spec.file, design.runs.size(), spec.factors.size(), design.alpha, total, processes,
                  spec.threads_per_run, spec.threads_per_run == 1 ? "" : "s", launcher.description(), output.string()));
  const std::atomic<int>& signals = install_signal_counter();
  RunBatches batches(output, processes, spec.threads_per_run, launcher, total, signals);
  const auto stopped = [&](int status) {
    if (status == exit_status::interrupted)
      fmt::print(stderr, "{}\n", interrupted_line(options, output, batches.finished(), total));
    return status;
  };

  // 1. The reference: its summary gives the targets and the values passed on.
  PlannedRun reference{1, "reference", spec.reference.scenario, spec.set, ""};
  reference.set.insert(reference.set.end(), spec.reference.set.begin(), spec.reference.set.end());
  if (const int status = batches.run({reference}); status != exit_status::success) return stopped(status);
  const ReferenceValues ref = reference_values(spec, read_summary(batches.directory(reference)));

  // 2. The design points.
  std::vector<std::string> common_set = spec.set;
  common_set.insert(common_set.end(), ref.pass_on_set.begin(), ref.pass_on_set.end());
  std::vector<PlannedRun> points;
  for (std::size_t p = 0; p < design.runs.size(); ++p) {
    PlannedRun run{static_cast<int>(p) + 2, fmt::format("point_{:02}", p + 1), spec.scenario, common_set,
                   factor_description(spec, design.runs[p].actual)};
    const auto sets = factor_sets(spec, design.runs[p].actual);
    run.set.insert(run.set.end(), sets.begin(), sets.end());
    points.push_back(run);
  }
  if (signals.load() > 0) return stopped(exit_status::interrupted);
  if (const int status = batches.run(points); status != exit_status::success) return stopped(status);

  // 3. Fit and solve.
  const std::vector<std::string> names = factor_names(spec);
  std::vector<std::vector<double>> x, y;
  for (std::size_t p = 0; p < points.size(); ++p) {
    const ordered_json summary = read_summary(batches.directory(points[p]));
    x.push_back(design.runs[p].actual);
    y.emplace_back();
    for (const auto& r : spec.responses)
      y.back().push_back(summary_number(summary, r.json_path, r.where, points[p].name));
  }
  std::vector<NamedUnit> response_columns;
  for (const auto& r : spec.responses) response_columns.push_back({r.name, r.unit});
  write_file_atomically(output / "runs.csv", runs_csv(spec.factors, response_columns, design, y));
  std::vector<doe::ResponseSurfaceFit> fits;
  std::string fit_text;
  json fit_document;
  fit_document["runs_file"] = (output / "runs.csv").string();
  fit_document["factors"] = json::array();
  const std::vector<doe::FactorRange> ranges = design_ranges(design);
  for (std::size_t f = 0; f < names.size(); ++f)
    fit_document["factors"].push_back(
        {{"name", names[f]}, {"unit", spec.factors[f].design.unit}, {"low", ranges[f].low}, {"high", ranges[f].high}});
  fit_document["responses"] = json::array();
  for (std::size_t r = 0; r < spec.responses.size(); ++r) {
    const auto& response = spec.responses[r];
    std::vector<double> values;
    for (const auto& row : y) values.push_back(row[r]);
    fits.push_back(fit_design_response(x, values, names, response.terms, response.name, response.where));
    fit_text += fit_report_text(fits.back(), response.unit);
    fit_document["responses"].push_back(fit_json(fits.back(), response.unit));
  }
  const SolveOutcome solved = solve(spec, fits, ref.targets, ranges);
  ordered_json solve_json = solved.description;
  solve_json["solutions"] = ordered_json::array();
  for (const auto& s : solved.solutions) solve_json["solutions"].push_back(ordered_json(solution_json(s, names, fits)));
  fit_document["solve"] = json(solve_json);
  write_file_atomically(output / "fit.txt", fit_text);
  write_file_atomically(output / "fit.json", fit_document.dump(2) + "\n");

  ordered_json result;
  result["calibration_file"] = spec.file;
  result["scenario"] = spec.scenario;
  result["reference_scenario"] = spec.reference.scenario;
  result["factors"] = ordered_json(fit_document["factors"]);
  for (std::size_t f = 0; f < names.size(); ++f) {
    result["factors"][f]["set"] = spec.factors[f].set_path;
    result["factors"][f]["centre"] = spec.factors[f].design.centre;
    result["factors"][f]["step"] = spec.factors[f].design.step;
  }
  result["pass_on"] = ref.pass_on_json;
  result["targets"] = ordered_json::object();
  for (std::size_t r = 0; r < spec.responses.size(); ++r)
    result["targets"][spec.responses[r].name] = {
        {"value", ref.targets[r]},
        {"from", spec.responses[r].target_value ? "given" : "reference: " + *spec.responses[r].target_reference_path}};
  result["design_points"] = design.runs.size();
  result["solve"] = solve_json;

  RunBatches::say("");
  std::string target_text;
  for (std::size_t r = 0; r < spec.responses.size(); ++r)
    target_text += fmt::format("{}{} = {}{}", target_text.empty() ? "" : ", ", spec.responses[r].name,
                               format_number(ref.targets[r], 8),
                               spec.responses[r].unit.empty() ? "" : " " + spec.responses[r].unit);
  RunBatches::say(fmt::format("Targets: {}", target_text));
  for (const auto& fit : fits)
    RunBatches::say(fmt::format("Fit: {}   (R² {:.5f}, adjusted {:.5f}, predicted {}; fit.txt has the statistics)",
                                fit.model.equation(fit.response_name), fit.r_squared, fit.adjusted_r_squared,
                                format_number(fit.predicted_r_squared, 5)));
  RunBatches::say(fmt::format("Solve {} ({}):", solved.text, solve_json["mode"].get<std::string>()));
  for (std::size_t s = 0; s < solved.solutions.size(); ++s)
    RunBatches::say(fmt::format("  {}. {}{}", s + 1, solution_text(solved.solutions[s], names, fits),
                                solved.solutions[s].inside() ? "" : "   OUTSIDE the design range"));
  // The root verified: the first preferred one whose values the scenario accepts (a root
  // can give a conductivity below zero, a restitution above one).
  std::optional<std::size_t> chosen;
  for (const std::size_t s : preferred_roots(spec, solved.solutions)) {
    std::vector<std::string> set = common_set;
    const auto sets = factor_sets(spec, solved.solutions[s].factors);
    set.insert(set.end(), sets.begin(), sets.end());
    try {
      PreparedRun::build(read_scenario_file(spec.scenario, set), 1);
      chosen = s;
      break;
    } catch (const InputError& problem) {
      result["solve"]["solutions"][s]["refused"] = problem.what();
      RunBatches::say(fmt::format("  root {} is not run: the scenario refuses its values: {}", s + 1, problem.what()));
    }
  }
  if (!chosen) {
    result["solution"] = nullptr;
    write_file_atomically(output / "calibration.json", result.dump(2) + "\n");
    if (solved.solutions.empty())
      fmt::print(stderr, "regodem: error: the fitted surfaces do not reach the targets (no real root); see {}\n",
                 (output / "fit.txt").string());
    else
      fmt::print(stderr,
                 "regodem: error: the scenario refuses the values of every root, so none is run (a wider or "
                 "shifted design, or other responses, may reach the targets); see {}\n",
                 (output / "calibration.json").string());
    return exit_status::run_failed;
  }
  const doe::Solution& solution = solved.solutions[*chosen];
  if (!solution.inside())
    fmt::print(stderr,
               "regodem: warning: the solution lies outside the design range ({}): the surfaces are "
               "extrapolated there\n",
               fmt::join(solution.outside, ", "));
  result["solution"] = ordered_json(solution_json(solution, names, fits));
  result["solution"]["index"] = *chosen + 1;

  // 4. The verification run at the solution.
  PlannedRun verification{total, "verification", spec.scenario, common_set, factor_description(spec, solution.factors)};
  const auto sets = factor_sets(spec, solution.factors);
  verification.set.insert(verification.set.end(), sets.begin(), sets.end());
  if (signals.load() > 0) return stopped(exit_status::interrupted);
  if (const int status = batches.run({verification}); status != exit_status::success) return stopped(status);
  const ordered_json verified = read_summary(batches.directory(verification));
  result["verification"] = {{"directory", batches.directory(verification).string()},
                            {"responses", ordered_json::object()}};
  RunBatches::say(fmt::format("\nVerification at root {} ({}):", *chosen + 1, verification.description));
  RunBatches::say(
      fmt::format("  {:<16} {:>14} {:>14} {:>14} {:>14}", "response", "target", "achieved", "difference", "fitted"));
  for (std::size_t r = 0; r < spec.responses.size(); ++r) {
    const auto& response = spec.responses[r];
    const double achieved = summary_number(verified, response.json_path, response.where, "verification");
    const double fitted = fits[r].model.evaluate(solution.factors);
    result["verification"]["responses"][response.name] = {{"target", ref.targets[r]},
                                                          {"achieved", achieved},
                                                          {"difference", achieved - ref.targets[r]},
                                                          {"fitted", fitted}};
    RunBatches::say(fmt::format("  {:<16} {:>14} {:>14} {:>14} {:>14}", header(response.name, response.unit),
                                format_number(ref.targets[r], 8), format_number(achieved, 8),
                                format_number(achieved - ref.targets[r], 4), format_number(fitted, 8)));
  }
  write_file_atomically(output / "calibration.json", result.dump(2) + "\n");
  RunBatches::say(
      fmt::format("\nWritten: {0}/calibration.json, fit.txt, fit.json, runs.csv, design.csv; each run's "
                  "outputs in {0}/runs/",
                  output.string()));
  return exit_status::success;
}

}  // namespace

CLI::App* add_calibrate_command(CLI::App& app, CalibrateOptions& options) {
  CLI::App* calibrate = app.add_subcommand(
      "calibrate",
      "Calibrate scenario values against a reference run: design, runs, response surfaces, solve, verification run");
  calibrate->add_option("CALIBRATION", options.calibration_path, "Calibration file (YAML; see docs/calibration.md)")
      ->required()
      ->check(CLI::ExistingFile);
  calibrate
      ->add_option("-o,--output", options.output_directory,
                   "Output directory (default: out/<calibration file name>); rerun with the same one to "
                   "continue an interrupted calibration")
      ->type_name("OUTDIR");
  calibrate->add_option("--processes", options.processes, "Runs at once (default: the file's `processes`)")
      ->type_name("N")
      ->check(CLI::Range(1, 4096));
  calibrate->add_option("--ranks-per-run", options.ranks_per_run,
                        "Each run over N MPI ranks, started with --mpirun (default: the file's `ranks_per_run`, 1)")
      ->type_name("N")
      ->check(CLI::Range(1, 4096));
  calibrate->add_option("--mpirun", options.mpirun,
                        "The launcher of a run over ranks and its options: -np N is appended, or {ranks} in it is replaced by N (srun -n {ranks}; default: mpirun --bind-to none)")
      ->type_name("COMMAND");
  calibrate->footer(
      "Runs the reference, every point of a central composite design, and a verification run at the solution, each\n"
      "as `regodem run` into OUTDIR/runs/NAME; writes OUTDIR/design.csv, runs.csv, fit.txt, fit.json and\n"
      "calibration.json. A run already completed with the same scenario and --set values is not run again. Ctrl-C\n"
      "stops the runs cleanly (exit status 130); the same command continues. See docs/calibration.md.");
  return calibrate;
}

int run_calibrate(const CalibrateOptions& options) {
  try {
    return calibrate(options);
  } catch (const InputError& error) {
    fmt::print(stderr, "regodem: error: {}\n", error.what());
    return exit_status::bad_input;
  }
}

}  // namespace regodem::app
