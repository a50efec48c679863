// The shipped drilling files conduct at the drill as the real materials would (issue 17:
// their steel once had a reduced modulus and no real one, so a grain-drill contact
// conducted ~40x too much). A grain of each file's regolith is pressed delta into the
// drill's cone tip; the contact's conductance in the simulation's thermal network must be
// Eq. 1 of the paper with the REAL moduli:
//   G = 2 S k_s a_F,  a_F = (3 F R / (4 E*_real))^(1/3),  F = 4/3 E*_mech sqrt(R) delta^(3/2)
// (R* = R at a wall), with E* mixed here from the constants the files state (regolith
// G 1e6 Pa, real 3e9 Pa, nu 0.25; steel G 1e6 Pa, real 79 GPa, nu 0.3) and k_s the grains'
// 14.76 W/(m K) (the drill gives none: Eq. 1's k_s). Tolerance 1e-9 (arithmetic only).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

#include "core/error.hpp"
#include "scenario/scenario_builder.hpp"
#include "scenario/scenario_reader.hpp"
#include "sim/simulation.hpp"
#include "shipped_scenario_text.hpp"

namespace regodem {
namespace {

/// E* = 1 / ((1 - nu_a^2)/E_a + (1 - nu_b^2)/E_b), E = 2 G (1 + nu).
double mixed_modulus_Pa(double shear_a_Pa, double nu_a, double shear_b_Pa, double nu_b) {
  const double youngs_a = 2.0 * shear_a_Pa * (1.0 + nu_a), youngs_b = 2.0 * shear_b_Pa * (1.0 + nu_b);
  return 1.0 / ((1.0 - nu_a * nu_a) / youngs_a + (1.0 - nu_b * nu_b) / youngs_b);
}

struct ShippedFile {
  const char* path;        // under scenarios/paper
  double time_scale;       // the file's heat.time_scale_factor
  double tip_z_m;          // the drill's placement: its cone tip
  double grain_radius_m;   // a grain of the file's fine size
};

class ShippedDrillConduction : public ::testing::TestWithParam<ShippedFile> {};

TEST_P(ShippedDrillConduction, GrainDrillConductanceUsesTheRealModuli) {
  const ShippedFile file = GetParam();
  const fs::path source = fs::path(REGODEM_SOURCE_DIR) / "scenarios" / "paper" / file.path;
  // The file as shipped, with one probe grain in place of its bed (not needed here).
  std::string text = without_initial_state(read_text(source));
  const fs::path dir = fs::temp_directory_path() / ("regodem-shipped-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const double radius = file.grain_radius_m, overlap = 1e-3 * radius;
  {
    std::ofstream csv(dir / "probe.csv");
    csv << "x,y,z,radius\n0,0," << file.tip_z_m - radius + overlap + 0.02 << "," << radius << "\n";
  }
  text += "\ninsertions:\n  - {name: probe, material: regolith, file: " + (dir / "probe.csv").string() +
          ", temperature: -196 degC}\n";
  PreparedRun run = PreparedRun::build(read_scenario_string(text, source.string()), 1);
  Simulation& sim = run.simulation();
  ASSERT_EQ(sim.walls.meshes.size(), 1u);
  ASSERT_NEAR(sim.walls.meshes[0].mesh.bounding_box().lo_m.z, file.tip_z_m, 1e-9) << "the tip is not where assumed";
  NewParticle grain;
  grain.position_m = {0, 0, file.tip_z_m - radius + overlap};
  grain.radius_m = radius;
  grain.density_kg_per_m3 = 3000.0;
  grain.material = 0;
  grain.temperature_K = 77.15;
  sim.add_particle(grain);

  std::vector<int> wall_node, wall_boundary;
  const ThermalNetwork network = sim.thermal_network(wall_node, wall_boundary);
  ASSERT_EQ(network.boundary_links.size(), 1u);  // the grain and the drill, once
  const double mechanics = mixed_modulus_Pa(1e6, 0.25, 1e6, 0.3);
  const double real = mixed_modulus_Pa(3e9, 0.25, 79e9, 0.3);
  const double force = 4.0 / 3.0 * mechanics * std::sqrt(radius) * std::pow(overlap, 1.5);
  const double expected = 2.0 * file.time_scale * 14.76 * std::cbrt(3.0 * force * radius / (4.0 * real));
  EXPECT_NEAR(network.boundary_links[0].conductance_W_per_K, expected, 1e-9 * expected);
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(PaperFiles, ShippedDrillConduction,
                         ::testing::Values(ShippedFile{"tiny/drill-sieve.yaml", 80.0, 12e-3, 1e-3},
                                           ShippedFile{"drill-sieve-reduced.yaml", 80.0, 58.7e-3, 0.75e-3},
                                           ShippedFile{"drill-nosieve-reduced.yaml", 80.0, 57.3e-3, 0.75e-3},
                                           ShippedFile{"drill-single-size-reduced.yaml", 80.0, 58.4e-3, 0.75e-3}),
                         [](const ::testing::TestParamInfo<ShippedFile>& case_info) {
                           std::string name = case_info.param.path;
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

}  // namespace
}  // namespace regodem

namespace regodem {
namespace {

// The guard: the old files' steel (reduced, no real modulus, beside grains that give one)
// is refused with the material, its line and where the heat flows; `same` is accepted.
TEST(RealModulusGuard, RefusesAConductingMaterialWithoutARealModulus) {
  const fs::path csv = fs::temp_directory_path() / ("regodem-guard-" + std::to_string(::getpid()) + ".csv");
  const std::string old_steel = tiny_drill_text(
      [](std::string t) { return replace_all(t, ", real_shear_modulus: 79 GPa", ""); }, csv);
  try {
    PreparedRun::build(read_scenario_string(old_steel, "drill-sieve.yaml"), 1);
    ADD_FAILURE() << "the old steel was accepted";
  } catch (const InputError& e) {
    const std::string message = e.what();
    // steel's line: 13 in the file, 12 once its initial_state line is gone
    EXPECT_NE(message.find("drill-sieve.yaml:12:3: materials.steel"), std::string::npos) << message;
    EXPECT_NE(message.find("material 'steel' gives no real modulus, but 'regolith' does"), std::string::npos)
        << message;
    EXPECT_NE(message.find("wall 'drill'"), std::string::npos) << message;
  }
  const std::string same = tiny_drill_text(
      [](std::string t) { return replace_all(t, "real_shear_modulus: 79 GPa", "real_shear_modulus: same"); },
      csv);
  const PreparedRun run = PreparedRun::build(read_scenario_string(same, "drill-sieve.yaml"), 1);
  bool described = false;
  for (const std::string& line : run.describe())
    if (line.find("conduction 'regolith' at wall 'drill' ('steel'): force law, contact radius from E*") !=
        std::string::npos)
      described = true;
  EXPECT_TRUE(described);
  fs::remove(csv);
}

}  // namespace
}  // namespace regodem

namespace regodem {
namespace {

// "Done when the guard refuses the old reduced files" (issue 17): the three reduced drilling
// files as they were shipped before the fix (c0f5ce3^, kept verbatim in
// tests/data/pre-issue-17), with one probe grain in place of their bed, are refused, and
// the message names the steel at its line in the file.
class PreFixReducedFile : public ::testing::TestWithParam<const char*> {};

TEST_P(PreFixReducedFile, IsRefusedForItsSteelWithoutARealModulus) {
  const fs::path source = fs::path(REGODEM_SOURCE_DIR) / "tests" / "data" / "pre-issue-17" / GetParam();
  const fs::path csv = fs::temp_directory_path() / ("regodem-prefix-" + std::to_string(::getpid()) + ".csv");
  {
    std::ofstream out(csv);
    out << "x,y,z,radius\n0,0,0.08,0.00075\n";
  }
  const std::string text = without_initial_state(read_text(source)) +
                           "\ninsertions:\n  - {name: probe, material: regolith, file: " + csv.string() +
                           ", temperature: -196 degC}\n";
  try {
    PreparedRun::build(read_scenario_string(text, source.string()), 1);
    ADD_FAILURE() << GetParam() << ": the old steel was accepted";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(": materials.steel: material 'steel' gives no real modulus, but 'regolith' does"),
              std::string::npos)
        << message;
  }
  fs::remove(csv);
}

INSTANTIATE_TEST_SUITE_P(Issue17, PreFixReducedFile,
                         ::testing::Values("drill-sieve-reduced.yaml", "drill-nosieve-reduced.yaml",
                                           "drill-single-size-reduced.yaml"),
                         [](const ::testing::TestParamInfo<const char*>& case_info) {
                           std::string name = case_info.param;
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

}  // namespace
}  // namespace regodem
