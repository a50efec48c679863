#pragma once
// Turns a validated ScenarioSpec into a ready-to-run simulation and stage plan, and
// runs it. Checks that need the built model (time step against the stable one,
// materials of walls and insertions) throw InputError before anything runs.
#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "scenario/scenario_spec.hpp"
#include "sim/run_observer.hpp"

namespace regodem {

class Checkpoint;
class Simulation;
struct StagePlan;

class PreparedRun {
 public:
  /// Builds the simulation; throws InputError on a scenario that cannot run.
  static PreparedRun build(const ScenarioSpec& spec, int threads);

  PreparedRun(PreparedRun&&) noexcept;
  PreparedRun& operator=(PreparedRun&&) noexcept;
  ~PreparedRun();

  /// Runs every stage, reporting to the observer; returns when all stages finished,
  /// one failed (blow-up, not settled in time) or stop_requested became true.
  RunOutcome run(RunObserver& observer, const std::atomic<bool>& stop_requested);
  /// Continues a checkpointed run of this scenario from its checkpoint (`regodem resume`).
  RunOutcome resume(const Checkpoint& checkpoint, RunObserver& observer, const std::atomic<bool>& stop_requested);

  /// Human-readable lines describing the plan: time step and Rayleigh time, walls,
  /// insertions, stages. `regodem validate` prints these.
  std::vector<std::string> describe() const;
  /// What may make the results depend on the step without making the run fail (a wall
  /// that strikes grains faster than the step resolves); also among describe()'s lines,
  /// after "warning: ". `regodem run` prints them.
  const std::vector<std::string>& warnings() const;

  const Simulation& simulation() const;
  /// Stages and insertions as the engine will run them.
  const StagePlan& plan() const;
  /// The built state, to work on without running the plan (`regodem estimate` samples it).
  Simulation& simulation();
  StagePlan& plan();
  double time_step_s() const;
  int threads() const;

 private:
  PreparedRun();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace regodem
