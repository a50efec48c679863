// `regodem envelope`: the operating map of a drill (issue 21; docs/drilling-heat.md, "The
// operating envelope"). A central composite design over scenario values (feed and speed,
// and any others), each point a drilling run as a child process (several at once, a run
// already done with the same inputs skipped, so an interrupted envelope continues);
// responses read from each run's outputs; response surfaces fitted with their statistics;
// a map of one fitted response over two factors with its threshold contour.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "core/error.hpp"
#include "design_runs.hpp"
#include "doe/central_composite_design.hpp"
#include "doe/envelope_spec.hpp"
#include "doe/response_surface_fit.hpp"
#include "fit_report.hpp"
#include "io/atomic_file.hpp"
#include "io/csv_table_reader.hpp"
#include "io/run_directory_lock.hpp"
#include "plot_script.hpp"
#include "scenario/calibration_reader.hpp"
#include "scenario/scenario_builder.hpp"
#include "scenario/scenario_reader.hpp"
#include "signal_handling.hpp"

namespace regodem::app {
namespace {

using doe::EnvelopeSpec;
using nlohmann::json;
using nlohmann::ordered_json;

std::vector<std::string> point_sets(const EnvelopeSpec& spec, const std::vector<double>& x) {
  std::vector<std::string> sets = spec.set;
  for (std::size_t f = 0; f < spec.factors.size(); ++f) sets.push_back(factor_set_text(spec.factors[f], x[f]));
  return sets;
}

std::string point_description(const EnvelopeSpec& spec, const std::vector<double>& x) {
  std::string text;
  for (std::size_t f = 0; f < spec.factors.size(); ++f)
    text += fmt::format("{}{} = {:.6g}{}", text.empty() ? "" : ", ", spec.factors[f].design.name, x[f],
                        spec.factors[f].design.unit.empty() ? "" : " " + spec.factors[f].design.unit);
  return text;
}

/// A column of one of the run's CSV files reduced over its numeric rows (nan skipped: a
/// region that held no particle then).
double series_value(const doe::EnvelopeResponse& r, const fs::path& run_directory, const std::string& run) {
  const fs::path file = run_directory / r.series_file;
  std::vector<double> values;
  try {
    const CsvTable table = read_csv_table(file.string());
    const std::size_t column = table.column(r.series_column);
    for (std::size_t row = 0; row < table.rows.size(); ++row) {
      const std::string& cell = table.rows[row][column];
      if (cell == "nan") continue;
      char* end = nullptr;
      const double v = std::strtod(cell.c_str(), &end);
      if (end == cell.c_str() || *end != '\0')
        throw InputError(fmt::format("{}:{}: '{}' is not a number", file.string(), table.line_numbers[row], cell));
      values.push_back(v);
    }
  } catch (const InputError& problem) {
    throw InputError(fmt::format("{}: run {}: {}", r.where, run, problem.what()));
  }
  if (values.empty())
    throw InputError(fmt::format("{}: run {}: column '{}' of {} holds no number", r.where, run, r.series_column,
                                 file.string()));
  switch (r.reduction) {
    case doe::SeriesReduction::max: return *std::max_element(values.begin(), values.end());
    case doe::SeriesReduction::min: return *std::min_element(values.begin(), values.end());
    case doe::SeriesReduction::final: return values.back();
    case doe::SeriesReduction::mean: {
      double sum = 0.0;
      for (double v : values) sum += v;
      return sum / static_cast<double>(values.size());
    }
  }
  return values.back();
}

double response_value(const doe::EnvelopeResponse& r, const fs::path& run_directory, const std::string& run) {
  if (!r.json_path.empty()) return summary_number(read_summary(run_directory), r.json_path, r.where, run);
  return series_value(r, run_directory, run);
}

std::size_t factor_index(const EnvelopeSpec& spec, const std::string& name) {
  for (std::size_t f = 0; f < spec.factors.size(); ++f)
    if (spec.factors[f].design.name == name) return f;
  return 0;
}

std::size_t response_index(const EnvelopeSpec& spec, const std::string& name) {
  for (std::size_t r = 0; r < spec.responses.size(); ++r)
    if (spec.responses[r].name == name) return r;
  return 0;
}

/// The map: the fitted response on a grid over x and y (the design's range of each, the
/// other factors at their centres). The box's corners lie beyond every design point (a
/// design covers the circle through its outermost points, radius max(alpha, sqrt 2) in
/// coded units), where the surface
/// extrapolates: each grid point says whether it is inside that circle, and `below` and
/// `inside` count only the points inside. Returns map.csv's text.
std::string map_csv(const EnvelopeSpec& spec, const doe::ResponseSurfaceFit& fit, double alpha,
                    const std::vector<doe::FactorRange>& ranges, std::size_t& below, std::size_t& inside) {
  const std::size_t fx = factor_index(spec, spec.map.x), fy = factor_index(spec, spec.map.y);
  const doe::EnvelopeResponse& response = spec.responses[response_index(spec, spec.map.response)];
  std::vector<double> x;
  for (const auto& f : spec.factors) x.push_back(f.design.centre);
  std::string text = fmt::format("{},{},{},inside_design [-]\n", header(spec.map.x, spec.factors[fx].design.unit),
                                 header(spec.map.y, spec.factors[fy].design.unit), header(response.name, response.unit));
  const int n = spec.map.grid;
  below = inside = 0;
  const auto coded = [&](std::size_t f, double value) {
    return (value - spec.factors[f].design.centre) / spec.factors[f].design.step;
  };
  for (int j = 0; j < n; ++j) {
    x[fy] = ranges[fy].low + (ranges[fy].high - ranges[fy].low) * j / (n - 1);
    for (int i = 0; i < n; ++i) {
      x[fx] = ranges[fx].low + (ranges[fx].high - ranges[fx].low) * i / (n - 1);
      const double value = fit.model.evaluate(x);
      const double radius2 = coded(fx, x[fx]) * coded(fx, x[fx]) + coded(fy, x[fy]) * coded(fy, x[fy]);
      // The circle through the outermost design points: the axial ones (alpha) or the factorial corners (sqrt 2).
      const bool in_design = radius2 <= std::max(alpha * alpha, 2.0) * (1.0 + 1e-12);
      inside += in_design ? 1 : 0;
      below += in_design && value < spec.map.threshold ? 1 : 0;
      text += fmt::format("{},{},{},{}\n", x[fx], x[fy], value, in_design ? 1 : 0);
    }
  }
  return text;
}

/// The PNG of the map, drawn by the plot script; a missing Python or matplotlib is a
/// warning (the CSV files are the results).
void draw_map(const fs::path& output, const EnvelopeSpec& spec) {
  try {
    const fs::path script = find_plot_script();
    const int status = run_and_wait({python_interpreter(), script.string(), "--envelope", output.string(),
                                     "--threshold", fmt::format("{}", spec.map.threshold)});
    if (status != 0)
      fmt::print(stderr, "regodem: warning: the map was not drawn (the plot script ended with status {})\n", status);
  } catch (const ToolError& problem) {
    fmt::print(stderr, "regodem: warning: the map was not drawn: {}\n", problem.what());
  }
}

int envelope(const EnvelopeOptions& options) {
  const EnvelopeSpec spec = read_envelope_file(options.envelope_path);
  const RunLauncher launcher =
      RunLauncher::from(options.ranks_per_run > 0 ? options.ranks_per_run : spec.ranks_per_run, options.mpirun);
  const int processes = launcher.processes(options.processes, spec.processes, spec.threads_per_run);
  const fs::path output =
      fs::absolute(options.output_directory.empty() ? fs::path("out") / fs::path(options.envelope_path).stem()
                                                    : fs::path(options.output_directory))
          .lexically_normal();
  std::vector<doe::DesignFactor> design_factors;
  for (const auto& f : spec.factors) design_factors.push_back(f.design);
  const doe::CentralCompositeDesign design = doe::make_central_composite_design(design_factors, spec.design);
  // Bad input before anything runs: the scenario at every point but the repeated centre.
  // The extremes are the axial points for alpha >= 1 and the factorial corners for alpha
  // below 1, and a value can be refused only in combination with another (a corner).
  for (const auto& point : design.runs) {
    if (&point != &design.runs.front() && point.type == doe::PointType::centre) continue;
    try {
      PreparedRun::build(read_scenario_file(spec.scenario, point_sets(spec, point.actual)), 1);
    } catch (const InputError& problem) {
      throw InputError(fmt::format("{}: the scenario does not read at the design point {}:\n{}", spec.file,
                                   point_description(spec, point.actual), problem.what()));
    }
  }

  const RunDirectoryLock lock(output, fmt::format("regodem envelope {}", options.envelope_path));
  std::error_code error;
  fs::create_directories(output / "runs", error);
  if (error)
    throw InputError(fmt::format("cannot create the output directory {}: {}", output.string(), error.message()));
  write_file_atomically(output / "design.csv", doe::design_csv(design));
  const int total = static_cast<int>(design.runs.size());
  RunBatches::say(fmt::format("envelope {}: {} design points ({} factors, α = {:.6g}), {} at once, {} thread{} each{}; "
                              "outputs in {}",
                              spec.file, total, spec.factors.size(), design.alpha, processes, spec.threads_per_run,
                              spec.threads_per_run == 1 ? "" : "s", launcher.description(), output.string()));
  const std::atomic<int>& signals = install_signal_counter();
  RunBatches batches(output, processes, spec.threads_per_run, launcher, total, signals);
  std::vector<PlannedRun> points;
  for (std::size_t p = 0; p < design.runs.size(); ++p)
    points.push_back({static_cast<int>(p) + 1, fmt::format("point_{:02}", p + 1), spec.scenario,
                      point_sets(spec, design.runs[p].actual), point_description(spec, design.runs[p].actual)});
  if (const int status = batches.run(points); status != exit_status::success) {
    if (status == exit_status::interrupted)
      fmt::print(stderr,
                 "regodem: envelope interrupted with {} of {} runs finished; they are kept and will not run again, "
                 "the stopped ones start over. Continue with: regodem envelope {} -o {}\n",
                 batches.finished(), total, options.envelope_path, output.string());
    return status;
  }

  // The responses, the fits and the map.
  std::vector<std::string> names;
  for (const auto& f : spec.factors) names.push_back(f.design.name);
  std::vector<std::vector<double>> x, y;
  for (std::size_t p = 0; p < points.size(); ++p) {
    x.push_back(design.runs[p].actual);
    y.emplace_back();
    for (const auto& r : spec.responses) y.back().push_back(response_value(r, batches.directory(points[p]), points[p].name));
  }
  std::vector<NamedUnit> columns;
  for (const auto& r : spec.responses) columns.push_back({r.name, r.unit});
  write_file_atomically(output / "runs.csv", runs_csv(spec.factors, columns, design, y));
  const std::vector<doe::FactorRange> ranges = design_ranges(design);
  // A response with the same value at every point (a drill that only cools keeps its
  // starting temperature as its peak) has nothing to fit: it is reported, not fitted.
  std::vector<std::optional<doe::ResponseSurfaceFit>> fits;
  std::vector<std::string> fit_lines;  // one line per response for the closing report
  std::string fit_text;
  ordered_json result;
  result["envelope_file"] = spec.file;
  result["scenario"] = spec.scenario;
  result["set"] = spec.set;
  result["factors"] = ordered_json::array();
  for (std::size_t f = 0; f < spec.factors.size(); ++f)
    result["factors"].push_back({{"name", names[f]},
                                 {"unit", spec.factors[f].design.unit},
                                 {"set", spec.factors[f].set_path},
                                 {"centre", spec.factors[f].design.centre},
                                 {"step", spec.factors[f].design.step},
                                 {"low", ranges[f].low},
                                 {"high", ranges[f].high}});
  result["design_points"] = design.runs.size();
  result["responses"] = ordered_json::array();
  const std::size_t mapped = response_index(spec, spec.map.response);
  for (std::size_t r = 0; r < spec.responses.size(); ++r) {
    const auto& response = spec.responses[r];
    std::vector<double> values;
    for (const auto& row : y) values.push_back(row[r]);
    ordered_json entry;
    if (std::all_of(values.begin(), values.end(), [&](double v) { return v == values.front(); })) {
      if (r == mapped)
        throw InputError(fmt::format("{}: the mapped response '{}' is {} at every design point: there is no map to draw",
                                     response.where, response.name, format_number(values.front(), 8)));
      fits.push_back(std::nullopt);
      fit_lines.push_back(fmt::format("Not fitted: {} = {}{} at every design point", response.name,
                                      format_number(values.front(), 8), response.unit.empty() ? "" : " " + response.unit));
      fit_text += fit_lines.back() + "\n\n";
      entry["name"] = response.name;
      entry["unit"] = response.unit;
      entry["constant"] = values.front();
    } else {
      fits.push_back(fit_design_response(x, values, names, response.terms, response.name, response.where));
      const doe::ResponseSurfaceFit& fit = *fits.back();
      fit_lines.push_back(fmt::format("Fit: {}   (R² {:.5f}, adjusted {:.5f}, predicted {})",
                                      fit.model.equation(fit.response_name), fit.r_squared, fit.adjusted_r_squared,
                                      format_number(fit.predicted_r_squared, 5)));
      fit_text += fit_report_text(fit, response.unit);
      entry = ordered_json(fit_json(*fits.back(), response.unit));
    }
    entry["source"] = response.json_path.empty()
                          ? fmt::format("{} column {} ({})", response.series_file, response.series_column,
                                        response.reduction == doe::SeriesReduction::max    ? "max"
                                        : response.reduction == doe::SeriesReduction::min  ? "min"
                                        : response.reduction == doe::SeriesReduction::mean ? "mean"
                                                                                           : "final")
                          : "summary.json " + response.json_path;
    entry["values"] = values;
    result["responses"].push_back(entry);
  }
  write_file_atomically(output / "fit.txt", fit_text);
  std::size_t below = 0, grid_points = 0;
  write_file_atomically(output / "map.csv", map_csv(spec, *fits[mapped], design.alpha, ranges, below, grid_points));
  std::vector<std::string> above;
  for (std::size_t p = 0; p < points.size(); ++p)
    if (!(y[p][mapped] < spec.map.threshold)) above.push_back(points[p].name);
  const double safe_fraction = static_cast<double>(below) / static_cast<double>(grid_points);
  result["map"] = {{"x", spec.map.x},
                   {"y", spec.map.y},
                   {"response", spec.map.response},
                   {"threshold", spec.map.threshold},
                   {"grid", spec.map.grid},
                   {"fitted_below_threshold_fraction", safe_fraction},  // of the grid inside the design's circle
                   {"points_at_or_above_threshold", above},
                   {"file", "map.csv"},
                   {"figure", "envelope_map.png"}};
  write_file_atomically(output / "envelope.json", result.dump(2) + "\n");
  draw_map(output, spec);

  RunBatches::say("");
  for (const std::string& line : fit_lines) RunBatches::say(line);
  const auto& unit = spec.responses[mapped].unit;
  RunBatches::say(fmt::format(
      "Map: {} below {}{} on {:.1f} % of the {} x {} design region (fitted, inside the design's circle, the other "
      "factors at their centres); measured at or above it: {}",
      spec.map.response, format_number(spec.map.threshold, 8), unit.empty() ? "" : " " + unit, 100.0 * safe_fraction,
      spec.map.x, spec.map.y, above.empty() ? std::string("no design point") : fmt::format("{}", fmt::join(above, ", "))));
  RunBatches::say(fmt::format("\nWritten: {0}/envelope.json, envelope_map.png, map.csv, fit.txt, runs.csv, design.csv; "
                              "each run's outputs in {0}/runs/",
                              output.string()));
  return exit_status::success;
}

}  // namespace

CLI::App* add_envelope_command(CLI::App& app, EnvelopeOptions& options) {
  CLI::App* command = app.add_subcommand(
      "envelope", "The operating map of a drill: a design over feed, speed and other values, a drilling run at each "
                  "point, response surfaces and a threshold map");
  command->add_option("ENVELOPE", options.envelope_path, "Envelope file (YAML; see docs/drilling-heat.md)")
      ->required()
      ->check(CLI::ExistingFile);
  command
      ->add_option("-o,--output", options.output_directory,
                   "Output directory (default: out/<envelope file name>); rerun with the same one to continue an "
                   "interrupted envelope")
      ->type_name("OUTDIR");
  command->add_option("--processes", options.processes, "Runs at once (default: the file's `processes`)")
      ->type_name("N")
      ->check(CLI::Range(1, 4096));
  command->add_option("--ranks-per-run", options.ranks_per_run,
                        "Each run over N MPI ranks, started with --mpirun (default: the file's `ranks_per_run`, 1)")
      ->type_name("N")
      ->check(CLI::Range(1, 4096));
  command->add_option("--mpirun", options.mpirun,
                        "The launcher of a run over ranks and its options: -np N is appended, or {ranks} in it is replaced by N (srun -n {ranks}; default: mpirun --bind-to none)")
      ->type_name("COMMAND");
  command->footer(
      "Runs every point of a central composite design as `regodem run` into OUTDIR/runs/point_NN; writes\n"
      "OUTDIR/design.csv, runs.csv, fit.txt, map.csv, envelope.json and envelope_map.png. A run already completed\n"
      "with the same scenario and --set values is not run again. Ctrl-C stops the runs cleanly (exit status 130);\n"
      "the same command continues. See docs/drilling-heat.md.");
  return command;
}

int run_envelope(const EnvelopeOptions& options) {
  try {
    return envelope(options);
  } catch (const InputError& error) {
    fmt::print(stderr, "regodem: error: {}\n", error.what());
    return exit_status::bad_input;
  }
}

}  // namespace regodem::app
