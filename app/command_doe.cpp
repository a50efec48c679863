// `regodem doe ccd`: a central composite design as a CSV table of runs, with coded and
// actual factor values (src/doe/central_composite_design.hpp).
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "commands.hpp"
#include "core/error.hpp"
#include "doe/central_composite_design.hpp"
#include "io/atomic_file.hpp"
#include "option_values.hpp"

namespace regodem::app {
namespace {

constexpr const char* factor_form = "NAME=CENTRE:STEP, e.g. C_wall=1200:600 (or \"C_wall [J/(kg K)]=1200:600\")";

doe::DesignFactor parse_factor(const std::string& text) {
  const auto [name_part, values] = split_name_value(text, "--factor", factor_form);
  doe::DesignFactor factor;
  factor.name = name_part;
  if (const auto open = name_part.find('['); open != std::string::npos) {
    if (name_part.back() != ']') throw InputError(fmt::format("--factor '{}': expected {}", text, factor_form));
    factor.name = trimmed(name_part.substr(0, open));
    factor.unit = trimmed(name_part.substr(open + 1, name_part.size() - open - 2));
  }
  if (factor.name.empty() || factor.name.find_first_of(",\" ") != std::string::npos)
    throw InputError(fmt::format("--factor '{}': the name must be non-empty without spaces, commas or quotes", text));
  const auto colon = values.find(':');
  if (colon == std::string::npos) throw InputError(fmt::format("--factor '{}': expected {}", text, factor_form));
  factor.centre = parse_number(values.substr(0, colon), "--factor " + factor.name + " centre");
  factor.step = parse_number(values.substr(colon + 1), "--factor " + factor.name + " step");
  if (!(factor.step > 0.0))
    throw InputError(fmt::format("--factor '{}': the step (actual change per coded unit) must be > 0", text));
  return factor;
}

doe::CcdOptions design_options(const DoeOptions& options) {
  doe::CcdOptions ccd;
  if (options.alpha == "rotatable") {
    ccd.alpha_kind = doe::AlphaKind::rotatable;
  } else if (options.alpha == "face") {
    ccd.alpha_kind = doe::AlphaKind::face;
  } else {
    ccd.alpha_kind = doe::AlphaKind::given;
    ccd.alpha = parse_number(options.alpha, "--alpha (rotatable, face or a number)");
    if (!(ccd.alpha > 0.0)) throw InputError(fmt::format("--alpha {}: α must be > 0", options.alpha));
  }
  ccd.centre_points = options.centre_points;
  ccd.half_fraction = options.half_fraction;
  ccd.order = options.order == "random" ? doe::RunOrder::random : doe::RunOrder::standard;
  ccd.seed = options.seed;
  return ccd;
}

}  // namespace

CLI::App* add_doe_command(CLI::App& app, DoeOptions& options) {
  CLI::App* doe = app.add_subcommand("doe", "Design experiments (a table of runs to make)");
  doe->require_subcommand(1);
  CLI::App* ccd = doe->add_subcommand(
      "ccd", "Central composite design: factorial, axial (±α) and centre points, coded and actual values, as CSV");
  ccd->add_option("--factor", options.factors,
                  "A factor: NAME=CENTRE:STEP (actual = CENTRE + coded × STEP); NAME may end in [unit]; repeatable, "
                  "one per factor")
      ->type_name("NAME=CENTRE:STEP")
      ->required()
      ->allow_extra_args(false);
  ccd->add_option("--alpha", options.alpha,
                  "Axial distance in coded units: rotatable (n_F^(1/4), n_F factorial points), face (1) or a number "
                  "(default rotatable)")
      ->type_name("rotatable|face|VALUE");
  ccd->add_option("--centre-points", options.centre_points, "Centre points (default 3)")
      ->type_name("N")
      ->check(CLI::Range(0, 1000));
  ccd->add_flag("--half-fraction", options.half_fraction,
                "Factorial part as the half fraction with I = AB…K (resolution V or more; 5 factors or more)");
  ccd->add_option("--order", options.order, "Run order: standard or random (default standard)")
      ->check(CLI::IsMember({"standard", "random"}));
  ccd->add_option("--seed", options.seed, "Seed of the random run order (default 1)")->type_name("S");
  ccd->add_option("-o,--output", options.output_path, "CSV file to write (default: standard output)")
      ->type_name("FILE");
  ccd->footer(
      "CSV columns: run, std_order, point_type (factorial, axial, centre), NAME_coded for each factor, then each\n"
      "factor's actual value under its name (with [unit] if given). Standard order: factorial points in Yates\n"
      "order (first factor fastest), axial points (−α, +α per factor), centre points. See docs/calibration.md.");
  return doe;
}

int run_doe(const DoeOptions& options) {
  try {
    std::vector<doe::DesignFactor> factors;
    for (const std::string& text : options.factors) factors.push_back(parse_factor(text));
    const doe::CentralCompositeDesign design = doe::make_central_composite_design(factors, design_options(options));
    const std::string csv = doe::design_csv(design);
    const std::string summary =
        fmt::format("central composite design: {} factor{}, α = {:.6g}; {} factorial + {} axial + {} centre = {} runs",
                    factors.size(), factors.size() == 1 ? "" : "s", design.alpha, design.factorial_points,
                    design.axial_points, design.centre_points, design.runs.size());
    if (options.output_path.empty()) {
      fmt::print("{}", csv);
      fmt::print(stderr, "{}\n", summary);
    } else {
      try {
        write_file_atomically(options.output_path, csv);
      } catch (const std::system_error& error) {
        throw InputError(fmt::format("cannot write the design: {}", error.what()));
      }
      fmt::print("{}; written to {}\n", summary, options.output_path);
    }
  } catch (const InputError& error) {
    fmt::print(stderr, "regodem: error: {}\n", error.what());
    return exit_status::bad_input;
  }
  return exit_status::success;
}

}  // namespace regodem::app
