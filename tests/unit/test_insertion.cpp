// Insertion: whole, non-overlapping particles inside the region; a full region places
// what fits and says so; counts from a solid fraction; size classes by number or mass.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "scenario/scenario_builder.hpp"
#include "sim/insertion.hpp"
#include "sim/simulation.hpp"

namespace regodem {
namespace {

Simulation empty_box(double half) {
  MaterialTable materials;
  materials.add({"grain", 2500.0, 1e8, 0.25});
  materials.set_pair(0, 0, PairProperties{});
  SimulationSettings s;
  s.domain = {{-half, -half, -half}, {half, half, half}};
  s.gravity_m_per_s2 = {};
  s.time_step_s = 1e-6;
  s.neighbor_skin_m = 1e-5;
  s.min_particle_radius_m = 1e-4;
  return Simulation(materials, WallSet{}, s);
}

Insertion box_insertion(double half, double radius, std::size_t count) {
  Insertion ins;
  ins.name = "box";
  ins.region.shape = InsertionShape::box;
  ins.region.min_m = {-half, -half, -half};
  ins.region.max_m = {half, half, half};
  ins.sizes = {{radius, 1.0}};
  ins.density_kg_per_m3 = 2500.0;
  ins.target_count = count;
  ins.start(0.0);
  return ins;
}

TEST(Insertion, PlacesWholeNonOverlappingParticles) {
  Simulation sim = empty_box(0.01);
  Insertion ins = box_insertion(0.005, 0.5e-3, 200);
  Rng rng(1);
  const InsertionReport report = insert_due_particles(sim, ins, rng);
  EXPECT_EQ(report.placed, 200u);
  const auto& p = sim.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_GE(p.position_m[i][axis] - p.radius_m[i], -0.005);
      EXPECT_LE(p.position_m[i][axis] + p.radius_m[i], 0.005);
    }
    for (std::size_t j = i + 1; j < p.size(); ++j)
      EXPECT_GE(norm(p.position_m[i] - p.position_m[j]), p.radius_m[i] + p.radius_m[j]);
  }
}

TEST(Insertion, FullRegionPlacesWhatFitsAndReportsIt) {
  Simulation sim = empty_box(0.01);
  // 2000 spheres of 1 mm diameter in a 4 mm cube would be a solid fraction of 16.
  Insertion ins = box_insertion(0.002, 0.5e-3, 2000);
  Rng rng(2);
  const InsertionReport report = insert_due_particles(sim, ins, rng);
  EXPECT_EQ(report.requested, 2000u);
  EXPECT_GT(report.placed, 10u);
  EXPECT_LT(report.placed, 70u);  // random sequential packing stops below phi = 0.38 (~58 here)
  EXPECT_TRUE(ins.finished);
  EXPECT_EQ(sim.particles.size(), report.placed);
}

TEST(Insertion, SizeClassesFollowTheirShareExactly) {
  Simulation sim = empty_box(0.02);
  Insertion ins = box_insertion(0.02, 0.3e-3, 100);
  ins.sizes = {{0.3e-3, 0.7}, {0.6e-3, 0.3}};
  ins.start(0.0);
  Rng rng(3);
  insert_due_particles(sim, ins, rng);
  std::size_t small = 0;
  for (double r : sim.particles.radius_m) small += r < 0.4e-3 ? 1 : 0;
  EXPECT_EQ(small, 70u);
}

class Quiet : public RunObserver {};

ScenarioSpec box_scenario() {
  ScenarioSpec spec;
  spec.name = "fill";
  spec.file = "fill.yaml";
  spec.gravity_m_per_s2 = {};
  spec.domain.min_m = {-0.01, -0.01, -0.01};
  spec.domain.max_m = {0.01, 0.01, 0.01};
  spec.materials.push_back(elastic_material("grain", 2500.0, 1e8, 0.25));
  InteractionSpec pair;
  pair.material_a = pair.material_b = "grain";
  spec.interactions.push_back(pair);
  StageSpec stage;
  stage.name = "fill";
  stage.duration_s = 0.0;
  spec.stages.push_back(stage);
  return spec;
}

InsertionSpec box_insertion_spec(InsertAmount kind, double amount) {
  InsertionSpec in;
  in.name = "grains";
  in.material = "grain";
  in.region.shape = RegionShape::box;
  in.region.min_m = {-0.005, -0.005, -0.005};
  in.region.max_m = {0.005, 0.005, 0.005};
  in.sizes = {{0.5e-3, 1.0}};
  in.amount_kind = kind;
  in.amount = amount;
  return in;
}

std::size_t inserted_count(const ScenarioSpec& spec) {
  PreparedRun run = PreparedRun::build(spec, 1);
  Quiet quiet;
  std::atomic<bool> stop{false};
  EXPECT_TRUE(run.run(quiet, stop).completed);
  return run.simulation().particles.size();
}

TEST(Insertion, SolidFractionAndMassGiveTheMatchingCount) {
  const double sphere_volume = 4.0 / 3.0 * std::numbers::pi * std::pow(0.5e-3, 3);
  ScenarioSpec by_fraction = box_scenario();
  by_fraction.insertions.push_back(box_insertion_spec(InsertAmount::solid_fraction, 0.15));
  EXPECT_EQ(inserted_count(by_fraction), static_cast<std::size_t>(std::llround(0.15 * 1e-6 / sphere_volume)));
  ScenarioSpec by_mass = box_scenario();
  const double mass = 100 * 2500.0 * sphere_volume;
  by_mass.insertions.push_back(box_insertion_spec(InsertAmount::mass, mass));
  EXPECT_EQ(inserted_count(by_mass), 100u);
}

TEST(Insertion, FractionsByMassBecomeNumberFractions) {
  ScenarioSpec spec = box_scenario();
  InsertionSpec in = box_insertion_spec(InsertAmount::count, 90);
  // Equal mass in each class: the 2x larger radius has 8x fewer particles.
  in.sizes = {{0.25e-3, 0.5}, {0.5e-3, 0.5}};
  in.fractions_by_mass = true;
  spec.insertions.push_back(in);
  PreparedRun run = PreparedRun::build(spec, 1);
  Quiet quiet;
  std::atomic<bool> stop{false};
  ASSERT_TRUE(run.run(quiet, stop).completed);
  std::size_t small = 0;
  for (double r : run.simulation().particles.radius_m) small += r < 0.3e-3 ? 1 : 0;
  EXPECT_EQ(small, 80u);  // 90 * 8/9
}

// A region asked for more than it holds: 1e6 grains of 1 mm in a 1 cm box (a solid
// fraction of 52, where 0.74 is the densest packing) fail the stage by default, saying
// how many were placed (it used to end "completed", exit 0); allow_partial goes on.
TEST(Insertion, ARegionThatFillsUpFailsTheStageUnlessPartialIsAllowed) {
  ScenarioSpec spec = box_scenario();
  spec.insertions.push_back(box_insertion_spec(InsertAmount::count, 1e6));
  {
    PreparedRun run = PreparedRun::build(spec, 1);
    Quiet quiet;
    std::atomic<bool> stop{false};
    const RunOutcome outcome = run.run(quiet, stop);
    EXPECT_FALSE(outcome.completed);
    EXPECT_NE(outcome.message.find("insertion 'grains' placed " + std::to_string(run.simulation().particles.size()) +
                                   " of the 1000000 particles it asks for: its region is full"),
              std::string::npos)
        << outcome.message;
    EXPECT_NE(outcome.message.find("allow_partial: true"), std::string::npos) << outcome.message;
  }
  spec.insertions.back().allow_partial = true;
  EXPECT_GT(inserted_count(spec), 100u);  // completed, with what fits
}

}  // namespace
}  // namespace regodem
