// One run into its output directory (run_session.hpp): `regodem run`, `regodem resume`
// and the Python module's Run all go through here, so their outputs are the same.
#include "run_session.hpp"

#include <omp.h>
#include <unistd.h>

#include <cstdlib>
#include <system_error>

#include <fmt/chrono.h>
#include <fmt/format.h>

#include "core/error.hpp"
#include "human_format.hpp"
#include "io/atomic_file.hpp"
#include "io/output_directory.hpp"
#include "io/stl_writer.hpp"
#include "measure/thermal_history.hpp"
#include "regodem/build_info.hpp"
#include "scenario/scenario_reader.hpp"
#include "sim/measurement_runner.hpp"
#include "sim/run_checkpoint.hpp"
#include "sim/simulation.hpp"
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
void write_reproduction_files(const fs::path& directory, const RunOptions& options,
                              const std::optional<std::string>& scenario_text) {
  if (scenario_text)
    write_file_atomically(directory / scenario_copy_file, *scenario_text);
  else
    copy_file_atomically(options.scenario_path, directory / scenario_copy_file);
  write_file_atomically(directory / overrides_file, overrides_file_content(options.overrides));
}

std::string stage_phrase(const std::optional<StageInfo>& stage) {
  if (!stage) return "before the first stage";
  return fmt::format("in stage {}/{} '{}'", stage->index + 1, stage->count, stage->name);
}

RunEnding ending_from_outcome(const RunOutcome& outcome) {
  if (outcome.completed) return {RunStatus::completed, exit_status::success, outcome};
  if (outcome.interrupted) return {RunStatus::interrupted, exit_status::interrupted, outcome};
  return {RunStatus::failed, exit_status::run_failed, outcome};
}

/// A runner that threw still leaves what the last progress report knew.
RunEnding ending_from_exception(const std::string& message, int exit_code, const RunRecorder* recorder,
                             double wall_s) {
  RunEnding ending;
  ending.exit_code = exit_code;
  ending.thrown = true;
  ending.outcome.message = message;
  ending.outcome.wall_s = wall_s;
  if (const std::optional<ProgressSnapshot> snapshot = recorder ? recorder->last_snapshot() : std::nullopt) {
    ending.outcome.particles = snapshot->particles;
    ending.outcome.steps = snapshot->step;
    ending.outcome.simulated_time_s = snapshot->time_s;
  }
  return ending;
}

RunSummary make_summary(const RunEnding& ending, const ScenarioSpec& spec, const RunOptions& options,
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
  summary.mpi_ranks = options.mpi_ranks;
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
  for (std::size_t b = 0; heat.enabled && b < sim.wall_thermal_state.size(); ++b) {
    const ThermalWallState& w = sim.wall_thermal_state[b];
    if (sim.model().wall_thermal[b].mode == WallThermalMode::lumped)
      summary.lumped_walls.push_back({sim.walls.bodies[b].name, w.temperature_K, w.peak_temperature_K,
                                      w.segment_temperature_K, w.generated_heat_J, w.heat_to_particles_J,
                                      w.radiated_heat_J, w.held_end_heat_in_J});
  }
  // A run over MPI ranks that threw (rank 0 could not write an output) with its particles
  // split: the run-wide sums over the particles need every rank, which are elsewhere (a
  // collective here would wait for them for ever), so the summary leaves them out.
  const bool split = sim.distributed();
  if (sim.keeps_energy_audit() && !split) {
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
  if (const ImpactRecord& impact = sim.fastest_impact(); impact.seen())
    summary.fastest_impact =
        ImpactSummary{impact.approach_speed_m_per_s, impact.contact_time_s(),
                      impact.contact_time_s() / sim.settings().time_step_s,
                      impact.wall_body < 0 ? std::string() : sim.walls.bodies[static_cast<std::size_t>(impact.wall_body)].name,
                      impact.time_s};
  if (sim.bonds_configured() && !split) {
    const BondCounts bonds = sim.bond_counts();  // the simulation's, whether the run ended or threw
    summary.bonds = BondSummary{bonds.formed, bonds.intact, bonds.broken_in_tension, bonds.broken_in_shear};
  }
  const StageResult unfinished =
      ending.status == RunStatus::interrupted ? StageResult::interrupted : StageResult::failed;
  if (const HeatSettings& h = sim.settings().heat; h.enabled && h.track_thermal_history && !split) {
    const ThermalHistorySummary t = thermal_history_summary(sim.particles, h.thermal_history_threshold_K);
    summary.thermal_history = ThermalHistoryFinal{h.thermal_history_threshold_K, t.particles, t.crossed,
                                                  t.crossed_fraction(), t.peak_temperature_max_K,
                                                  t.time_above_threshold_mean_s, t.time_above_threshold_max_s};
  }
  summary.measurements = recorder.measurement_finals();
  summary.stages = recorder.stage_summaries(outcome.simulated_time_s, unfinished);
  summary.notices = recorder.notices();
  if (split)
    summary.notices.push_back("the run stopped with its particles split over the MPI ranks: summary.json leaves out "
                              "the sums over the particles (the energy audit, the bond counts, the thermal history)");
  return summary;
}

std::string final_line(const RunEnding& ending, const RunRecorder& recorder, const CheckpointKeeper& checkpoints,
                       const fs::path& directory, double time_scale_factor, const std::string& stop_cause) {
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
          "regodem: interrupted by {} {} at t = {}{} after {}; outputs so far in {}; {}", stop_cause,
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

}  // namespace

ThreadChoice choose_run_threads(int requested) {
  if (requested > 0) return {requested, ""};
  if (std::getenv("OMP_NUM_THREADS") != nullptr) return {omp_get_max_threads(), ""};  // the user's own choice
  return choose_threads(omp_get_max_threads(), runnable_processes_elsewhere());
}

RunSession::RunSession(const RunOptions& options, const ResumePoint* resume, std::optional<std::string> scenario_text,
                       bool writes_outputs)
    : options_(options),
      resume_(resume),
      writes_outputs_(writes_outputs),
      scenario_text_(std::move(scenario_text)),
      started_at_(std::chrono::system_clock::now()) {
  try {
    spec_ = scenario_text_ ? read_scenario_string(*scenario_text_, options_.scenario_path, options_.overrides)
                           : read_scenario_file(options_.scenario_path, options_.overrides);
    directory_ = options_.output_directory.empty()
                     ? default_output_directory(scenario_name_of(spec_, options_.scenario_path))
                     : fs::path(options_.output_directory);
    if (!writes_outputs_) {
      prepared_.emplace(PreparedRun::build(spec_, options_.threads));
      return;
    }
    if (!resume_) check_output_directory(directory_, options_.overwrite);  // before the lock creates it
    lock_.emplace(directory_, resume_ ? fmt::format("regodem resume {}", directory_.string())
                                      : fmt::format("regodem run {}", options_.scenario_path));
    if (resume_) {
      const RunIdentity identity = read_identity(resume_->checkpoint);
      if (identity.content_hash != spec_.content_hash)
        throw InputError(fmt::format(
            "the scenario '{}' (with its --set values) has changed since the run wrote checkpoint '{}' (content hash "
            "{}, now {}); resuming would not continue that run. Restore the file, or start a new run from the "
            "checkpoint with `initial_state: {{checkpoint: {}}}`",
            options_.scenario_path, resume_->file, identity.content_hash, spec_.content_hash, resume_->file));
    } else {
      // Refuse a used directory before building, which may take a while, but clear it
      // only after, so that a scenario that cannot run leaves a previous run's outputs.
      check_output_directory(directory_, options_.overwrite);
      std::vector<fs::path> inputs = run_input_paths(spec_, options_.scenario_path);
      if (scenario_text_) inputs.erase(inputs.begin());  // no file: the text is the scenario
      check_inputs_outside_outputs(directory_, run_output_names(spec_), inputs);
    }
    prepared_.emplace(PreparedRun::build(spec_, options_.threads));
  } catch (const InputError&) {
    abandon();  // a refused run leaves no empty folder behind
    throw;
  }
}

RunSession::~RunSession() = default;

void RunSession::abandon() {
  if (lock_) lock_->release_and_remove_created_directory();
  lock_.reset();
}

fs::path RunSession::identity_scenario_path() const {
  const fs::path file = scenario_text_ ? directory_ / scenario_copy_file : fs::path(options_.scenario_path);
  return fs::absolute(file).lexically_normal();
}

void RunSession::begin(std::FILE* progress) {
  if (!writes_outputs_) {
    if (resume_) check_resumable(*prepared_, resume_->checkpoint, directory_);
    return;
  }
  try {
    if (resume_) {
      check_resumable(*prepared_, resume_->checkpoint, directory_);
    } else {
      for (const fs::path& kept : prepare_output_directory(directory_, options_.overwrite, run_output_names(spec_)))
        if (progress) fmt::print(progress, "regodem: note: --overwrite kept '{}' (not a file a run writes)\n", kept.string());
    }
  } catch (const InputError&) {
    abandon();
    throw;
  }
  if (progress)
    for (const std::string& warning : prepared_->warnings()) fmt::print(progress, "regodem: warning: {}\n", warning);
  if (!resume_) {
    try {
      write_reproduction_files(directory_, options_, scenario_text_);
      write_generated_meshes(directory_, spec_);
    } catch (const std::system_error& error) {
      // A directory the run may not write into (read-only, a file in the way) is bad
      // input, before anything ran.
      throw InputError(fmt::format("cannot write the run's files in '{}': {}", directory_.string(), error.what()));
    }
  }

  display_ = std::make_unique<ProgressDisplay>(progress, progress != nullptr && ::isatty(::fileno(progress)) == 1,
                                               spec_.output.progress_interval_s);
  display_->set_time_scale(TimeScale{prepared_->simulation().settings().heat.time_scale_factor});
  std::vector<std::string> stage_names;
  for (const StageSpec& stage : spec_.stages) stage_names.push_back(stage.name);
  recorder_ = std::make_unique<RunRecorder>(directory_ / time_series_file, *display_, stage_names);
  if (const SnapshotSpec& snap = spec_.output.snapshots; snap.enabled) {
    snapshots_.emplace(directory_, VtpOptions{snap.compress}, snap.walls, prepared_->plan().region_names);
    recorder_->write_snapshots_with(&*snapshots_);
  }
  recorder_->set_bond_breaks_path(directory_ / bond_breaks_file);
  recorder_->set_measurements_directory(directory_);
  checkpoints_ = std::make_unique<CheckpointKeeper>(directory_, options_.checkpoint_every_s);
  recorder_->keep_checkpoints_with(
      checkpoints_.get(),
      RunIdentity{identity_scenario_path().string(), options_.overrides, spec_.content_hash, options_.threads});
  if (resume_) {
    for (const std::string& skipped : resume_->skipped) recorder_->notice(skipped);
    try {
      recorder_->resume_outputs(resume_->checkpoint);
    } catch (const std::exception& error) {
      throw InputError(fmt::format("cannot continue the outputs in {}: {}", directory_.string(), error.what()));
    }
    display_->notice(fmt::format("resuming from {}", resume_->file));
  }
}

RunEnding RunSession::run(const std::atomic<bool>& stop_requested, RunObserver* extra) {
  const auto wall_start = std::chrono::steady_clock::now();
  const auto wall_s = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  };
  std::optional<ObserverPair> pair;
  RunObserver& recorder = writes_outputs_ ? static_cast<RunObserver&>(*recorder_) : quiet_;
  if (extra) pair.emplace(recorder, *extra);
  RunObserver& observer = pair ? static_cast<RunObserver&>(*pair) : recorder;
  RunEnding ending;
  try {
    ending = ending_from_outcome(resume_ ? prepared_->resume(resume_->checkpoint, observer, stop_requested)
                                         : prepared_->run(observer, stop_requested));
  } catch (const InputError& error) {
    // Something only the run could find out (a particle file that will not read).
    ending = ending_from_exception(error.what(), exit_status::bad_input, recorder_.get(), wall_s());
  } catch (const std::exception& error) {
    ending = ending_from_exception(error.what(), exit_status::run_failed, recorder_.get(), wall_s());
  }
  if (display_) display_->finish();
  return ending;
}

std::string RunSession::finish(const RunEnding& ending, const std::string& stop_cause) {
  if (!writes_outputs_) return "";
  write_summary_json(directory_ / summary_file,
                     make_summary(ending, spec_, options_, *prepared_, *recorder_, started_at_));
  return final_line(ending, *recorder_, *checkpoints_, directory_,
                    prepared_->simulation().settings().heat.time_scale_factor, stop_cause);
}

}  // namespace regodem::app
