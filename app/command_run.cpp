// `regodem run`: read and build the scenario, prepare the output directory, run every
// stage with progress on stderr, write summary.json, and end with one line that says
// how it went and where the outputs are.
#include <unistd.h>

#include <omp.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <optional>
#include <string>
#include <system_error>

#include <fmt/chrono.h>
#include <fmt/format.h>

#include "checkpoint_keeper.hpp"
#include "commands.hpp"
#include "core/error.hpp"
#include "core/thread_choice.hpp"
#include "human_format.hpp"
#include "io/atomic_file.hpp"
#include "io/output_directory.hpp"
#include "io/run_directory_lock.hpp"
#include "io/stl_writer.hpp"
#include "io/summary_json_writer.hpp"
#include "measure/thermal_history.hpp"
#include "progress_display.hpp"
#include "regodem/build_info.hpp"
#include "run_recorder.hpp"
#include "scenario/scenario_builder.hpp"
#include "scenario/scenario_reader.hpp"
#include "signal_handling.hpp"
#include "sim/measurement_runner.hpp"
#include "sim/run_checkpoint.hpp"
#include "sim/simulation.hpp"
#include "sim/snapshot_capture.hpp"
#include "sim/stage_plan.hpp"

namespace regodem::app {
namespace {

namespace fs = std::filesystem;

// The files a run writes in its output directory; --overwrite replaces these only.
constexpr const char* time_series_file = "time_series.csv";
constexpr const char* summary_file = "summary.json";
constexpr const char* scenario_copy_file = "scenario.yaml";
constexpr const char* overrides_file = "overrides.txt";
constexpr const char* bond_breaks_file = "bond_breaks.csv";  // only when a bond broke
constexpr const char* regions_folder = "regions";    // measurements: regions and bands
constexpr const char* profiles_folder = "profiles";  // measurements: profiles

std::string utc_timestamp(std::chrono::system_clock::time_point when) {
  return fmt::format("{:%Y-%m-%dT%H:%M:%SZ}", fmt::gmtime(std::chrono::system_clock::to_time_t(when)));
}

std::string scenario_name_of(const ScenarioSpec& spec, const std::string& scenario_path) {
  return spec.name.empty() ? fs::path(scenario_path).stem().string() : spec.name;
}

/// "out/demo/": a trailing separator says "a folder" in the final message.
std::string folder_for_message(const fs::path& directory) {
  std::string text = directory.string();
  if (text.empty() || text.back() != '/') text += '/';
  return text;
}

std::string overrides_file_content(const std::vector<std::string>& overrides) {
  std::string content;
  for (const std::string& override_text : overrides) content += override_text + '\n';
  return content;
}

/// Generated meshes (augers) are written as '<wall>.stl', so users can look at the
/// drill they simulated (in its placement at the start).
std::vector<std::string> generated_mesh_files(const ScenarioSpec& spec) {
  std::vector<std::string> names;
  for (const WallSpec& wall : spec.walls)
    if (wall.auger && wall.mesh) names.push_back(wall.name + ".stl");
  return names;
}

/// Every file and folder the run writes in its output directory.
std::vector<std::string> run_output_names(const ScenarioSpec& spec) {
  std::vector<std::string> outputs{time_series_file,
                                   summary_file,
                                   scenario_copy_file,
                                   overrides_file,
                                   SnapshotSeries::particles_collection,
                                   SnapshotSeries::walls_collection,
                                   SnapshotSeries::data_folder,
                                   bond_breaks_file,
                                   regions_folder,
                                   profiles_folder,
                                   CheckpointKeeper::folder};
  for (const std::string& mesh_file : generated_mesh_files(spec)) outputs.push_back(mesh_file);
  return outputs;
}

/// Every file the run reads: the scenario, its meshes and particle files, and the
/// checkpoints it starts from (a run's directory: its checkpoints folder).
std::vector<fs::path> run_input_paths(const ScenarioSpec& spec, const std::string& scenario_path) {
  std::vector<fs::path> inputs{scenario_path};
  for (const WallSpec& wall : spec.walls)
    if (!wall.mesh_file.empty()) inputs.emplace_back(wall.mesh_file);
  for (const InsertionSpec& insertion : spec.insertions)
    if (!insertion.from_file.empty()) inputs.emplace_back(insertion.from_file);
  if (const fs::path initial(spec.initial_state_checkpoint); !initial.empty())
    inputs.push_back(fs::is_directory(initial) ? initial / CheckpointKeeper::folder : initial);
  return inputs;
}

void write_generated_meshes(const fs::path& directory, const ScenarioSpec& spec) {
  for (const WallSpec& wall : spec.walls)
    if (wall.auger && wall.mesh) write_stl(directory / (wall.name + ".stl"), *wall.mesh, StlFormat::binary, wall.name);
}

/// The copy of the scenario and the --set values that together reproduce the run.
void write_reproduction_files(const fs::path& directory, const RunOptions& options) {
  copy_file_atomically(options.scenario_path, directory / scenario_copy_file);
  write_file_atomically(directory / overrides_file, overrides_file_content(options.overrides));
}

std::string signal_name(int signal_number) {
  if (signal_number == SIGINT) return "SIGINT";
  if (signal_number == SIGTERM) return "SIGTERM";
  return fmt::format("signal {}", signal_number);
}

std::string stage_phrase(const std::optional<StageInfo>& stage) {
  if (!stage) return "before the first stage";
  return fmt::format("in stage {}/{} '{}'", stage->index + 1, stage->count, stage->name);
}

/// How the run ended, whether the runner returned or threw.
struct Ending {
  RunStatus status = RunStatus::failed;
  int exit_code = exit_status::run_failed;
  RunOutcome outcome;
};

Ending ending_from_outcome(const RunOutcome& outcome) {
  if (outcome.completed) return {RunStatus::completed, exit_status::success, outcome};
  if (outcome.interrupted) return {RunStatus::interrupted, exit_status::interrupted, outcome};
  return {RunStatus::failed, exit_status::run_failed, outcome};
}

/// A runner that threw still leaves what the last progress report knew.
Ending ending_from_exception(const std::string& message, int exit_code, const RunRecorder& recorder,
                             double wall_s) {
  Ending ending;
  ending.exit_code = exit_code;
  ending.outcome.message = message;
  ending.outcome.wall_s = wall_s;
  if (const std::optional<ProgressSnapshot> snapshot = recorder.last_snapshot()) {
    ending.outcome.particles = snapshot->particles;
    ending.outcome.steps = snapshot->step;
    ending.outcome.simulated_time_s = snapshot->time_s;
  }
  return ending;
}

RunSummary make_summary(const Ending& ending, const ScenarioSpec& spec, const RunOptions& options,
                        const PreparedRun& prepared, const RunRecorder& recorder,
                        std::chrono::system_clock::time_point started_at) {
  const RunOutcome& outcome = ending.outcome;
  RunSummary summary;
  summary.status = ending.status;
  summary.message = outcome.message;
  summary.particles = outcome.particles;
  summary.steps = outcome.steps;
  summary.simulated_time_s = outcome.simulated_time_s;
  summary.wall_time_s = outcome.wall_s;
  summary.particle_steps_per_s = outcome.particle_steps_per_s;
  summary.time_step_s = prepared.time_step_s();
  summary.threads = prepared.threads();
  summary.version = build_info::version;
  summary.build_type = build_info::build_type;
  summary.compiler = build_info::compiler;
  summary.started_at_utc = utc_timestamp(started_at);
  summary.scenario_name = scenario_name_of(spec, options.scenario_path);
  summary.scenario_file = options.scenario_path;
  summary.scenario_hash = spec.content_hash;
  summary.scenario_copy = scenario_copy_file;
  summary.overrides = options.overrides;
  const HeatSettings& heat = prepared.simulation().settings().heat;
  summary.heat = {heat.enabled,      heat.time_scale_factor, heat.friction_heating, heat.dissipation_heating,
                  to_string(heat.partition), heat.friction_partition};
  const Simulation& sim = prepared.simulation();
  for (std::size_t b = 0; heat.enabled && b < sim.wall_thermal.size(); ++b) {
    const ThermalWall& w = sim.wall_thermal[b];
    if (w.mode == WallThermalMode::lumped)
      summary.lumped_walls.push_back({sim.walls.bodies[b].name, w.temperature_K, w.peak_temperature_K,
                                      w.segment_temperature_K, w.generated_heat_J, w.heat_to_particles_J,
                                      w.radiated_heat_J, w.held_end_heat_in_J});
  }
  if (sim.keeps_energy_audit()) {
    const EnergyAudit& audit = sim.energy_audit();
    EnergyAuditSummary a;
    a.wall_work_J = audit.wall_work_J;
    a.dissipated_J = audit.dissipated_J;
    a.spring_source_J = audit.spring_source_J;
    a.exchanged_J = audit.exchanged_J;
    a.mechanical_energy_J = sim.mechanical_energy_J();
    a.imbalance_J = sim.mechanical_imbalance_J();
    a.relative_imbalance = audit.relative(a.imbalance_J);
    for (std::size_t b = 0; b < sim.walls.bodies.size(); ++b) {
      const WallBody& wall = sim.walls.bodies[b];
      if (wall.fed_or_spun())
        a.wall_work_by_wall_J.emplace_back(wall.name, audit.wall_work_by_body_J[b]);
    }
    summary.energy_audit = a;
  }
  if (sim.bonds_configured()) {
    const BondCounts bonds = sim.bond_counts();  // the simulation's, whether the run ended or threw
    summary.bonds = BondSummary{bonds.formed, bonds.intact, bonds.broken_in_tension, bonds.broken_in_shear};
  }
  const StageResult unfinished =
      ending.status == RunStatus::interrupted ? StageResult::interrupted : StageResult::failed;
  if (const HeatSettings& h = sim.settings().heat; h.enabled && h.track_thermal_history) {
    const ThermalHistorySummary t = thermal_history_summary(sim.particles, h.thermal_history_threshold_K);
    summary.thermal_history = ThermalHistoryFinal{h.thermal_history_threshold_K, t.particles, t.crossed,
                                                  t.crossed_fraction(), t.peak_temperature_max_K,
                                                  t.time_above_threshold_mean_s, t.time_above_threshold_max_s};
  }
  summary.measurements = recorder.measurement_finals();
  summary.stages = recorder.stage_summaries(outcome.simulated_time_s, unfinished);
  summary.notices = recorder.notices();
  return summary;
}

std::string final_line(const Ending& ending, const RunRecorder& recorder, const CheckpointKeeper& checkpoints,
                       const fs::path& directory, double time_scale_factor) {
  const RunOutcome& outcome = ending.outcome;
  const std::string real = real_time_note(time_scale_factor, {outcome.simulated_time_s});
  const std::string where = folder_for_message(directory);
  switch (ending.status) {
    case RunStatus::completed:
      return fmt::format("regodem: completed {} stage{} in {} ({} particle-steps/s); outputs in {}",
                         outcome.stages_finished, outcome.stages_finished == 1 ? "" : "s",
                         format_wall_duration(outcome.wall_s),
                         format_compact(outcome.particle_steps_per_s), where);
    case RunStatus::interrupted:
      return fmt::format(
          "regodem: interrupted by {} {} at t = {}{} after {}; outputs so far in {}; {}", signal_name(stop_signal()),
          stage_phrase(recorder.current_stage()), format_simulated_time(outcome.simulated_time_s), real,
          format_wall_duration(outcome.wall_s), where,
          checkpoints.latest() && recorder.checkpoint_failure().empty()
              ? fmt::format("checkpoint {}; continue with: regodem resume {}", checkpoints.latest()->string(),
                            directory.string())
              : fmt::format("no checkpoint could be written ({})", recorder.checkpoint_failure()));
    case RunStatus::failed:
      break;
  }
  return fmt::format("regodem: failed {} at t = {}{} after {}; outputs so far in {}",
                     stage_phrase(recorder.current_stage()),
                     format_simulated_time(outcome.simulated_time_s), real,
                     format_wall_duration(outcome.wall_s), where);
}

/// Restores the checkpoint once before any output is touched, so that one whose
/// contents do not fit (another list of particle fields, other walls) is refused with
/// the run directory as it was. The run restores it again where it goes on.
void check_resumable(PreparedRun& prepared, const Checkpoint& checkpoint, const fs::path& directory) {
  try {
    StagePlan& plan = prepared.plan();
    Rng rng(plan.seed);
    SnapshotClock snapshots(plan.snapshots);
    MeasurementRunner measurements(plan.measurements);
    restore_run_state(checkpoint, plan, rng, snapshots, measurements);
    prepared.simulation().restore_state(checkpoint);
  } catch (const CheckpointError& error) {
    throw InputError(fmt::format("{} (nothing in '{}' was changed)", error.what(), directory.string()));
  }
}

/// `regodem run`, or with `resume` the continuation of a run from its checkpoint.
int execute(const RunOptions& options, const ResumePoint* resume) {
  const auto started_at = std::chrono::system_clock::now();
  // First of all, so that a signal while the scenario is read or built still ends in a
  // summary and a checkpoint (at the run's first step boundary).
  const std::atomic<bool>& stop_requested = install_stop_request_handlers();
  ThreadChoice choice{options.threads, ""};  // the default: the cores other processes leave
  if (options.threads <= 0)
    choice = std::getenv("OMP_NUM_THREADS") != nullptr
                 ? ThreadChoice{omp_get_max_threads(), ""}  // the user's own choice, as --threads
                 : choose_threads(omp_get_max_threads(), runnable_processes_elsewhere());
  const int threads = choice.threads;
  if (!choice.note.empty()) fmt::print(stderr, "regodem: note: {}\n", choice.note);
  omp_set_num_threads(threads);

  std::optional<ScenarioSpec> spec;
  std::optional<PreparedRun> prepared;
  std::optional<RunDirectoryLock> lock;  // held to the end of the run: one writer per directory
  fs::path directory;
  try {
    spec = read_scenario_file(options.scenario_path, options.overrides);
    directory = options.output_directory.empty()
                    ? default_output_directory(scenario_name_of(*spec, options.scenario_path))
                    : fs::path(options.output_directory);
    if (!resume) check_output_directory(directory, options.overwrite);  // before the lock creates it
    lock.emplace(directory, resume ? fmt::format("regodem resume {}", directory.string())
                                   : fmt::format("regodem run {}", options.scenario_path));
    if (resume) {
      const RunIdentity identity = read_identity(resume->checkpoint);
      if (identity.content_hash != spec->content_hash)
        throw InputError(fmt::format(
            "the scenario '{}' (with its --set values) has changed since the run wrote checkpoint '{}' (content hash "
            "{}, now {}); resuming would not continue that run. Restore the file, or start a new run from the "
            "checkpoint with `initial_state: {{checkpoint: {}}}`",
            options.scenario_path, resume->file, identity.content_hash, spec->content_hash, resume->file));
    } else {
      // Refuse a used directory before building, which may take a while, but clear it
      // only after, so that a scenario that cannot run leaves a previous run's outputs.
      check_output_directory(directory, options.overwrite);
      check_inputs_outside_outputs(directory, run_output_names(*spec),
                                   run_input_paths(*spec, options.scenario_path));
    }
    prepared.emplace(PreparedRun::build(*spec, threads));
    // A signal while the scenario was read or built: stop before any old output goes.
    if (stop_requested.load()) {
      lock->release_and_remove_created_directory();
      fmt::print(stderr, "regodem: interrupted by {} before the run started; nothing in '{}' was changed\n",
                 signal_name(stop_signal()), directory.string());
      return exit_status::interrupted;
    }
    if (resume) {
      check_resumable(*prepared, resume->checkpoint, directory);
    } else {
      for (const fs::path& kept : prepare_output_directory(directory, options.overwrite, run_output_names(*spec)))
        fmt::print(stderr, "regodem: note: --overwrite kept '{}' (not a file a run writes)\n", kept.string());
    }
  } catch (const InputError& error) {
    if (lock) lock->release_and_remove_created_directory();  // a refused run leaves no empty folder behind
    fmt::print(stderr, "regodem: error: {}\n", error.what());
    return exit_status::bad_input;
  }
  if (!resume) {
    try {
      write_reproduction_files(directory, options);
      write_generated_meshes(directory, *spec);
    } catch (const std::system_error& error) {
      // A directory the run may not write into (read-only, a file in the way) is bad
      // input, before anything ran: exit 2, not an internal error.
      fmt::print(stderr, "regodem: error: cannot write the run's files in '{}': {}\n", directory.string(), error.what());
      return exit_status::bad_input;
    }
  }

  ProgressDisplay display(stderr, ::isatty(::fileno(stderr)) == 1, spec->output.progress_interval_s);
  const double time_scale_factor = prepared->simulation().settings().heat.time_scale_factor;
  display.set_time_scale(TimeScale{time_scale_factor});
  std::vector<std::string> stage_names;
  for (const StageSpec& stage : spec->stages) stage_names.push_back(stage.name);
  RunRecorder recorder(directory / time_series_file, display, stage_names);
  std::optional<SimulationSnapshotWriter> snapshots;
  if (const SnapshotSpec& snap = spec->output.snapshots; snap.enabled) {
    snapshots.emplace(directory, VtpOptions{snap.compress}, snap.walls, prepared->plan().region_names);
    recorder.write_snapshots_with(&*snapshots);
  }
  recorder.set_bond_breaks_path(directory / bond_breaks_file);
  recorder.set_measurements_directory(directory);
  CheckpointKeeper checkpoints(directory, options.checkpoint_every_s);
  recorder.keep_checkpoints_with(&checkpoints,
                                 RunIdentity{fs::absolute(options.scenario_path).lexically_normal().string(),
                                             options.overrides, spec->content_hash, threads});
  if (resume) {
    for (const std::string& skipped : resume->skipped) recorder.notice(skipped);
    try {
      recorder.resume_outputs(resume->checkpoint);
    } catch (const std::exception& error) {
      fmt::print(stderr, "regodem: error: cannot continue the outputs in {}: {}\n", directory.string(), error.what());
      return exit_status::bad_input;
    }
    display.notice(fmt::format("resuming from {}", resume->file));
  }

  const auto wall_start = std::chrono::steady_clock::now();
  const auto wall_s = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  };
  Ending ending;
  try {
    ending = ending_from_outcome(resume ? prepared->resume(resume->checkpoint, recorder, stop_requested)
                                        : prepared->run(recorder, stop_requested));
  } catch (const InputError& error) {
    // Something only the run could find out (a particle file that will not read).
    ending = ending_from_exception(error.what(), exit_status::bad_input, recorder, wall_s());
  } catch (const std::exception& error) {
    ending = ending_from_exception(error.what(), exit_status::run_failed, recorder, wall_s());
  }
  display.finish();

  if (ending.status == RunStatus::failed && !ending.outcome.message.empty()) {
    fmt::print(stderr, "regodem: {}\n", ending.outcome.message);
  }
  write_summary_json(directory / summary_file,
                     make_summary(ending, *spec, options, *prepared, recorder, started_at));
  fmt::print("{}\n", final_line(ending, recorder, checkpoints, directory, time_scale_factor));
  std::fflush(stdout);
  return ending.exit_code;
}

}  // namespace

int run_scenario(const RunOptions& options) { return execute(options, nullptr); }

int continue_run(const RunOptions& options, const ResumePoint& resume) { return execute(options, &resume); }

}  // namespace regodem::app
