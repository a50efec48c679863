// The drill as a thermal body in a scenario (issue 21): the tiny drilling file's drill
// made a lumped rod of axial segments, with its held end and radiation, and the errors
// for what cannot be.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <numeric>

#include "core/error.hpp"
#include "scenario/scenario_builder.hpp"
#include "scenario/scenario_reader.hpp"
#include "shipped_scenario_text.hpp"
#include "sim/simulation.hpp"

namespace regodem {
namespace {

const std::string kFixedDrill = "thermal: {mode: fixed, temperature: -100 degC}";

std::string drill_as(const std::string& thermal, const fs::path& csv) {
  return tiny_drill_text([&](std::string text) { return replace_all(text, kFixedDrill, thermal); }, csv);
}

fs::path probe_csv() { return fs::temp_directory_path() / ("regodem-drill-body-" + std::to_string(::getpid()) + ".csv"); }

// 2 g of steel (c = 460 J/(kg K)) in 5 slices of the 25 mm drill: the slices' m C by their
// area share, summing to m c; linked by k A / dz = 16 x 2 mm^2 / 5 mm, the held end by twice
// that; the tip's triangles in slice 1.
TEST(ScenarioDrillBody, ALumpedDrillIsARodOfSegments) {
  const fs::path csv = probe_csv();
  const std::string text = drill_as(
      "thermal: {mode: lumped, temperature: -100 degC, specific_heat: 460 J/(kg K), mass: 2 g, segments: 5,\n"
      "              rod: {conductivity: 16 W/(m K), cross_section: 2 mm^2}, held_end: -100 degC,\n"
      "              radiation: {emissivity: 0.3, surroundings: 40 K}}",
      csv);
  const PreparedRun run = PreparedRun::build(read_scenario_string(text, "drill.yaml"), 1);
  const Simulation& sim = run.simulation();
  ASSERT_EQ(sim.walls.meshes.size(), 1u);
  const MeshWall& mesh = sim.walls.meshes[0];
  const ThermalWall& drill = sim.model().wall_thermal[mesh.body];
  ASSERT_EQ(drill.rod.segment_heat_capacity_J_per_K.size(), 5u);
  const auto& c = drill.rod.segment_heat_capacity_J_per_K;
  EXPECT_NEAR(std::accumulate(c.begin(), c.end(), 0.0), 2e-3 * 460.0, 1e-12);
  EXPECT_NEAR(std::accumulate(drill.rod.segment_area_m2.begin(), drill.rod.segment_area_m2.end(), 0.0),
              mesh.mesh.area(), 1e-12 * mesh.mesh.area());
  const double link = 16.0 * 2e-6 / 5e-3;
  EXPECT_NEAR(drill.rod.link_conductance_W_per_K, link, 1e-12 * link);
  EXPECT_NEAR(drill.rod.held_end_conductance_W_per_K, 2.0 * link, 1e-12 * link);
  ASSERT_TRUE(drill.rod.held_end_K);
  EXPECT_DOUBLE_EQ(*drill.rod.held_end_K, 173.15);
  EXPECT_DOUBLE_EQ(drill.rod.emissivity, 0.3);
  EXPECT_DOUBLE_EQ(drill.rod.surroundings_K, 40.0);
  EXPECT_EQ(sim.wall_thermal_state[mesh.body].segment_temperature_K, std::vector<double>(5, *drill.rod.held_end_K));  // both -100 degC
  ASSERT_EQ(mesh.triangle_segment.size(), mesh.mesh.triangle_count());
  std::size_t lowest = 0;
  double lowest_z = 1e9;
  for (std::size_t t = 0; t < mesh.mesh.triangle_count(); ++t) {
    const double z = std::min({mesh.mesh.corner(t, 0).z, mesh.mesh.corner(t, 1).z, mesh.mesh.corner(t, 2).z});
    if (z < lowest_z) lowest_z = z, lowest = t;
  }
  EXPECT_EQ(mesh.triangle_segment[lowest], 0);
  EXPECT_EQ(*std::max_element(mesh.triangle_segment.begin(), mesh.triangle_segment.end()), 4);
  const std::vector<std::string> lines = run.describe();
  EXPECT_TRUE(std::any_of(lines.begin(), lines.end(), [](const std::string& l) {
    return l.find("5 axial segments (1 at the tip)") != std::string::npos &&
           l.find("far end held at 173.15 K") != std::string::npos &&
           l.find("radiates with emissivity 0.3 to 40 K") != std::string::npos;
  }));
  fs::remove(csv);
}

void expect_refused(const std::string& thermal, const std::string& fragment) {
  const fs::path csv = probe_csv();
  const std::string text = drill_as(thermal, csv);
  try {
    (void)PreparedRun::build(read_scenario_string(text, "drill.yaml"), 1);
    ADD_FAILURE() << "accepted: " << thermal;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
  fs::remove(csv);
}

TEST(ScenarioDrillBody, WhatARodCannotBeIsRefused) {
  const std::string lumped = "thermal: {mode: lumped, temperature: -100 degC, specific_heat: 460 J/(kg K), mass: 2 g, ";
  expect_refused(lumped + "segments: 4}", "heat runs along the rod");
  expect_refused(lumped + "held_end: 170 K}", "heat runs along the rod");
  expect_refused(lumped + "rod: {conductivity: 16 W/(m K), cross_section: 2 mm^2}}", "a rod conducts between segments");
  // The drill's steel gives no conductivity (contacts use the grains' k_s).
  expect_refused(lumped + "segments: 4, rod: {cross_section: 2 mm^2}}", "give `rod: {conductivity: ...}`");
  expect_refused(lumped + "segments: 0}", "must be 1 to 1000");
  expect_refused(lumped + "radiation: {emissivity: 1.5, surroundings: 40 K}}", "must be at most 1");
  expect_refused("thermal: {mode: fixed, temperature: -100 degC, segments: 4}", "only a lumped wall has its own heat paths");
  // So thick a rod that its 1 mm slices swap heat faster than the step.
  expect_refused(lumped + "segments: 25, rod: {conductivity: 400 W/(m K), cross_section: 1 m^2}}",
                 "exchange heat too fast for the time step");
}

// A drill whose steel gives its k (16 W/(m K), for the rod and a partition by conductivity
// or effusivity) conducts at its contacts with that k, unless its thermal block says
// `conductivity: particles`: then with the grains' own (Eq. 1's k_s), as the paper's files.
TEST(ScenarioDrillBody, ADrillMayConductWithTheParticlesOwnKWhileItsSteelGivesOne) {
  const fs::path csv = probe_csv();
  const std::string steel = "steel: {density: 7800 kg/m^3,";
  const auto drill_with = [&](const std::string& extra) {
    return tiny_drill_text(
        [&](std::string text) {
          text = replace_all(text, steel, "steel: {conductivity: 16 W/(m K), density: 7800 kg/m^3,");
          return replace_all(text, kFixedDrill,
                             "thermal: {mode: lumped, temperature: -100 degC, specific_heat: 500 J/(kg K), mass: 2 g, "
                             "segments: 5, rod: {cross_section: 2 mm^2}" + extra + "}");
        },
        csv);
  };
  for (const bool own : {false, true}) {
    SCOPED_TRACE(own ? "conductivity: particles" : "the material's k");
    const PreparedRun run =
        PreparedRun::build(read_scenario_string(drill_with(own ? ", conductivity: particles" : ""), "drill.yaml"), 1);
    const Simulation& sim = run.simulation();
    const ThermalWall& drill = sim.model().wall_thermal[sim.walls.meshes.at(0).body];
    if (own) {
      EXPECT_FALSE(drill.conductivity_W_per_mK.has_value());
    } else {
      ASSERT_TRUE(drill.conductivity_W_per_mK.has_value());
      EXPECT_DOUBLE_EQ(*drill.conductivity_W_per_mK, 16.0);
    }
    const double link = 16.0 * 2e-6 / 5e-3;  // the rod takes the steel's k either way
    EXPECT_NEAR(drill.rod.link_conductance_W_per_K, link, 1e-12 * link);
  }
  try {
    (void)PreparedRun::build(read_scenario_string(drill_with(", conductivity: grains"), "drill.yaml"), 1);
    ADD_FAILURE() << "accepted conductivity: grains";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("got 'grains', which is not a number"), std::string::npos) << e.what();
  }
  fs::remove(csv);
}

TEST(ScenarioDrillBody, APrimitiveWallHasNoRodButMayRadiate) {
  const fs::path csv = probe_csv();
  const std::string barrel = "ends: {bottom: capped}}";
  const auto with_barrel = [&](const std::string& thermal) {
    return tiny_drill_text(
        [&](std::string text) {
          return replace_all(text, barrel, "ends: {bottom: capped},\n     thermal: {mode: lumped, temperature: 100 K, "
                                           "specific_heat: 460 J/(kg K), mass: 50 g" + thermal + "}}");
        },
        csv);
  };
  try {
    (void)PreparedRun::build(read_scenario_string(with_barrel(", segments: 3"), "drill.yaml"), 1);
    ADD_FAILURE() << "a cylinder took segments";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("belongs to a mesh or auger wall"), std::string::npos) << e.what();
  }
  const PreparedRun run = PreparedRun::build(
      read_scenario_string(with_barrel(", radiation: {emissivity: 0.5, surroundings: 30 K}"), "drill.yaml"), 1);
  const ThermalWall& t = run.simulation().model().wall_thermal[0];
  EXPECT_DOUBLE_EQ(t.rod.emissivity, 0.5);
  // The barrel's side and its capped bottom: 2 pi r L + pi r^2, r = 8 mm, L = 30 mm.
  EXPECT_NEAR(t.rod.area_m2, 2 * M_PI * 8e-3 * 30e-3 + M_PI * 64e-6, 1e-15);
  fs::remove(csv);
}

}  // namespace
}  // namespace regodem
