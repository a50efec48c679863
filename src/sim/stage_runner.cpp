#include "sim/stage_runner.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <span>

#include "core/error.hpp"
#include "measure/measure_region.hpp"
#include "sim/measurement_runner.hpp"
#include "sim/recent_rate.hpp"
#include "sim/static_heat_stepper.hpp"
#include "sim/time_scale.hpp"

namespace regodem {
namespace {

constexpr std::uint64_t kCheckEverySteps = 64;

/// Applies a stage's overrides to the pair table; returns the table to restore.
MaterialTable apply_overrides(Simulation& sim, const std::vector<PairOverride>& overrides) {
  MaterialTable original = sim.model().materials;
  MaterialTable changed = original;
  const std::size_t n = original.size();
  for (const PairOverride& o : overrides) {
    for (std::size_t a = 0; a < n; ++a)
      for (std::size_t b = a; b < n; ++b) {
        const bool every_pair = o.material_a < 0;
        const bool this_pair = (static_cast<int>(a) == o.material_a && static_cast<int>(b) == o.material_b) ||
                               (static_cast<int>(b) == o.material_a && static_cast<int>(a) == o.material_b);
        if (!every_pair && !this_pair) continue;
        const auto ma = static_cast<MaterialIndex>(a), mb = static_cast<MaterialIndex>(b);
        PairProperties p = changed.pair(ma, mb);
        if (o.restitution) p.restitution = *o.restitution;
        if (o.sliding_friction) p.sliding_friction = *o.sliding_friction;
        if (o.rolling_friction) p.rolling_friction = *o.rolling_friction;
        changed.set_pair(ma, mb, p);
      }
  }
  if (!overrides.empty()) sim.set_materials(std::move(changed));
  return original;
}

double kinetic_energy_per_particle(const Simulation& sim) {
  const std::size_t count = sim.run_particle_count();
  if (count == 0) return 0.0;
  return (sim.translational_kinetic_energy_J() + sim.rotational_kinetic_energy_J()) / static_cast<double>(count);
}

// Decisions a rank's clock or a signal makes; under MPI every rank takes them at the same
// step (Simulation::bits_over_ranks), as any rank's clock or signal says.
enum ClockDecision : std::uint32_t { stop_now = 1, checkpoint_now = 2, progress_now = 4 };

/// Refuses a coupled heat step above the explicit limit min m c / sum G (DESIGN.md
/// section 2): the temperatures would oscillate and grow.
void check_coupled_heat_step(Simulation& sim) {
  if (!sim.heat_enabled()) return;
  const double limit = sim.thermal_stability_limit_s();
  if (sim.time_step_s() < limit) return;
  const double scale = sim.settings().heat.time_scale_factor;
  throw SimulationError(fmt::format(
      "the time step {:.4g} s is above the heat stability limit {:.4g} s (min m c / sum G over the particles at "
      "t = {:.6g} s) with time_scale_factor S = {:.4g}; use S below {:.3g}, or a static heat_stepping for a bed "
      "at rest",
      sim.time_step_s(), limit, sim.time_s(), scale, scale * limit / sim.time_step_s()));
}

bool conducting_wall(const ThermalWall& w) { return w.mode != WallThermalMode::adiabatic; }

/// A stage that ends at a drill depth: the time its wall needs to get there at its
/// feed speed (infinite when it is not moving).
/// A step count from a number of steps that the plan's limits keep below 1e12; one that
/// is not finite (a wall that never gets there) counts 0, "not known", and one past the
/// limit (a stage refused as it starts) is capped, rather than overflowing the conversion.
std::uint64_t whole_steps(double steps) {
  return std::isfinite(steps) && steps > 0.0 ? static_cast<std::uint64_t>(std::min(steps, max_steps_per_stage)) : 0;
}

double time_to_depth_s(const Simulation& sim, const Stage& stage) {
  const WallBody& wall = sim.walls.bodies[static_cast<std::size_t>(stage.depth_body)];
  const double speed = norm(wall.motion.velocity_m_per_s);
  const double to_go = std::max(0.0, stage.depth_m - wall.depth_m());
  return to_go == 0.0 ? 0.0 : speed > 0.0 ? to_go / speed : std::numeric_limits<double>::infinity();
}

bool feed_ended(const Simulation& sim, const Stage& stage) {
  const WallMotion& motion = sim.walls.bodies[static_cast<std::size_t>(stage.depth_body)].motion;
  return norm2(motion.velocity_m_per_s) == 0.0 || sim.time_s() >= motion.stop_s;
}

std::string measurement_not_reached(const Simulation& sim, const StagePlan& plan, const Stage& stage) {
  const MeasurementTarget& target = *stage.until_measured;
  const Measurement& m = plan.measurements.items[target.measurement];
  return fmt::format(
      "stage '{}' ended at its max_duration of {:.6g} s before '{}' {} {:.6g} K: it is {:.6g} K. Raise max_duration.",
      stage.name, stage.max_duration_s, m.name, target.rising ? "rose to" : "fell to", target.value_K,
      measured_value(m, sim, target.quantity));
}

/// Whether the run's fastest impact so far had at least kMinimumStepsPerImpact steps.
bool impacts_resolved(const Simulation& sim) {
  const ImpactRecord& impact = sim.fastest_impact();
  return !impact.seen() || impact.contact_time_s() >= kMinimumStepsPerImpact * sim.settings().time_step_s;
}

/// Said once a run, when its fastest impact first gets fewer steps than that.
std::string unresolved_impact_notice(const Simulation& sim, const std::string& stage) {
  const ImpactRecord& impact = sim.fastest_impact();
  return fmt::format(
      "stage '{}': at t = {:.4g} s a particle closed on {} at {:.3g} m/s, a Hertz contact of {:.1f} steps, fewer than "
      "{:.0f}: the losses of such contacts (and their heat) depend on the step (docs/physics.md, \"Time step and "
      "integration\"); the run's fastest impact is in summary.json",
      stage, impact.time_s,
      impact.wall_body < 0 ? std::string("another")
                           : fmt::format("wall '{}'", sim.walls.bodies[static_cast<std::size_t>(impact.wall_body)].name),
      impact.approach_speed_m_per_s, impact.contact_time_s() / sim.settings().time_step_s, kMinimumStepsPerImpact);
}

bool reached_depth(const Simulation& sim, const Stage& stage) {
  return sim.walls.bodies[static_cast<std::size_t>(stage.depth_body)].depth_m() >= stage.depth_m * (1.0 - 1e-12);
}

}  // namespace

std::vector<SeriesColumn> time_series_columns(const Simulation& sim) {
  // Simulated time, then its real-time equivalent (x S, sim/time_scale.hpp): the same
  // column with S = 1, so that every file has one shape.
  std::vector<SeriesColumn> columns = {
      {"time", "s"},
      {"real_time", "s"},
      {"step", "-"},
      {"stage", "-"},
      {"particles", "-"},
  };
  if (sim.settings().lost_particles == LostParticles::remove) columns.push_back({"particles_lost", "-"});
  columns.insert(columns.end(), {
      {"kinetic_energy", "J"},
      {"rotational_kinetic_energy", "J"},
      {"potential_energy", "J"},
      {"max_speed", "m/s"},
      {"particle_contacts", "-"},
      {"wall_contacts", "-"},
      {"coordination_number", "-"},
      {"max_overlap_fraction", "-"},
      {"fastest_impact_speed", "m/s"},     // the run's so far (sim/impact_record.hpp)
      {"shortest_impact_steps", "-"},      // its Hertz contact time over the step
  });
  for (const WallBody& wall : sim.walls.bodies) {
    for (const char* axis : {"x", "y", "z"}) columns.push_back({wall.name + ".force_" + axis, "N"});
    for (const char* axis : {"x", "y", "z"}) columns.push_back({wall.name + ".torque_" + axis, "N m"});
    // A drilling engineer's first look: depth, thrust against the feed, torque against the turn.
    if (wall.fed()) columns.insert(columns.end(), {{wall.name + ".depth", "m"}, {wall.name + ".thrust", "N"}});
    if (wall.spun()) columns.push_back({wall.name + ".drive_torque", "N m"});
  }
  if (sim.bonds_configured()) columns.insert(columns.end(), {{"bonds_intact", "-"}, {"bonds_broken", "-"}});
  if (sim.keeps_energy_audit()) {
    // The energy audit (docs/physics.md, "Energy audit"): kinetic + potential + elastic =
    // wall work + exchanged + spring source - dissipated, up to the imbalance.
    columns.insert(columns.end(), {{"elastic_energy", "J"},
                                   {"wall_work", "J"},
                                   {"dissipated_energy", "J"},
                                   {"spring_source", "J"},
                                   {"exchanged_energy", "J"},
                                   {"mechanical_imbalance", "-"}});
    for (const WallBody& wall : sim.walls.bodies)
      if (wall.fed_or_spun()) columns.push_back({wall.name + ".work", "J"});  // on the particles, so far
  }
  if (!sim.heat_enabled()) return columns;
  columns.insert(columns.end(), {{"temperature_mean", "K"},
                                 {"temperature_min", "K"},
                                 {"temperature_max", "K"},
                                 {"thermal_energy", "J"},
                                 {"boundary_heat_in", "J"},
                                 {"generated_heat", "J"},
                                 {"energy_imbalance", "-"}});
  const std::vector<SeriesColumn> history = thermal_history_columns(sim);
  columns.insert(columns.end(), history.begin(), history.end());
  for (std::size_t b = 0; b < sim.walls.bodies.size(); ++b)
    if (conducting_wall(sim.model().wall_thermal[b])) {
      columns.push_back({sim.walls.bodies[b].name + ".temperature", "K"});
      columns.push_back({sim.walls.bodies[b].name + ".heat_flow", "W"});  // into the particles
      columns.push_back({sim.walls.bodies[b].name + ".heat_flow_real", "W"});  // the same in real time (/ S)
      columns.push_back({sim.walls.bodies[b].name + ".heat_to_particles", "J"});  // cumulative
      // A drill as a thermal body (docs/drilling-heat.md): its hottest node so far, each
      // segment, and what its own heat paths took (cumulative).
      const ThermalWall& w = sim.model().wall_thermal[b];
      if (w.mode != WallThermalMode::lumped || !w.rod.exchanges()) continue;
      columns.push_back({sim.walls.bodies[b].name + ".peak_temperature", "K"});
      for (std::size_t s = 0; s < sim.wall_thermal_state[b].segment_temperature_K.size(); ++s)
        columns.push_back({fmt::format("{}[{}].temperature", sim.walls.bodies[b].name, s + 1), "K"});
      if (w.rod.emissivity > 0.0) columns.push_back({sim.walls.bodies[b].name + ".radiated_heat", "J"});
      if (w.rod.held_end_K) columns.push_back({sim.walls.bodies[b].name + ".held_end_heat", "J"});  // in
    }
  return columns;
}

std::vector<double> time_series_row(const Simulation& sim, std::size_t stage_index) {
  const auto& stats = sim.contact_statistics();
  const double n = static_cast<double>(sim.run_particle_count());
  const TimeScale scale{sim.settings().heat.time_scale_factor};
  const ImpactRecord& impact = sim.fastest_impact();
  std::vector<double> row = {
      sim.time_s(),
      scale.real_time_s(sim.time_s()),
      static_cast<double>(sim.step_count()),
      static_cast<double>(stage_index),
      n,
  };
  if (sim.settings().lost_particles == LostParticles::remove)
    row.push_back(static_cast<double>(sim.lost_particle_count()));
  row.insert(row.end(), {
      sim.translational_kinetic_energy_J() + sim.rotational_kinetic_energy_J(),
      sim.rotational_kinetic_energy_J(),
      sim.gravitational_potential_energy_J(),
      sim.max_speed_m_per_s(),
      static_cast<double>(stats.particle_contacts),
      static_cast<double>(stats.wall_contacts),
      n > 0 ? (2.0 * static_cast<double>(stats.particle_contacts) + static_cast<double>(stats.wall_contacts)) / n : 0.0,
      sim.max_overlap_fraction(),
      impact.seen() ? impact.approach_speed_m_per_s : std::numeric_limits<double>::quiet_NaN(),
      impact.seen() ? impact.contact_time_s() / sim.settings().time_step_s : std::numeric_limits<double>::quiet_NaN(),
  });
  for (const WallBody& wall : sim.walls.bodies) {
    row.insert(row.end(), {wall.force_N.x, wall.force_N.y, wall.force_N.z});
    row.insert(row.end(), {wall.torque_N_m.x, wall.torque_N_m.y, wall.torque_N_m.z});
    if (wall.fed()) row.insert(row.end(), {wall.depth_m(), -dot(wall.force_N, wall.feed_direction)});
    if (wall.spun()) row.push_back(-dot(wall.torque_N_m, wall.spin_axis));
  }
  if (sim.bonds_configured()) {
    const BondCounts bonds = sim.bond_counts();
    row.insert(row.end(), {static_cast<double>(bonds.intact), static_cast<double>(bonds.broken())});
  }
  if (sim.keeps_energy_audit()) {
    const EnergyAudit& audit = sim.energy_audit();
    row.insert(row.end(), {sim.elastic_energy_J(), audit.wall_work_J, audit.dissipated_J, audit.spring_source_J,
                           audit.exchanged_J, audit.relative(sim.mechanical_imbalance_J())});
    for (std::size_t b = 0; b < sim.walls.bodies.size(); ++b)
      if (sim.walls.bodies[b].fed_or_spun()) row.push_back(audit.wall_work_by_body_J[b]);
  }
  if (!sim.heat_enabled()) return row;
  // Every particle's temperature, each rank's own merged over the ranks when split.
  TemperatureAccumulator temperatures;
  const std::span<const std::uint8_t> ghosts = sim.left_out();
  for (std::size_t i = 0; i < sim.particles.size(); ++i)
    if (ghosts.empty() || !ghosts[i]) temperatures.add(sim.particles.temperature_K[i], false);
  sim.merge_over_ranks(std::span<TemperatureAccumulator>(&temperatures, 1));
  const TemperatureStatistics t = temperatures.result();
  const double energy = sim.thermal_energy_J();
  const ThermalLedger& ledger = sim.thermal_ledger();
  const double imbalance = energy - ledger.expected_energy_J();
  row.insert(row.end(), {t.mean_K, t.min_K, t.max_K, energy,
                         ledger.boundary_heat_in_J, ledger.generated_heat_J,
                         energy != 0.0 ? imbalance / std::abs(energy) : 0.0});
  const std::vector<double> history = thermal_history_row(sim);
  row.insert(row.end(), history.begin(), history.end());
  for (std::size_t b = 0; b < sim.wall_thermal_state.size(); ++b) {
    const ThermalWall& wall = sim.model().wall_thermal[b];
    const ThermalWallState& w = sim.wall_thermal_state[b];
    if (!conducting_wall(wall)) continue;
    row.insert(row.end(), {w.temperature_K, w.heat_flow_to_particles_W, scale.real_rate(w.heat_flow_to_particles_W),
                           w.heat_to_particles_J});
    if (wall.mode != WallThermalMode::lumped || !wall.rod.exchanges()) continue;
    row.push_back(w.peak_temperature_K);
    row.insert(row.end(), w.segment_temperature_K.begin(), w.segment_temperature_K.end());
    if (wall.rod.emissivity > 0.0) row.push_back(w.radiated_heat_J);
    if (wall.rod.held_end_K) row.push_back(w.held_end_heat_in_J);
  }
  return row;
}

RunOutcome run_stages(Simulation& sim, StagePlan& plan, RunObserver& observer,
                      const std::atomic<bool>& stop_requested, const RunResume* resume) {
  RunOutcome outcome;
  outcome.threads = sim.threads();
  outcome.time_step_s = sim.time_step_s();
  // Wall time by the observer's clock (a test's may not depend on the machine's load).
  const auto seconds_since = [&observer](double start_s) { return observer.wall_clock_s() - start_s; };
  const double run_start = observer.wall_clock_s();
  double particle_steps = 0.0;
  Rng rng(plan.seed);
  observer.columns(time_series_columns(sim));
  MeasurementRunner measurements(plan.measurements);
  measurements.announce(sim, observer);
  const double dt = sim.time_step_s();
  SnapshotClock snapshots(plan.snapshots);
  // A resumed run: the RNG, insertions and snapshot clock now, the Simulation where its
  // stage stood (after the stage's overrides, which would otherwise reset its forces).
  RunPosition resumed;
  if (resume) {
    resumed = restore_run_state(resume->checkpoint, plan, rng, snapshots, measurements);
    particle_steps = resumed.particle_steps;
    outcome.stages_finished = resumed.stage;
  }
  const auto snapshot_depth_m = [&] {
    const int body = plan.snapshots.depth_body;
    return body >= 0 ? sim.walls.bodies[static_cast<std::size_t>(body)].depth_m() : 0.0;
  };
  auto take_snapshot = [&](double half_step_s) {
    observer.snapshot(sim);
    snapshots.taken(sim.time_s(), half_step_s, snapshot_depth_m());
  };

  auto finish = [&](bool completed, const std::string& message) {
    outcome.completed = completed;
    outcome.message = message;
    outcome.particles = sim.run_particle_count();
    outcome.steps = sim.step_count();
    outcome.simulated_time_s = sim.time_s();
    outcome.wall_s = seconds_since(run_start);
    outcome.particle_steps_per_s = outcome.wall_s > 0.0 ? particle_steps / outcome.wall_s : 0.0;
    outcome.bonds_configured = sim.bonds_configured();
    outcome.bonds = sim.bond_counts();
    return outcome;
  };

  if (resume && !resumed.inside_stage) sim.restore_state(resume->checkpoint);
  for (std::size_t s = resume ? resumed.stage : 0; s < plan.stages.size(); ++s) {
    const Stage& stage = plan.stages[s];
    // Resuming inside this stage: its start has happened; its loop goes on from `inside`.
    const RunPosition* inside = resume && resumed.inside_stage && s == resumed.stage ? &resumed : nullptr;
    StageInfo info;
    info.name = stage.name;
    info.index = s;
    info.count = plan.stages.size();
    info.start_time_s = inside ? inside->stage_start_time_s : sim.time_s();
    info.ends_when_settled = stage.until_settled;
    info.planned_end_time_s =
        inside ? inside->planned_end_time_s
               : info.start_time_s + (stage.ends_at_depth()                                    ? time_to_depth_s(sim, stage)
                                      : stage.until_settled || stage.ends_on_measurement() ? stage.max_duration_s
                                                                                           : stage.duration_s);
    observer.stage_started(info);
    const MaterialTable original_pairs = apply_overrides(sim, stage.overrides);
    if (inside) sim.restore_state(resume->checkpoint);

    std::vector<Insertion*> active;
    for (Insertion& ins : plan.insertions)
      if (ins.stage == s) {
        if (!inside) ins.start(sim.time_s());
        active.push_back(&ins);
      }

    std::optional<StaticHeatStepper> frozen;  // a static-bed stage: heat alone, its own step
    std::string failure;
    StageResult result = StageResult::finished;
    try {
      // Under MPI: bonds form, and a static bed's heat is stepped, on the whole run.
      if (stage.freezes_mechanics() || (stage.form_bonds && !inside)) sim.gather_everywhere();
      if (stage.form_bonds && !inside) {
        const BondFormation& f = *stage.form_bonds;
        const std::size_t formed = sim.form_bonds(f.gap_fraction, f.materials, f.regions);
        observer.notice(fmt::format("stage '{}': formed {} bonds ({} intact in all)", stage.name, formed,
                                    sim.bond_counts().intact));
      }
      if (stage.freezes_mechanics() && inside) {
        Stage same_step = stage;  // the heat step chosen at the stage's start
        same_step.thermal_time_step_s = inside->step_s;
        frozen.emplace(sim, same_step);
      } else if (stage.freezes_mechanics()) {
        frozen.emplace(sim, stage);
      } else {
        check_coupled_heat_step(sim);
      }
    } catch (const std::exception& e) {
      failure = fmt::format("stage '{}' cannot start: {}", stage.name, e.what());
      result = StageResult::failed;
    }
    const double step_s = frozen ? frozen->time_step_s() : dt;
    if (frozen && !inside && result == StageResult::finished &&
        !(stage.duration_s / step_s <= max_steps_per_stage)) {
      failure = fmt::format("stage '{}' would take {:.3g} thermal steps of {:.4g} s (the static bed's default step) "
                            "for its {:.4g} s; at most {:.0e} steps a stage can be run: shorten it, or give a larger "
                            "thermal_time_step",
                            stage.name, stage.duration_s / step_s, step_s, stage.duration_s, max_steps_per_stage);
      result = StageResult::failed;
    }
    const double stage_end_s =
        info.start_time_s + (stage.ends_on_measurement() ? stage.max_duration_s : stage.duration_s);
    const std::uint64_t check_every = frozen ? 1 : kCheckEverySteps;
    const bool ends_by_time = !stage.until_settled && !stage.ends_at_depth() && !stage.ends_on_measurement();
    const std::uint64_t planned_steps =
        inside                ? inside->planned_steps
        : stage.ends_at_depth() ? whole_steps(std::ceil(time_to_depth_s(sim, stage) / dt))
        : stage.until_settled || stage.ends_on_measurement() ? 0
        : frozen            ? whole_steps(std::ceil(stage.duration_s / step_s - 1e-9))
                            : static_cast<std::uint64_t>(std::llround(stage.duration_s / dt));
    const std::uint64_t min_steps = static_cast<std::uint64_t>(std::llround(stage.min_duration_s / dt));
    const double max_steps_d = stage.max_duration_s / dt;
    double sample_interval = plan.sample_interval_s;
    if (sample_interval <= 0.0)
      sample_interval = stage.until_settled          ? 0.01
                        : stage.ends_at_depth()       ? std::max(time_to_depth_s(sim, stage), dt) / 100.0
                        : stage.ends_on_measurement() ? stage.max_duration_s / 100.0
                                                      : stage.duration_s / 100.0;
    sample_interval = std::max(sample_interval, step_s);  // a zero-length stage still samples once
    if (inside) sample_interval = inside->sample_interval_s;
    double next_sample_s = inside ? inside->next_sample_s : sim.time_s();
    auto last_progress_clock = observer.wall_clock_s();
    std::uint64_t last_progress_step = 0;
    double steps_per_s = 0.0;
    std::uint64_t done = inside ? inside->done : 0;  // steps of this stage (thermal steps in a static-bed stage)
    last_progress_step = done;
    double last_sampled_time_s = inside ? inside->last_sampled_time_s : std::numeric_limits<double>::quiet_NaN();

    const auto stage_clock = observer.wall_clock_s();
    bool checkpoint_wanted = false;  // under MPI, at the next gather
    RecentRate recent_rate;  // a resumed stage times only its own steps
    recent_rate.add(0.0, done);
    // A checkpoint at the top of an iteration: resuming replays that iteration's
    // insertions, sample and snapshot checks, which are no longer due.
    auto checkpoint_here = [&](CheckpointReason reason) {
      RunPosition at;
      at.stage = s;
      at.inside_stage = true;
      at.stage_start_time_s = info.start_time_s;
      at.planned_end_time_s = info.planned_end_time_s;
      at.done = done;
      at.planned_steps = planned_steps;
      at.step_s = step_s;
      at.sample_interval_s = sample_interval;
      at.next_sample_s = next_sample_s;
      at.last_sampled_time_s = last_sampled_time_s;
      at.particle_steps = particle_steps;
      observer.checkpoint(RunState{sim, plan, at, rng, snapshots, reason, &measurements});
    };

    // The run's fastest impact is said once, when it first goes unresolved. Under MPI a
    // rank's impacts reach the others (and rank 0, which writes) at the next sample or
    // gather, so the check runs after each of those as well as after each step.
    bool impact_noticed = !impacts_resolved(sim);
    const auto notice_unresolved_impact = [&] {
      if (impact_noticed || impacts_resolved(sim)) return;
      observer.notice(unresolved_impact_notice(sim, stage.name));
      impact_noticed = true;
    };

    auto sample = [&] {
      // Under MPI the sample and its measurements are sums over each rank's own
      // particles, merged (exactly) over the ranks: nothing is gathered.
      sim.merge_fastest_impact_over_ranks();
      notice_unresolved_impact();
      observer.sample(time_series_row(sim, s));
      measurements.with_time_series(sim, observer);
      last_sampled_time_s = sim.time_s();
      while (next_sample_s <= sim.time_s() + 0.5 * step_s) next_sample_s += sample_interval;
    };
    if (result == StageResult::finished) try {
      for (;;) {
        // Under MPI: the clock's decisions taken by all ranks at once, and the particles
        // gathered on every rank when anything this iteration reads or adds them (a
        // static-bed stage stays gathered).
        std::uint32_t decided = 0;
        if (done % check_every == 0) {
          if (stop_requested.load(std::memory_order_relaxed)) decided |= stop_now;
          if (observer.checkpoint_due()) decided |= checkpoint_now;
          if (seconds_since(last_progress_clock) >= observer.progress_interval_s()) decided |= progress_now;
          decided = sim.bits_over_ranks(decided);
        }
        if (sim.distributed()) {
          // Not the samples, measurements and measured ends: their sums are merged over
          // the ranks. But every kSamplesPerGather-th sample of a stage gathers (a point of
          // the schedule, the same on any rank count and after a resume), so that a
          // periodic checkpoint, which waits for a gather, comes within that many samples.
          const bool sample_due = sim.time_s() + 0.5 * step_s >= next_sample_s;
          const auto sample_index =
              static_cast<std::int64_t>(std::llround((next_sample_s - info.start_time_s) / sample_interval));
          bool reads_particles = frozen.has_value() || (decided & stop_now) != 0 ||
                                 snapshots.due(sim.time_s(), 0.5 * step_s, snapshot_depth_m()) ||
                                 (sample_due && sample_index % kSamplesPerGather == 0);
          for (const Insertion* ins : active)
            reads_particles = reads_particles || (!ins->finished && sim.time_s() + 0.5 * dt >= ins->next_attempt_s());
          if (reads_particles) {
            sim.gather_everywhere();
            notice_unresolved_impact();
          }
          // Bonds broken on any rank since the split, now every rank's (in one order).
          if (!sim.distributed() && sim.bond_breaks_pending()) observer.bonds_broken(sim.take_bond_breaks());
        }
        bool insertions_done = true;
        for (Insertion* ins : active) {
          if (!ins->finished && sim.time_s() + 0.5 * dt >= ins->next_attempt_s()) {
            const InsertionReport r = insert_due_particles(sim, *ins, rng);
            if (r.placed < r.requested)
              observer.notice(fmt::format("insertion '{}': placed {} of {} particles at t = {:.4g} s; the region is full{}",
                                          ins->name, r.placed, r.requested, sim.time_s(),
                                          ins->finished ? fmt::format(" ({} of {} in all)", ins->inserted, ins->target_count) : ", will retry"));
            if (ins->finished && ins->inserted < ins->target_count && !ins->allow_partial && failure.empty())
              failure = fmt::format(
                  "insertion '{}' placed {} of the {} particles it asks for: its region is full. Ask for fewer "
                  "(count, solid_fraction or mass), give it a larger region, or set `allow_partial: true` to go on "
                  "with what fits",
                  ins->name, ins->inserted, ins->target_count);
          }
          insertions_done = insertions_done && ins->finished;
        }
        if (!failure.empty()) {
          result = StageResult::failed;
          break;
        }
        if (sim.time_s() + 0.5 * step_s >= next_sample_s) {
          sample();
          if (!frozen) check_coupled_heat_step(sim);  // the contacts have changed since the last check
        }
        if (snapshots.due(sim.time_s(), 0.5 * step_s, snapshot_depth_m())) take_snapshot(0.5 * step_s);
        if (!measurements.empty()) measurements.before_step(sim, 0.5 * step_s, observer);
        // Under MPI a periodic checkpoint waits for the next gather the run makes anyway
        // (every kSamplesPerGather-th sample at the latest): a gather of its own would
        // rebuild the lists and change the run's later sums in the last bit.
        if (checkpoint_wanted && !sim.distributed()) {
          checkpoint_here(CheckpointReason::periodic);
          checkpoint_wanted = false;
        }

        if (ends_by_time && done >= planned_steps) break;
        if (stage.ends_at_depth() && reached_depth(sim, stage)) break;
        if (stage.ends_on_measurement() && done % check_every == 0 &&
            target_reached(plan.measurements, *stage.until_measured, sim))
          break;
        if (done % check_every == 0) {
          if (stage.ends_on_measurement() && !frozen && static_cast<double>(done) >= max_steps_d) {
            failure = measurement_not_reached(sim, plan, stage);
            result = StageResult::failed;
            break;
          }
          if (stage.until_settled && insertions_done && done >= min_steps &&
              kinetic_energy_per_particle(sim) < stage.settled_kinetic_energy_J)
            break;
          if (stage.until_settled && static_cast<double>(done) >= max_steps_d) {
            failure = fmt::format(
                "stage '{}' did not settle within its max_duration of {:.4g} s: kinetic energy per particle is "
                "{:.3g} J, the threshold {:.3g} J. Raise max_duration or the threshold.",
                stage.name, stage.max_duration_s, kinetic_energy_per_particle(sim), stage.settled_kinetic_energy_J);
            result = StageResult::failed;
            break;
          }
          if (stage.ends_at_depth() && feed_ended(sim, stage)) {
            const WallBody& wall = sim.walls.bodies[static_cast<std::size_t>(stage.depth_body)];
            failure = fmt::format(
                "stage '{}' cannot end: wall '{}' stopped feeding at a depth of {:.6g} m, short of {:.6g} m (its "
                "motion's 'stop' time or 'stop_at_depth' comes first)",
                stage.name, wall.name, wall.depth_m(), stage.depth_m);
            result = StageResult::failed;
            break;
          }
          if (decided & stop_now) {
            checkpoint_here(CheckpointReason::interrupted);
            result = StageResult::interrupted;
            failure = fmt::format("interrupted during stage '{}' at t = {:.6g} s", stage.name, sim.time_s());
            break;
          }
          if (decided & checkpoint_now) {
            if (sim.distributed())
              checkpoint_wanted = true;
            else
              checkpoint_here(CheckpointReason::periodic);
          }
          const double since = seconds_since(last_progress_clock);
          if (decided & progress_now) {
            steps_per_s = static_cast<double>(done - last_progress_step) / since;
            // The time left uses the rate of the last minute: steadier than the last
            // interval's, and it follows a machine that gets loaded (or freed) mid-stage.
            recent_rate.add(seconds_since(stage_clock), done);
            const double stage_rate = recent_rate.steps_per_s();
            last_progress_clock = observer.wall_clock_s();
            last_progress_step = done;
            ProgressSnapshot snap;
            snap.stage = info;
            snap.time_s = sim.time_s();
            snap.step = sim.step_count();
            snap.particles = sim.run_particle_count();
            snap.wall_s = seconds_since(run_start);
            snap.steps_per_s = steps_per_s;
            snap.particle_steps_per_s = steps_per_s * static_cast<double>(snap.particles);
            const double steps_left = stage.ends_at_depth() ? time_to_depth_s(sim, stage) / dt
                                                            : static_cast<double>(planned_steps) - static_cast<double>(done);
            snap.estimated_remaining_s =
                stage.until_settled || stage.ends_on_measurement() || stage_rate <= 0.0 || std::isinf(steps_left) ? -1.0 : steps_left / stage_rate;
            snap.kinetic_energy_per_particle_J = kinetic_energy_per_particle(sim);
            observer.progress(snap);
          }
        }
        if (frozen) {
          const double remaining_s = stage_end_s - sim.time_s();
          if (remaining_s <= 0.0) {
            if (stage.ends_on_measurement()) {
              failure = measurement_not_reached(sim, plan, stage);
              result = StageResult::failed;
            }
            break;
          }
          observer.before_step(sim);
          frozen->advance(std::min(step_s, remaining_s));
        } else {
          observer.before_step(sim);
          sim.distribute_again();
          sim.step();
          if (!sim.distributed() && sim.bond_breaks_pending()) observer.bonds_broken(sim.take_bond_breaks());
          notice_unresolved_impact();
        }
        ++done;
        snapshots.count_step();
        measurements.count_step();
        particle_steps += static_cast<double>(sim.run_particle_count());
      }
    } catch (const SimulationError& e) {
      result = StageResult::failed;
      failure = fmt::format("stage '{}' failed: {}", stage.name, e.what());
    }
    sim.gather_everywhere();  // the stage's end reads the particles (under MPI)
    notice_unresolved_impact();
    if (sim.bond_breaks_pending()) observer.bonds_broken(sim.take_bond_breaks());
    if (result == StageResult::finished) {
      if (last_sampled_time_s != sim.time_s()) sample();
      for (Insertion* ins : active) {
        if (ins->inserted >= ins->target_count || !ins->from_file.empty()) continue;
        if (ins->allow_partial) {
          observer.notice(fmt::format("insertion '{}' placed {} of {} particles during stage '{}'", ins->name,
                                      ins->inserted, ins->target_count, stage.name));
        } else if (failure.empty()) {
          result = StageResult::failed;
          failure = fmt::format(
              "stage '{}' ended with insertion '{}' at {} of its {} particles{}: lengthen the stage{}, or set "
              "`allow_partial: true` to go on with what was placed",
              stage.name, ins->name, ins->inserted, ins->target_count,
              ins->rate_per_s > 0.0 ? fmt::format(" (at {:.4g} /s they take {:.4g} s)", ins->rate_per_s,
                                                  static_cast<double>(ins->target_count) / ins->rate_per_s)
                                    : "",
              ins->rate_per_s > 0.0 ? " or raise the rate" : "");
        }
      }
    }
    // The state a stage ends in, also a failed or interrupted one (it shows what went wrong).
    if (snapshots.due_at_stage_end(sim.time_s())) take_snapshot(0.0);
    measurements.at_stage_end(sim, observer);
    sim.set_materials(original_pairs);
    info.end_time_s = sim.time_s();
    observer.stage_finished(info, result, failure);
    if (result != StageResult::finished) {
      outcome.interrupted = result == StageResult::interrupted;
      return finish(false, failure);
    }
    ++outcome.stages_finished;
    RunPosition next;  // between stages: the next one starts afresh
    next.stage = s + 1;
    next.particle_steps = particle_steps;
    observer.checkpoint(RunState{sim, plan, next, rng, snapshots, CheckpointReason::stage_end, &measurements});
  }
  return finish(true, "");
}

}  // namespace regodem
