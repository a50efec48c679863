// A run that goes wrong stops with the particle, the time and a suggestion; a packing
// file is read by its header and refused, with its line, when malformed, overlapped,
// outside the domain or inside a wall.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.hpp"
#include "io/particle_csv_reader.hpp"
#include "scenario/scenario_builder.hpp"
#include "scenario/scenario_reader.hpp"
#include "sim/simulation.hpp"

namespace regodem {
namespace {

Simulation two_grains(double time_step_s, double gravity) {
  MaterialTable materials;
  materials.add({"grain", 2500.0, 1e8, 0.25});
  materials.set_pair(0, 0, PairProperties{});
  SimulationSettings s;
  s.domain = {{-0.01, -0.01, -0.01}, {0.01, 0.01, 0.01}};
  s.gravity_m_per_s2 = {0, 0, gravity};
  s.time_step_s = time_step_s;
  s.neighbor_skin_m = 1e-4;
  s.min_particle_radius_m = 1e-3;
  return Simulation(materials, WallSet{}, s);
}

std::string error_of(Simulation& sim, std::uint64_t steps) {
  try {
    sim.advance(steps);
  } catch (const SimulationError& e) {
    return e.what();
  }
  return "";
}

TEST(BlowUp, DeepOverlapWithAHugeStepStopsWithParticleTimeAndAdvice) {
  Simulation sim = two_grains(1e-4, 0.0);  // ~10 Rayleigh times
  NewParticle a;
  a.radius_m = 1e-3;
  a.density_kg_per_m3 = 2500.0;
  a.position_m = {-0.5e-3, 0, 0};
  NewParticle b = a;
  b.position_m = {0.5e-3, 0, 0};
  sim.add_particle(a);
  sim.add_particle(b);
  const std::string message = error_of(sim, 100);
  ASSERT_FALSE(message.empty()) << "the overlap should have blown up";
  EXPECT_NE(message.find("particle "), std::string::npos) << message;
  EXPECT_NE(message.find("t = 0.0001 s (step 1)"), std::string::npos) << message;
  EXPECT_NE(message.find("too large"), std::string::npos) << message;
}

TEST(BlowUp, ParticleLeavingTheDomainIsNamed) {
  Simulation sim = two_grains(1e-6, -9.81);
  NewParticle a;
  a.radius_m = 1e-3;
  a.density_kg_per_m3 = 2500.0;
  a.position_m = {0, 0, -0.0095};
  a.velocity_m_per_s = {0, 0, -1.0};
  sim.add_particle(a);
  const std::string message = error_of(sim, 10000);
  ASSERT_FALSE(message.empty());
  EXPECT_NE(message.find("particle 0 left the domain"), std::string::npos) << message;
  EXPECT_NE(message.find("enlarge the domain"), std::string::npos) << message;
}

std::filesystem::path write_temp(const std::string& name, const std::string& content) {
  const auto path = std::filesystem::temp_directory_path() / name;
  std::ofstream(path) << content;
  return path;
}

TEST(ParticleCsv, ReadsColumnsInAnyOrderWithOptionalVelocity) {
  const auto path = write_temp("regodem-packing.csv", "# made elsewhere\nradius,z,y,x,vz\n0.001,3,2,1,-0.5\n0.002,6,5,4,0\n");
  const std::vector<ParticleRecord> records = read_particle_csv(path.string());
  ASSERT_EQ(records.size(), 2u);
  EXPECT_EQ(records[0].position_m, (Vec3{1, 2, 3}));
  EXPECT_EQ(records[0].radius_m, 0.001);
  EXPECT_EQ(records[0].velocity_m_per_s.z, -0.5);
  EXPECT_FALSE(records[0].has_temperature);
}

TEST(ParticleCsv, MalformedFilesAreRefusedWithTheirLine) {
  auto message_for = [](const std::string& content) {
    try {
      read_particle_csv(write_temp("regodem-bad-packing.csv", content).string());
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message_for("x,y,z\n1,2,3\n").find("lacks the column 'radius'"), std::string::npos);
  EXPECT_NE(message_for("x,y,z,radius\n1,2,3,0.1\n1,2,3\n").find(":3: 3 values"), std::string::npos);
  EXPECT_NE(message_for("x,y,z,radius\n1,2,abc,0.1\n").find(":2: column 'z'"), std::string::npos);
  EXPECT_NE(message_for("x,y,z,radius\n1,2,3,-0.1\n").find("radius must be positive"), std::string::npos);
  EXPECT_NE(message_for("x,y,z,radius,colour\n").find("unknown column 'colour'"), std::string::npos);
  EXPECT_NE(message_for("x,y,z,radius,x\n1,2,3,0.1,4\n").find(":1: the column 'x' appears twice (columns 1 and 5)"),
            std::string::npos)
      << message_for("x,y,z,radius,x\n1,2,3,0.1,4\n");
}

// A packing file is checked as a whole before it runs: 90 % overlaps used to be blasted
// apart with exit 0, and a particle outside the domain passed validate.
std::string packing_refusal(const std::string& csv, const std::string& extra_insertion_keys = "") {
  const std::filesystem::path file = write_temp("regodem-packing-check.csv", csv);
  const std::string scenario = R"(
name: packing
domain: {min: [-10 mm, -10 mm, -10 mm], max: [10 mm, 10 mm, 10 mm]}
materials:
  grain: {density: 2500 kg/m^3, shear_modulus: 1e6 Pa, poisson_ratio: 0.25}
interactions:
  - {materials: [grain, grain], restitution: 0.3, sliding_friction: 0.5}
walls:
  - {name: floor, type: plane, point: [0, 0, -5 mm], normal: [0, 0, 1]}
insertions:
  - {name: bed, material: grain, file: ')" + file.string() + "'" + extra_insertion_keys + R"(}
stages:
  - {name: settle, duration: 1 ms}
)";
  try {
    PreparedRun::build(read_scenario_string(scenario, "packing.yaml"), 1);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ParticleCsv, APackingIsCheckedForOverlapsTheDomainAndTheWalls) {
  // Radius 1 mm, centres 2 mm apart: touching; 1.92 mm: 0.04 of the diameter, under
  // the default limit 0.05; 1.88 mm: 0.06, over it; 0.2 mm apart: 0.9.
  EXPECT_EQ(packing_refusal("x,y,z,radius\n0,0,0,0.001\n0.002,0,0,0.001\n"), "");
  EXPECT_EQ(packing_refusal("x,y,z,radius\n0,0,0,0.001\n0.00192,0,0,0.001\n"), "");
  EXPECT_NE(packing_refusal("x,y,z,radius\n0,0,0,0.001\n0.00188,0,0,0.001\n").find("overlap by 0.06"),
            std::string::npos);
  const std::string deep = packing_refusal("x,y,z,radius\n0,0,0,0.001\n0.003,0,0,0.001\n0.0002,0,0,0.001\n");
  EXPECT_NE(deep.find("the particles of lines 2 and 4 overlap by 0.9 of the smaller diameter"), std::string::npos)
      << deep;
  EXPECT_EQ(packing_refusal("x,y,z,radius\n0,0,0,0.001\n0.0002,0,0,0.001\n", ", max_overlap: 0.95"), "");
  const std::string outside = packing_refusal("x,y,z,radius\n0,0,0,0.001\n0,0,0.0095,0.001\n");
  EXPECT_NE(outside.find(":3: the particle at (0, 0, 0.0095) m, radius 0.001 m, is not wholly inside the domain"),
            std::string::npos)
      << outside;
  // The floor at z = -5 mm: a centre 0.5 mm above it reaches 0.25 of the diameter in.
  const std::string wall = packing_refusal("x,y,z,radius\n0,0,0,0.001\n0,0,-0.0045,0.001\n");
  EXPECT_NE(wall.find(":3: the particle at (0, 0, -0.0045) m, radius 0.001 m, reaches into wall 'floor' by 0.25 of "
                      "its diameter"),
            std::string::npos)
      << wall;
}

// The t = 0 sample comes before the first contact pass: the overlap is found without
// a neighbour list (it reported 0 for a packing that started overlapped).
TEST(ParticleCsv, TheLargestOverlapIsReportedBeforeTheFirstStep) {
  Simulation sim = two_grains(1e-6, 0.0);
  NewParticle a;
  a.radius_m = 1e-3;
  a.density_kg_per_m3 = 2500.0;
  a.position_m = {0, 0, 0};
  NewParticle b = a;
  b.position_m = {1.8e-3, 0, 0};  // 0.2 mm overlap = 0.1 of the diameter
  sim.add_particle(a);
  sim.add_particle(b);
  EXPECT_NEAR(sim.max_overlap_fraction(), 0.1, 1e-12);
}

}  // namespace
}  // namespace regodem
