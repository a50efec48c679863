#pragma once
// Where a run of stages stands, for checkpoints (docs/checkpoint-format.md): the
// stage, what its loop keeps (steps done, the next sample, the end it planned at its
// start), the insertion RNG, the insertions' progress and the snapshot clock. With the
// Simulation's own sections this is all a resumed run needs to go on bit for bit.
#include <cstddef>
#include <cstdint>

#include "core/rng.hpp"
#include "sim/snapshot_schedule.hpp"
#include "sim/stage_plan.hpp"

namespace regodem {

class Checkpoint;
class MeasurementRunner;
class Simulation;

struct RunPosition {
  std::size_t stage = 0;      // the stage running (inside_stage) or the next one to start
  bool inside_stage = false;  // false: between stages; stage == count: the run is complete
  // The stage loop's state (inside_stage only).
  double stage_start_time_s = 0.0;
  double planned_end_time_s = 0.0;
  std::uint64_t done = 0;           // steps of the stage so far
  std::uint64_t planned_steps = 0;  // fixed at the stage's start
  double step_s = 0.0;              // a static-bed stage's heat step, fixed at its start
  double sample_interval_s = 0.0;
  double next_sample_s = 0.0;
  double last_sampled_time_s = 0.0;  // NaN: none yet in this stage
  double particle_steps = 0.0;       // of the whole run, for its speed
};

enum class CheckpointReason { periodic, stage_end, interrupted };

/// A run's state at a step boundary, handed to RunObserver::checkpoint().
struct RunState {
  const Simulation& sim;
  const StagePlan& plan;
  const RunPosition& position;
  const Rng& rng;
  const SnapshotClock& snapshots;
  CheckpointReason reason;
  const MeasurementRunner* measurements = nullptr;  // their clocks (none: no measurements)
};

/// Adds the Simulation's sections and the run's ("RUNP").
void save_run_state(Checkpoint& checkpoint, const RunState& state);

/// What run_stages needs to continue a checkpointed run.
struct RunResume {
  const Checkpoint& checkpoint;
};

/// Whether the checkpoint was taken after the run's last stage (nothing left to run).
bool run_completed(const Checkpoint& checkpoint);

/// Reads the run's section: the position, and restores the insertions' progress, the
/// RNG, the snapshot clock and the measurements' clocks. Throws CheckpointError when it
/// does not fit the plan.
RunPosition restore_run_state(const Checkpoint& checkpoint, StagePlan& plan, Rng& rng, SnapshotClock& snapshots,
                              MeasurementRunner& measurements);

}  // namespace regodem
