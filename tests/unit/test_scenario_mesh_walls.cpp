// Mesh walls and drilling motion in a scenario: a `type: mesh` wall's file, scale and
// placement; feed with a depth at start and a stop depth; a stage that ends at a
// depth; the drill's depth, thrust and torque columns; and clear errors for bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "core/error.hpp"
#include "scenario/scenario_builder.hpp"
#include "scenario/scenario_reader.hpp"
#include "sim/simulation.hpp"
#include "sim/stage_plan.hpp"

namespace regodem {
namespace {

// A 4 mm x 4 mm square plate in millimetres, in the file's z = 0 plane.
constexpr const char* kPlateStl = R"(solid plate
facet normal 0 0 1
 outer loop
  vertex -2 -2 0
  vertex 2 -2 0
  vertex 2 2 0
 endloop
endfacet
facet normal 0 0 1
 outer loop
  vertex -2 -2 0
  vertex 2 2 0
  vertex -2 2 0
 endloop
endfacet
endsolid plate
)";

constexpr const char* kScenario = R"(name: mesh-wall
domain:
  min: [-10 mm, -10 mm, -10 mm]
  max: [10 mm, 10 mm, 10 mm]
gravity: [0, 0, 0]
time_step: 1 ms
materials:
  regolith: {density: 3000 kg/m^3, shear_modulus: 1 kPa, poisson_ratio: 0.25}  # soft: a 1 ms step
interactions:
  - {materials: [regolith, regolith], restitution: 0.5, sliding_friction: 0.5}
walls:
  - name: plate
    type: mesh
    file: plate.stl
    scale: 0.001
    placement:
      translation: [0, 0, 5 mm]
      rotation: {axis: [1, 0, 0], angle: 90 deg}
    motion:
      velocity: [0, 0, -1 mm/s]
      angular_velocity: 60 rpm
      axis: [0, 0, 1]
      depth_at_start: -1 mm
      stop_at_depth: 3 mm
insertions:
  - name: one
    material: regolith
    region: {type: box, min: [6 mm, 6 mm, -9 mm], max: [9 mm, 9 mm, -6 mm]}
    diameter: 1 mm
    count: 1
stages:
  - name: drill
    until: {wall: plate, depth: 2 mm}
)";

class MeshScenario : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("regodem-mesh-scenario-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
    write("plate.stl", kPlateStl);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) const {
    const std::filesystem::path path = dir_ / name;
    std::ofstream(path) << text;
    return path.string();
  }
  /// The scenario with one line replaced, read from the temporary directory.
  ScenarioSpec read(const std::string& from = "", const std::string& to = "") const {
    std::string text = kScenario;
    if (!from.empty()) {
      const std::size_t at = text.find(from);
      EXPECT_NE(at, std::string::npos) << from;
      text.replace(at, from.size(), to);
    }
    return read_scenario_file(write("scenario.yaml", text));
  }
  std::string error_of(const std::string& from, const std::string& to) const {
    try {
      PreparedRun::build(read(from, to), 1);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }

  std::filesystem::path dir_;
};

// Scale, then a quarter turn about x (the plate stands up in the x-z plane), then the
// translation: the file's (2, 2, 0) mm lands at (2, 0, 7) mm (to 1e-15 m).
TEST_F(MeshScenario, FileIsScaledAndPlaced) {
  const ScenarioSpec spec = read();
  ASSERT_EQ(spec.walls.size(), 1u);
  const WallSpec& wall = spec.walls[0];
  ASSERT_TRUE(wall.mesh);
  EXPECT_EQ(wall.mesh->triangle_count(), 2u);
  const Aabb box = wall.mesh->bounding_box();
  EXPECT_NEAR(box.lo_m.x, -2e-3, 1e-15);
  EXPECT_NEAR(box.hi_m.x, 2e-3, 1e-15);
  EXPECT_NEAR(box.lo_m.y, 0.0, 1e-15);
  EXPECT_NEAR(box.hi_m.y, 0.0, 1e-15);
  EXPECT_NEAR(box.lo_m.z, 3e-3, 1e-15);
  EXPECT_NEAR(box.hi_m.z, 7e-3, 1e-15);
  EXPECT_NEAR(wall.motion.depth_at_start_m, -1e-3, 1e-18);
  EXPECT_NEAR(wall.motion.stop_at_depth_m, 3e-3, 1e-18);
  // "60 rpm" about +z through the placement's translation.
  EXPECT_NEAR(wall.motion.angular_velocity_rad_per_s.z, 2.0 * std::numbers::pi, 1e-12);
  EXPECT_NEAR(wall.motion.axis_point_m.z, 5e-3, 1e-18);
}

// The stage runs until the depth reaches 2 mm: 3 mm of feed at 1 mm/s from -1 mm, i.e.
// 3 s (3000 steps of 1 ms), within one step; the body then stops at 3 mm depth in a
// later stage; the time series carries depth, thrust and drive torque.
TEST_F(MeshScenario, StageEndsAtTheDrillDepth) {
  PreparedRun run = PreparedRun::build(read(), 1);
  const Simulation& sim = run.simulation();
  ASSERT_EQ(sim.walls.meshes.size(), 1u);
  EXPECT_NEAR(sim.walls.bodies[0].motion.max_travel_m, 4e-3, 1e-18);
  EXPECT_TRUE(run.plan().stages[0].ends_at_depth());
  EXPECT_TRUE(std::isinf(sim.walls.bodies[0].motion.max_thrust_N));  // no thrust limit unless given
  PreparedRun limited = PreparedRun::build(read("stop_at_depth: 3 mm", "stop_at_depth: 3 mm\n      stop_at_thrust: 0.25 N"), 1);
  EXPECT_DOUBLE_EQ(limited.simulation().walls.bodies[0].motion.max_thrust_N, 0.25);
  struct Columns : RunObserver {
    std::vector<std::string> names;
    void columns(const std::vector<SeriesColumn>& c) override {
      for (const SeriesColumn& s : c) names.push_back(s.name);
    }
  } observer;
  const std::atomic<bool> stop{false};
  const RunOutcome outcome = run.run(observer, stop);
  ASSERT_TRUE(outcome.completed) << outcome.message;
  EXPECT_NEAR(sim.walls.bodies[0].depth_m(), 2e-3, 1e-6 + 1e-12);
  EXPECT_NEAR(sim.time_s(), 3.0, 1e-3 + 1e-9);
  for (const char* column : {"plate.depth", "plate.thrust", "plate.drive_torque"})
    EXPECT_NE(std::find(observer.names.begin(), observer.names.end(), column), observer.names.end()) << column;
}

// Snapshots every 1 mm of the drill's depth: at the start (-1 mm), then at 0, 1 and 2
// mm, each on the first step at or past its depth (the feed moves 1 micrometre a step),
// and none doubled at the stage's end.
TEST_F(MeshScenario, SnapshotsEveryMillimetreOfDepth) {
  ScenarioSpec spec = read("stages:", "output:\n  snapshots: {every_depth: {wall: plate, depth: 1 mm}}\nstages:");
  PreparedRun run = PreparedRun::build(spec, 1);
  struct Depths : RunObserver {
    std::vector<double> depth_m;
    void snapshot(const Simulation& sim) override { depth_m.push_back(sim.walls.bodies[0].depth_m()); }
  } observer;
  const std::atomic<bool> stop{false};
  ASSERT_TRUE(run.run(observer, stop).completed);
  ASSERT_EQ(observer.depth_m.size(), 4u);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(observer.depth_m[static_cast<std::size_t>(k)], -1e-3 + 1e-3 * k, 1e-6 + 1e-12) << k;
  EXPECT_NE(error_of("stages:", "output:\n  snapshots: {every_depth: {wall: lid, depth: 1 mm}}\nstages:")
                .find("no wall named 'lid'"),
            std::string::npos);
}

// A depth the wall stops short of fails the stage with a message that says why.
TEST_F(MeshScenario, DepthBeyondTheStopFailsClearly) {
  PreparedRun run = PreparedRun::build(read("until: {wall: plate, depth: 2 mm}", "until: {wall: plate, depth: 5 mm}"), 1);
  const std::atomic<bool> stop{false};
  RunObserver quiet;
  const RunOutcome outcome = run.run(quiet, stop);
  EXPECT_FALSE(outcome.completed);
  EXPECT_NE(outcome.message.find("stopped feeding at a depth of 0.003"), std::string::npos) << outcome.message;
}

TEST_F(MeshScenario, BadInputIsReportedAtItsKey) {
  EXPECT_NE(error_of("file: plate.stl", "file: missing.stl").find("no such file"), std::string::npos);
  write("plate.txt", kPlateStl);
  EXPECT_NE(error_of("file: plate.stl", "file: plate.txt").find("must end in .stl"), std::string::npos);
  write("broken.stl", "solid broken\nfacet normal 0 0 1\n outer loop\n  vertex 0 0 0\n");
  EXPECT_NE(error_of("file: plate.stl", "file: broken.stl").find("walls.plate.file"), std::string::npos);
  EXPECT_NE(error_of("translation: [0, 0, 5 mm]", "translation: [0, 0, 9 mm]").find("outside the domain"),
            std::string::npos);
  EXPECT_NE(error_of("scale: 0.001", "scale: -1").find("greater than 0"), std::string::npos);
  EXPECT_NE(error_of("stop_at_depth: 3 mm", "stop_at_depth: -2 mm").find("deeper than 'depth_at_start'"),
            std::string::npos);
  EXPECT_NE(error_of("velocity: [0, 0, -1 mm/s]", "velocity: [0, 0, 0]").find("give the wall a velocity"),
            std::string::npos);
  EXPECT_NE(error_of("stop_at_depth: 3 mm", "stop_at_thrust: -2 N").find("greater than 0"), std::string::npos);
  EXPECT_NE(error_of("stop_at_depth: 3 mm", "stop_at_thrust: 2 mm").find("walls.plate.motion.stop_at_thrust"),
            std::string::npos);
  EXPECT_NE(error_of("until: {wall: plate, depth: 2 mm}", "until: {wall: drill, depth: 2 mm}")
                .find("no wall named 'drill'"),
            std::string::npos);
  EXPECT_NE(error_of("file: plate.stl", "center: [0, 0, 0]").find("placement"), std::string::npos);
}

}  // namespace
}  // namespace regodem
