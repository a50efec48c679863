// Plans no machine can meet are refused before they start, with their numbers: a
// modulus or density that makes the step 1e-150 s (these passed validate, and `run`
// never ended), a depth stage whose wall feeds too slowly, an insertion larger than any
// memory, a count that would overflow its conversion. The shipped-size plans pass.
#include <string>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "scenario/plan_limits.hpp"
#include "scenario/scenario_builder.hpp"
#include "scenario/scenario_reader.hpp"

namespace regodem {
namespace {

// 0.25 mm grains of 1e6 Pa: the Rayleigh time ~2e-5 s, a step ~4e-6 s.
const std::string kScenario = R"(
name: plan-limits
domain: {min: [-10 mm, -10 mm, -10 mm], max: [10 mm, 10 mm, 10 mm]}
materials:
  grain: {density: 2500 kg/m^3, shear_modulus: 1e6 Pa, poisson_ratio: 0.25}
interactions:
  - {materials: [grain, grain], restitution: 0.3, sliding_friction: 0.5}
walls:
  - name: piston
    type: disk
    center: [0, 0, 9 mm]
    normal: [0, 0, 1]
    radius: 4 mm
    motion: {velocity: [0, 0, -0.1 m/s]}
insertions:
  - {name: fill, material: grain, region: {type: box, min: [-5 mm, -5 mm, -10 mm], max: [5 mm, 5 mm, -5 mm]},
     diameter: 0.5 mm, count: 100, stage: fill}
stages:
  - {name: fill, duration: 1 s}
  - {name: press, until: {wall: piston, depth: 1 mm}}
)";

std::string refusal(const std::vector<std::string>& overrides) {
  try {
    PreparedRun::build(read_scenario_string(kScenario, "plan.yaml", overrides), 1);
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(PlanLimits, ThePlainPlanIsAccepted) { EXPECT_EQ(refusal({}), ""); }

TEST(PlanLimits, AModulusThatMakesTheStepAbsurdIsRefusedNamingTheMaterial) {
  const std::string message = refusal({"materials.grain.shear_modulus=1e300 Pa"});
  EXPECT_TRUE(contains(message, "stage 'fill' would take")) << message;
  EXPECT_TRUE(contains(message, "material 'grain': shear modulus 1e+300 Pa")) << message;
  EXPECT_TRUE(contains(message, "at most 1e+12 steps")) << message;
}

TEST(PlanLimits, ADensityThatMakesTheStepAbsurdIsRefused) {
  const std::string message = refusal({"materials.grain.density=1e-300 kg/m^3"});
  EXPECT_TRUE(contains(message, "density 1e-300 kg/m^3")) << message;
}

// 1 s at ~4e-6 s is ~2.5e5 steps; a 1e8 s stage is ~2.5e13, past the limit.
TEST(PlanLimits, AStageTooLongForTheStepIsRefused) {
  EXPECT_TRUE(contains(refusal({"stages.fill.duration=1e8 s"}), "stage 'fill' would take")) << refusal({"stages.fill.duration=1e8 s"});
  EXPECT_EQ(refusal({"stages.fill.duration=1e5 s"}), "");  // ~2.5e10 steps: long, but it can be run
}

// 1 mm at 1e-12 m/s takes 1e9 s: ~2.5e14 steps.
TEST(PlanLimits, ADepthStageWhoseWallCrawlsIsRefusedNamingTheWall) {
  const std::string message = refusal({"walls.piston.motion.velocity=[0, 0, -1e-12 m/s]"});
  EXPECT_TRUE(contains(message, "stage 'press' would take")) << message;
  EXPECT_TRUE(contains(message, "the time wall 'piston' takes to feed 0.001 m")) << message;
}

// 1e14 particles need 2e16 B at the least; no machine has 20 PB of memory.
TEST(PlanLimits, MoreParticlesThanAnyMemoryAreRefused) {
  const std::string message = refusal({"insertions.fill.count=100000000000000"});
  EXPECT_TRUE(contains(message, "the run would hold 1e+14 particles")) << message;
  EXPECT_TRUE(contains(message, "GB of memory")) << message;
}

TEST(PlanLimits, TheMemoryCheckComparesWithThisMachine) {
  ASSERT_GT(physical_memory_bytes(), 0.0);
  const double fits = 0.5 * physical_memory_bytes() / min_bytes_per_particle;
  EXPECT_NO_THROW(check_particle_memory(fits, SourceLocation{}));
  EXPECT_THROW(check_particle_memory(4.0 * fits, SourceLocation{}), InputError);
}

}  // namespace
}  // namespace regodem
