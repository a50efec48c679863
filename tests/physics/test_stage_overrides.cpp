// A stage's overrides change the contact properties only while it runs: a sphere on a
// 30 degree slope slides freely (a = g sin t) in a stage with friction 0; then, with
// the scenario's friction 0.3 back, it slides with Coulomb friction while friction
// spins it up (a = g (sin t - mu cos t) until v = omega R, which takes
// v1 / (g (3.5 mu cos t - sin t)) = 0.061 s, longer than the 0.05 s stage). Time step
// 0.05 of the Rayleigh time; tolerance 1 % on each stage's change of speed.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "scenario/scenario_builder.hpp"
#include "sim/simulation.hpp"

namespace regodem {
namespace {

/// Records the kinetic energy at the end of each stage.
class StageEnds : public RunObserver {
 public:
  // time, real_time, step, stage, particles, kinetic_energy, ...
  void sample(const std::vector<double>& row) override { last_kinetic_energy = row[5]; }
  void stage_finished(const StageInfo&, StageResult, const std::string&) override {
    kinetic_energy_at_end.push_back(last_kinetic_energy);
  }
  double last_kinetic_energy = 0.0;
  std::vector<double> kinetic_energy_at_end;
};

TEST(StageOverrides, FrictionOffOnlyDuringItsStage) {
  const double angle = 30.0 * std::numbers::pi / 180.0, g = 9.81, radius = 1e-3;
  const std::filesystem::path csv = std::filesystem::temp_directory_path() / "regodem-one-sphere.csv";
  {
    std::ofstream out(csv);
    out << "x,y,z,radius\n0,0," << 0.99999 * radius << ',' << radius << '\n';
  }
  ScenarioSpec spec;
  spec.name = "overrides";
  spec.file = "overrides.yaml";
  spec.gravity_m_per_s2 = {g * std::sin(angle), 0, -g * std::cos(angle)};
  spec.domain.min_m = {-0.01, -0.01, -0.001};
  spec.domain.max_m = {0.5, 0.01, 0.01};
  spec.time_step_s = 0.0;
  spec.rayleigh_fraction = 0.05;
  spec.materials.push_back(elastic_material("grain", 2500.0, 1e8, 0.25));
  InteractionSpec pair;
  pair.material_a = pair.material_b = "grain";
  pair.restitution = 0.5;
  pair.sliding_friction = 0.3;
  spec.interactions.push_back(pair);
  WallSpec slope;
  slope.name = "slope";
  slope.shape = WallShape::plane;
  spec.walls.push_back(slope);
  InsertionSpec one;
  one.name = "sphere";
  one.material = "grain";
  one.from_file = csv.string();
  spec.insertions.push_back(one);
  StageSpec slide, roll;
  slide.name = "slide";
  slide.duration_s = 0.05;
  OverrideSpec frictionless;
  frictionless.sliding_friction = 0.0;
  slide.overrides.push_back(frictionless);
  roll.name = "roll";
  roll.duration_s = 0.05;
  spec.stages = {slide, roll};

  PreparedRun run = PreparedRun::build(spec, 1);
  StageEnds ends;
  std::atomic<bool> stop{false};
  ASSERT_TRUE(run.run(ends, stop).completed);
  ASSERT_EQ(ends.kinetic_energy_at_end.size(), 2u);
  const double mass = run.simulation().particles.mass_kg[0];
  // Frictionless: no torque, pure sliding; kinetic energy all translational.
  const double v1 = std::sqrt(2.0 * ends.kinetic_energy_at_end[0] / mass);
  EXPECT_NEAR(v1, g * std::sin(angle) * 0.05, 0.01 * g * std::sin(angle) * 0.05);
  // Friction back: sliding against Coulomb friction for the whole second stage.
  const double slip_ends_s = v1 / (g * (3.5 * 0.3 * std::cos(angle) - std::sin(angle)));
  ASSERT_GT(slip_ends_s, 0.05);
  const Vec3 v2 = run.simulation().particles.velocity_m_per_s[0];
  const double gained = v2.x - v1;
  const double expected = g * (std::sin(angle) - 0.3 * std::cos(angle)) * 0.05;
  EXPECT_NEAR(gained, expected, 0.01 * expected);
  std::filesystem::remove(csv);
}

}  // namespace
}  // namespace regodem
