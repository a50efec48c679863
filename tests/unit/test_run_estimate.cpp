// `regodem estimate`'s arithmetic (sim/run_estimate.hpp): particles and steps of each
// stage on a scenario whose answers are worked out by hand below, and an estimate of
// a small dense scenario against a real run of it (steps and particles; the rates are
// wall-clock figures and only checked to be sane, never compared: they vary with load).
#include <atomic>
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "scenario/scenario_builder.hpp"
#include "scenario/scenario_reader.hpp"
#include "sim/run_estimate.hpp"
#include "sim/simulation.hpp"

namespace regodem {
namespace {

// Both scenarios' grains: soft, conducting, heat on.
constexpr const char* kGrains = R"(
materials:
  grain: {density: 2500 kg/m^3, shear_modulus: 1e6 Pa, poisson_ratio: 0.25,
          conductivity: 1 W/(m K), specific_heat: 800 J/(kg K)}
interactions:
  - {materials: [grain, grain], restitution: 0.3, sliding_friction: 0.5}
heat: {}
)";

// time_step 1e-6 s. Insertions: `first` 100 by count in stage fill; `second` by solid
// fraction 0.3 of a 10 x 10 x 5 mm box of 1 mm grains: 0.3 x 5e-7 / 5.236e-10 = 286.48
// -> 286, in stage settle; `third` by mass 1e-4 kg of 1 mm and 0.5 mm grains, half
// each by number, 2500 kg/m^3: mean mass 2500 x (5.236e-10 + 6.545e-11) / 2 =
// 7.363e-7 kg -> 135.8 -> 136, in stage press.
// Stages: fill 1 ms = 1000 steps; settle at most 2 ms = 2000 steps (upper bound);
// press until the piston (depth -1 mm at t = 0, feeding 0.1 m/s from t = 0) is 1 mm deep:
// at the stage's start (t = 3 ms, counting settle's bound) it is at -0.7 mm, so 1.7 mm
// to go = 17 ms = 17000 steps; heat, a static bed, 1 s at a heat step of 0.01 s = 100
// heat steps; rest, until settled with no max_duration: assumed 0.1 s = 100000 steps.
const std::string kScenario = R"(
name: estimate-counts
gravity: [0, 0, -9.81 m/s^2]
domain: {min: [-10 mm, -10 mm, -10 mm], max: [10 mm, 10 mm, 10 mm]}
time_step: 1e-6 s
)" + std::string(kGrains) + R"(
walls:
  - {name: floor, type: plane, point: [0, 0, -10 mm], normal: [0, 0, 1]}
  - name: piston
    type: disk
    center: [0, 0, 9 mm]
    normal: [0, 0, 1]
    radius: 4 mm
    motion: {velocity: [0, 0, -0.1 m/s], depth_at_start: -1 mm}
insertions:
  - {name: first, material: grain, region: {type: box, min: [-5 mm, -5 mm, -10 mm], max: [5 mm, 5 mm, -5 mm]},
     diameter: 1 mm, count: 100, temperature: 300 K, stage: fill}
  - {name: second, material: grain, region: {type: box, min: [-5 mm, -5 mm, -5 mm], max: [5 mm, 5 mm, 0 mm]},
     diameter: 1 mm, solid_fraction: 0.3, temperature: 300 K, stage: settle}
  - name: third
    material: grain
    region: {type: box, min: [-5 mm, -5 mm, 0 mm], max: [5 mm, 5 mm, 5 mm]}
    sizes: [{diameter: 1 mm, fraction: 0.5}, {diameter: 0.5 mm, fraction: 0.5}]
    mass: 1e-4 kg
    temperature: 300 K
    stage: press
stages:
  - {name: fill, duration: 1 ms}
  - {name: settle, until: settled, kinetic_energy_per_particle: 1e-12 J, max_duration: 2 ms}
  - {name: press, until: {wall: piston, depth: 1 mm}}
  - {name: heat, duration: 1 s, heat_stepping: static_explicit, thermal_time_step: 0.01 s}
  - {name: rest, until: settled, kinetic_energy_per_particle: 1e-12 J, min_duration: 0.5 ms}
)";

TEST(RunEstimate, StageParticlesAndStepsFromThePlan) {
  const PreparedRun run = PreparedRun::build(read_scenario_string(kScenario, "estimate-counts.yaml"), 1);
  const std::vector<StageCost> costs = plan_stage_costs(run.simulation(), run.plan(), EstimateOptions{});
  ASSERT_EQ(costs.size(), 5u);

  EXPECT_EQ(costs[0].particles, 100u);
  EXPECT_EQ(costs[1].particles, 386u);
  EXPECT_EQ(costs[2].particles, 522u);
  EXPECT_EQ(costs[3].particles, 522u);
  EXPECT_EQ(costs[4].particles, 522u);

  EXPECT_EQ(costs[0].end, "time");
  EXPECT_EQ(costs[0].steps, 1000u);
  EXPECT_EQ(costs[0].basis, StepCount::exact);
  EXPECT_DOUBLE_EQ(costs[0].step_s, 1e-6);

  EXPECT_EQ(costs[1].end, "settled");
  EXPECT_EQ(costs[1].steps, 2000u);
  EXPECT_EQ(costs[1].basis, StepCount::upper_bound);

  EXPECT_EQ(costs[2].end, "depth");
  EXPECT_EQ(costs[2].basis, StepCount::exact);
  EXPECT_NEAR(costs[2].simulated_s, 0.017, 1e-12);
  EXPECT_EQ(costs[2].steps, 17000u);

  EXPECT_TRUE(costs[3].static_bed);
  EXPECT_DOUBLE_EQ(costs[3].step_s, 0.01);
  EXPECT_EQ(costs[3].steps, 100u);
  EXPECT_EQ(costs[3].basis, StepCount::exact);

  EXPECT_EQ(costs[4].basis, StepCount::assumed);
  EXPECT_EQ(costs[4].steps, 100000u);
  EXPECT_NE(costs[4].note.find("cannot be bounded"), std::string::npos);
}

// A bed of 200 grains placed by the estimate as the run places it (all at once,
// at rest), 30 ms at 1e-5 s = 3000 steps, then 2 s of heat at 0.05 s = 40 heat steps on
// the frozen bed.
const std::string kDenseScenario = R"(
name: estimate-dense
gravity: [0, 0, -9.81 m/s^2]
domain: {min: [-5 mm, -5 mm, -1 mm], max: [5 mm, 5 mm, 12 mm]}
time_step: 1e-5 s
)" + std::string(kGrains) + R"(
walls:
  - {name: box, type: cylinder, base: [0, 0, 0], radius: 4.5 mm, length: 10 mm}
  - {name: heater, type: plane, point: [0, 0, 0], normal: [0, 0, 1], thermal: {mode: fixed, temperature: 400 K}}
insertions:
  - {name: grains, material: grain, region: {type: cylinder, base: [0, 0, 0], radius: 4.4 mm, length: 10 mm},
     diameter: 1 mm, count: 200, temperature: 300 K, stage: shake}
stages:
  - {name: shake, duration: 30 ms}
  - {name: heat, duration: 2 s, heat_stepping: static_explicit, thermal_time_step: 0.05 s}
)";

class Quiet : public RunObserver {};

TEST(RunEstimate, AgreesWithARealRunOnStepsAndParticlesAndTimesASample) {
  ScenarioSpec spec = read_scenario_string(kDenseScenario, "estimate-dense.yaml");
  PreparedRun sampled = PreparedRun::build(spec, 1);
  EstimateOptions options;
  options.sample_steps = 60;
  options.sample_seconds = 2.0;
  const RunEstimate estimate = estimate_run(sampled.simulation(), sampled.plan(), options);
  ASSERT_EQ(estimate.stages.size(), 2u);
  EXPECT_TRUE(estimate.complete);
  EXPECT_FALSE(estimate.upper_bound);

  PreparedRun real = PreparedRun::build(spec, 1);
  Quiet quiet;
  std::atomic<bool> stop{false};
  const RunOutcome outcome = real.run(quiet, stop);
  ASSERT_TRUE(outcome.completed) << outcome.message;
  // Mechanical steps are the run's step count (static-bed heat steps are not counted there).
  EXPECT_EQ(estimate.stages[0].steps, outcome.steps);
  EXPECT_EQ(estimate.stages[0].particles, outcome.particles);
  EXPECT_EQ(estimate.stages[1].steps, 40u);
  EXPECT_EQ(estimate.steps, outcome.steps + 40u);

  for (const StageCost& c : estimate.stages) {
    EXPECT_TRUE(c.sampled) << c.name << ": " << c.note;
    EXPECT_EQ(c.sample_particles, 200u) << c.name;  // the region holds them at 0.6
    EXPECT_GT(c.sample_steps, 0u);
    EXPECT_TRUE(std::isfinite(c.particle_steps_per_s) && c.particle_steps_per_s > 0.0) << c.name;
    EXPECT_TRUE(std::isfinite(c.predicted_wall_s) && c.predicted_wall_s > 0.0) << c.name;
    EXPECT_GT(c.resident_bytes, 0.0);
  }
  // The geometric bed does not blow apart: after the sample it is still in contact.
  EXPECT_GT(sampled.simulation().contact_statistics().particle_contacts, 200u);
  EXPECT_LT(sampled.simulation().max_overlap_fraction(), 0.01);
  EXPECT_NEAR(estimate.predicted_wall_s, estimate.stages[0].predicted_wall_s + estimate.stages[1].predicted_wall_s,
              1e-12);
}

}  // namespace
}  // namespace regodem
