// `regodem estimate`: what a run of the scenario would cost on this machine (wall time,
// steps, memory), from a short timed sample of each stage (src/sim/run_estimate.hpp,
// docs/estimate.md). Nothing is written but the optional JSON.
#include <omp.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "core/error.hpp"
#include "human_format.hpp"
#include "io/atomic_file.hpp"
#include "regodem/build_info.hpp"
#include "scenario/scenario_builder.hpp"
#include "scenario/scenario_reader.hpp"
#include "sim/run_estimate.hpp"
#include "sim/simulation.hpp"

namespace regodem::app {
namespace {

std::string megabytes(double bytes) { return bytes > 0.0 ? fmt::format("{:.0f} MB", bytes / 1e6) : "?"; }

/// "<=" before a bound, "~" before an assumption: how far to trust the number.
const char* mark(StepCount basis) {
  return basis == StepCount::upper_bound ? "<= " : basis == StepCount::assumed ? "~ " : "";
}

std::string end_text(const StageCost& c) { return c.static_bed ? fmt::format("{} (static bed)", c.end) : c.end; }

std::string machine_line(int threads) {
  return fmt::format("machine: {} cores, {} thread{} used; {}, {} build, regodem {}", omp_get_num_procs(), threads,
                     threads == 1 ? "" : "s", build_info::compiler, build_info::build_type, build_info::version);
}

void print_table(const RunEstimate& e, int threads) {
  fmt::print("{:<16} {:<24} {:>10} {:>11} {:>15} {:>14} {:>16} {:>8}\n", "stage", "end", "particles", "step",
             "steps", "particle-st/s", "predicted", "memory");
  for (const StageCost& c : e.stages)
    fmt::print("{:<16} {:<24} {:>10} {:>11} {:>15} {:>14} {:>16} {:>8}\n", c.name, end_text(c), c.particles,
               c.step_s > 0.0 ? fmt::format("{:.4g} s", c.step_s) : "?", fmt::format("{}{}", mark(c.basis), c.steps),
               c.sampled ? format_compact(c.particle_steps_per_s) : "-",
               c.sampled ? fmt::format("{}{}", mark(c.basis), format_wall_duration(c.predicted_wall_s)) : "-",
               megabytes(c.resident_bytes));
  std::size_t shortfall = 0;  // said once while it stays the same from stage to stage
  for (const StageCost& c : e.stages) {
    if (!c.note.empty()) fmt::print("  {}: {}\n", c.name, c.note);
    if (c.sampled && c.sample_particles < c.particles && c.particles - c.sample_particles != shortfall)
      fmt::print("  {}: sampled on {} of its {} particles (a region full at this solid fraction, or "
                 "particles taken out of the walls' way); the prediction scales the rate to the full count\n",
                 c.name, c.sample_particles, c.particles);
    if (c.sampled) shortfall = c.particles - c.sample_particles;
  }
  const char* bound = e.assumed ? " (includes assumed stage lengths, marked ~)"
                      : e.upper_bound ? " (an upper bound: stages marked <= count their max_duration)"
                                      : "";
  fmt::print("total: {} steps, predicted wall time {}{}{}, peak resident memory {}\n", e.steps,
             e.upper_bound || e.assumed ? "<= " : "", format_wall_duration(e.predicted_wall_s), bound,
             megabytes(e.peak_resident_bytes));
  if (!e.complete) fmt::print("total: incomplete, a stage could not be sampled (see above)\n");
  fmt::print("{}\n", machine_line(threads));
}

/// The run projected onto MPI ranks (--ranks): per rank count, each stage's step on the
/// slowest rank, by part, its gathers, and the total.
void print_over_ranks(const RunEstimate& e, const EstimateOptions& options, int threads) {
  if (options.ranks.empty()) return;
  const CodeTraffic traffic = code_traffic();
  fmt::print("\nover MPI ranks ({} thread{} each; network latency {:.3g} us, {:.3g} GB/s per rank; a ghost {} B per "
             "step; see docs/estimate.md):\n",
             threads, threads == 1 ? "" : "s", options.network.latency_s * 1e6,
             options.network.bandwidth_bytes_per_s / 1e9, traffic.refresh_bytes_per_ghost);
  fmt::print("{:>6} {:<16} {:>10} {:>9} {:>8} {:>10} {:>9} {:>9} {:>9} {:>9} {:>10} {:>10} {:>16} {:>6}\n", "ranks", "stage",
             "own/rank", "ghosts", "partners", "step", "compute", "halo", "builds", "collect.", "gathers", "each",
             "predicted", "eff.");
  for (std::size_t k = 0; k < options.ranks.size(); ++k) {
    for (const StageCost& c : e.stages) {
      if (k >= c.over_ranks.size()) continue;
      const StageOverRanks& o = c.over_ranks[k];
      const auto us = [](double s) { return fmt::format("{:.3g} us", s * 1e6); };
      const auto short_wall = [](double s) { return s < 1.0 ? fmt::format("{:.3g} ms", s * 1e3) : format_wall_duration(s); };
      if (c.static_bed)
        fmt::print("{:>6} {:<16} {:>10} {:>9} {:>8} {:>10} {:>9} {:>9} {:>9} {:>9} {:>10} {:>10} {:>16} {:>6}\n",
                   options.ranks[k], c.name, "-", "-", "-", "-", "-", "-", "-", "-", "-", "-",
                   fmt::format("{}{}", mark(c.basis), format_wall_duration(o.predicted_wall_s)), "(one)");
      else
        fmt::print("{:>6} {:<16} {:>10.0f} {:>9.0f} {:>8} {:>10} {:>9} {:>9} {:>9} {:>9} {:>10} {:>10} {:>16} {:>6.2f}\n",
                   options.ranks[k], c.name, o.step.own, o.step.ghosts, o.step.partners, us(o.step.step_s),
                   us(o.step.compute_s), us(o.step.halo_s), us(o.step.build_s), us(o.step.collectives_s),
                   fmt::format("<= {}", o.gathers), short_wall(o.gather_s),
                   fmt::format("{}{}", mark(c.basis), format_wall_duration(o.predicted_wall_s)), o.step.efficiency);
    }
    const double wall_s = e.over_ranks_wall_s[k], gather_s = e.over_ranks_gather_s[k];
    fmt::print("total on {} ranks: predicted wall time {}{} ({} of it in gathers), {:.2f}x one process{}\n",
               options.ranks[k], e.upper_bound || e.assumed || gather_s > 0.0 ? "<= " : "",
               format_wall_duration(wall_s), format_wall_duration(gather_s),
               wall_s > 0.0 ? e.predicted_wall_s / wall_s : 0.0, e.complete ? "" : " (incomplete: a stage was not sampled)");
  }
  fmt::print("every rank holds every particle at a gather: each needs the memory of one process ({})\n",
             megabytes(e.peak_resident_bytes));
}

nlohmann::json over_ranks_json(const StageCost& c, const EstimateCommandOptions& options) {
  nlohmann::json rows = nlohmann::json::array();
  for (std::size_t k = 0; k < c.over_ranks.size() && k < options.ranks.size(); ++k) {
    const StageOverRanks& o = c.over_ranks[k];
    rows.push_back({{"ranks", options.ranks[k]},
                    {"own_particles", o.step.own},
                    {"ghosts", o.step.ghosts},
                    {"partners", o.step.partners},
                    {"step_s", o.step.step_s},
                    {"compute_s", o.step.compute_s},
                    {"halo_s", o.step.halo_s},
                    {"build_s", o.step.build_s},
                    {"collectives_s", o.step.collectives_s},
                    {"efficiency", o.step.efficiency},
                    {"gathers_at_most", o.gathers},
                    {"gather_s", o.gather_s},
                    {"merge_s", o.merge_s},
                    {"predicted_wall_s", o.predicted_wall_s}});
  }
  return rows;
}

nlohmann::json to_json(const RunEstimate& e, const EstimateCommandOptions& options, int threads) {
  nlohmann::json over_ranks = nlohmann::json::array();
  for (std::size_t k = 0; k < options.ranks.size() && k < e.over_ranks_wall_s.size(); ++k)
    over_ranks.push_back({{"ranks", options.ranks[k]},
                          {"predicted_wall_s", e.over_ranks_wall_s[k]},
                          {"gather_wall_s", e.over_ranks_gather_s[k]}});
  nlohmann::json stages = nlohmann::json::array();
  for (const StageCost& c : e.stages)
    stages.push_back({{"name", c.name},
                      {"end", c.end},
                      {"static_bed", c.static_bed},
                      {"particles", c.particles},
                      {"step_s", c.step_s},
                      {"simulated_time_s", c.simulated_s},
                      {"steps", c.steps},
                      {"steps_basis", step_count_name(c.basis)},
                      {"note", c.note},
                      {"sampled", c.sampled},
                      {"sample_particles", c.sample_particles},
                      {"sample_steps", c.sample_steps},
                      {"sample_wall_s", c.sample_wall_s},
                      {"particle_steps_per_s", c.particle_steps_per_s},
                      {"setup_wall_s", c.setup_wall_s},
                      {"predicted_wall_s", c.predicted_wall_s},
                      {"resident_bytes", c.resident_bytes},
                      {"builds_per_step", c.builds_per_step},
                      {"over_ranks", over_ranks_json(c, options)}});
  return {{"scenario_file", options.scenario_path},
          {"overrides", options.overrides},
          {"solid_fraction", options.solid_fraction},
          {"stages", stages},
          {"total",
           {{"steps", e.steps},
            {"predicted_wall_s", e.predicted_wall_s},
            {"peak_resident_bytes", e.peak_resident_bytes},
            {"upper_bound", e.upper_bound},
            {"assumed", e.assumed},
            {"complete", e.complete},
            {"over_ranks", over_ranks}}},
          {"network", {{"latency_s", options.latency_us * 1e-6}, {"bandwidth_bytes_per_s", options.bandwidth_GB_per_s * 1e9}}},
          {"machine",
           {{"cores", omp_get_num_procs()},
            {"threads", threads},
            {"compiler", build_info::compiler},
            {"build_type", build_info::build_type},
            {"version", build_info::version}}}};
}

}  // namespace

CLI::App* add_estimate_command(CLI::App& app, EstimateCommandOptions& options) {
  CLI::App* estimate = app.add_subcommand(
      "estimate", "Predict a run's wall time, steps and memory on this machine from a short timed sample of each stage");
  estimate->add_option("SCENARIO", options.scenario_path, "Scenario file (YAML)")
      ->required()
      ->check(CLI::ExistingFile);
  estimate->add_option("--set", options.overrides, "Override a scenario value, as for `regodem run`; repeatable")
      ->type_name("KEY.PATH=VALUE")
      ->allow_extra_args(false);
  estimate->add_option("--threads", options.threads, "OpenMP threads (default: OMP_NUM_THREADS, else every core)")
      ->type_name("N")
      ->check(CLI::Range(1, 4096));
  estimate->add_option("--json", options.json_path, "Also write the estimate as JSON to this file")->type_name("FILE");
  estimate->add_option("--solid-fraction", options.solid_fraction,
                       "Solid fraction of the beds built in the insertion regions for the sample (default 0.6)")
      ->check(CLI::Range(0.05, 0.74));
  estimate->add_option("--sample-steps", options.sample_steps, "Steps timed per stage (default 300)")
      ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{1000000}));
  estimate->add_option("--sample-seconds", options.sample_seconds,
                       "Wall-clock cap of one stage's timed steps, in seconds (default 5)")
      ->check(CLI::PositiveNumber);
  estimate->add_option("--ranks", options.ranks,
                       "Also predict the run on N MPI ranks (each with --threads threads); repeatable, or N,M,...")
      ->type_name("N")
      ->delimiter(',')
      ->check(CLI::Range(1, kMostProjectedRanks));
  estimate->add_option("--latency-us", options.latency_us,
                       "For --ranks: the network's latency per message or collective round, in us (default 2)")
      ->check(CLI::PositiveNumber);
  estimate->add_option("--bandwidth-gb-per-s", options.bandwidth_GB_per_s,
                       "For --ranks: the bandwidth of one rank, in gigabytes (not bits) per second (default 10)")
      ->check(CLI::PositiveNumber);
  estimate->footer(
      "Each stage's particles are put in place at once, on a lattice at the solid fraction, and a few hundred of\n"
      "its steps (heat steps for a static bed) are timed; the prediction is steps x particles / rate. Stages that\n"
      "end on settling or on a measurement count their max_duration: an upper bound, marked <=. See docs/estimate.md.");
  return estimate;
}

int estimate_scenario(const EstimateCommandOptions& options) {
  const int threads = options.threads > 0 ? options.threads : omp_get_max_threads();
  omp_set_num_threads(threads);
  std::optional<PreparedRun> prepared;
  try {
    if (!options.json_path.empty()) {
      const std::filesystem::path folder = std::filesystem::absolute(options.json_path).parent_path();
      if (!std::filesystem::is_directory(folder))
        throw InputError(fmt::format("--json {}: the folder '{}' does not exist", options.json_path, folder.string()));
    }
    const ScenarioSpec spec = read_scenario_file(options.scenario_path, options.overrides);
    prepared.emplace(PreparedRun::build(spec, threads));
  } catch (const InputError& error) {
    fmt::print(stderr, "regodem: error: {}\n", error.what());
    return exit_status::bad_input;
  }
  EstimateOptions estimate_options;
  estimate_options.solid_fraction = options.solid_fraction;
  estimate_options.sample_steps = options.sample_steps;
  estimate_options.sample_seconds = options.sample_seconds;
  estimate_options.ranks = options.ranks;
  estimate_options.network.latency_s = options.latency_us * 1e-6;
  estimate_options.network.bandwidth_bytes_per_s = options.bandwidth_GB_per_s * 1e9;
  const RunEstimate estimate =
      estimate_run(prepared->simulation(), prepared->plan(), estimate_options, [](const std::string& line) {
        fmt::print(stderr, "estimate: {}\n", line);
        std::fflush(stderr);
      });
  print_table(estimate, threads);
  print_over_ranks(estimate, estimate_options, threads);
  if (!options.json_path.empty())
    write_file_atomically(options.json_path, to_json(estimate, options, threads).dump(2) + "\n");
  std::fflush(stdout);
  return estimate.complete ? exit_status::success : exit_status::run_failed;
}

}  // namespace regodem::app
