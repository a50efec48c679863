#pragma once
// What a whole run will cost on this machine, without running it (`regodem estimate`,
// docs/estimate.md), as the paper's "estimated time provided by the discrete element
// software": per stage, its particles, its step and number of steps (known from the
// plan), and a sample of a few hundred steps timed on the stage's bed, built
// geometrically where the run would only have it after a pour.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "parallel/rank_cost_model.hpp"
#include "sim/stage_plan.hpp"

namespace regodem {

class Simulation;

struct EstimateOptions {
  double solid_fraction = 0.6;       // of the geometric beds standing in for poured ones
  double overlap_fraction = 1e-5;    // their lattice contacts' overlap, of a diameter
  std::uint64_t sample_steps = 300;  // timed per stage (mechanical, or heat steps of a static bed)
  std::uint64_t warmup_steps = 20;   // before the clock starts (the first builds the neighbour lists)
  double sample_seconds = 5.0;       // the timed steps of one stage stop after this much wall time
  // A stage that ends on settling or on a measurement with no max_duration has no
  // bound: it is counted as max(min_duration, this), and marked assumed.
  double unbounded_duration_s = 0.1;
  // Rank counts to project the run onto (`--ranks`), over this network; each rank with
  // the threads of the sample.
  std::vector<int> ranks;
  NetworkModel network;
};

/// A stage on N ranks (src/parallel/rank_cost_model.hpp).
struct StageOverRanks {
  RankStepCost step;              // one mechanical step, on the slowest rank
  std::uint64_t gathers = 0;      // at most: snapshots, insertion attempts, bond forming, the end
  double gather_s = 0.0;          // each
  double merge_s = 0.0;           // the samples', measurements' and measured ends' merged sums, in all
  double predicted_wall_s = 0.0;  // steps x step + gathers x gather + merges (+ the static bed's setup)
};

/// How sure a stage's number of steps is.
enum class StepCount {
  exact,        // duration / step, or the distance to a depth / the feed speed
  upper_bound,  // until settled or a measurement: its max_duration
  assumed,      // until settled or a measurement without max_duration (see unbounded_duration_s)
};
const char* step_count_name(StepCount basis);

struct StageCost {
  std::string name;
  std::string end;          // "time", "settled", "depth", "measurement"
  bool static_bed = false;  // heat alone on a frozen bed, with its own step
  std::size_t particles = 0;      // initial state and every insertion of this stage and earlier
  double step_s = 0.0;            // mechanical step; a static bed's heat step (0 until sampled if not given)
  double simulated_s = 0.0;       // simulated time the stage covers (a bound or an assumption, see basis)
  std::uint64_t steps = 0;
  StepCount basis = StepCount::exact;
  std::string note;               // why the count is a bound or an assumption, or what went wrong

  // From the sample.
  bool sampled = false;
  std::size_t sample_particles = 0;  // fewer than `particles` where a region was full
  std::uint64_t sample_steps = 0;
  double sample_wall_s = 0.0;
  double particle_steps_per_s = 0.0;
  double setup_wall_s = 0.0;         // once per stage: a static bed's conduction network and solver
  double resident_bytes = 0.0;       // resident set once the stage's sample state is built
  double predicted_wall_s = 0.0;     // setup + steps x particles / rate
  double builds_per_step = 0.0;      // neighbour-list builds in the timed steps, per step
  std::vector<StageOverRanks> over_ranks;  // one per EstimateOptions::ranks, when sampled
};

struct RunEstimate {
  std::vector<StageCost> stages;
  std::uint64_t steps = 0;
  double predicted_wall_s = 0.0;
  double peak_resident_bytes = 0.0;
  bool upper_bound = false;  // some stage counted its max_duration
  bool assumed = false;      // some stage had no bound at all
  bool complete = true;      // every stage was sampled
  // Per EstimateOptions::ranks: the whole run's predicted wall time, and of it the gathers'.
  std::vector<double> over_ranks_wall_s, over_ranks_gather_s;
};

/// What the plan says without running: particles, step and steps of each stage. A
/// static-bed stage whose heat step is a fraction of the bed's stability limit gets its
/// step and steps from the sample.
std::vector<StageCost> plan_stage_costs(const Simulation& sim, const StagePlan& plan, const EstimateOptions& options);

/// Builds each stage's bed on `sim` (freshly built from the scenario, not yet run) and
/// times its sample; `progress` hears one line per step of the work. A sample that
/// fails (a blow-up) ends the sampling: that stage and the later ones keep no rate.
RunEstimate estimate_run(Simulation& sim, const StagePlan& plan, const EstimateOptions& options,
                         const std::function<void(const std::string&)>& progress = {});

/// Resident set size of this process (/proc/self/statm), in bytes; 0 where unreadable.
double resident_set_bytes();

}  // namespace regodem
