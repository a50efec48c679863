// The model of a run (sim/simulation_model.hpp, issue 18): what it derives from the
// materials and settings, and that replacing the materials (a stage's overrides) derives
// it again, each value against its closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <utility>

#include "core/error.hpp"
#include "sim/simulation.hpp"

namespace regodem {
namespace {

/// A material with what the model derives from: moduli, and c and k as given.
Material material(const char* name, double shear_modulus_Pa, double poisson, TemperatureCurve specific_heat,
                  TemperatureCurve conductivity) {
  Material m;
  m.name = name;
  m.density_kg_per_m3 = 3000.0;
  m.shear_modulus_Pa = shear_modulus_Pa;
  m.poisson_ratio = poisson;
  m.specific_heat_J_per_kgK = std::move(specific_heat);
  m.conductivity_W_per_mK = std::move(conductivity);
  return m;
}

SimulationSettings settings() {
  SimulationSettings s;
  s.domain = {{-0.01, -0.01, -0.01}, {0.01, 0.01, 0.01}};
  s.time_step_s = 1e-6;
  s.neighbor_skin_m = 1e-4;
  s.min_particle_radius_m = s.max_particle_radius_m = 1e-3;
  s.heat.enabled = true;
  s.heat.time_scale_factor = 20.0;
  return s;
}

MaterialTable two_materials(double restitution, double sliding_friction) {
  MaterialTable materials;
  // c constant and k a table of T for the grain; the other way round for the steel.
  materials.add(material("grain", 1e6, 0.25, TemperatureCurve(800.0), TemperatureCurve({100.0, 300.0}, {0.01, 0.03})));
  materials.add(material("steel", 79e9, 0.3, TemperatureCurve({100.0, 300.0}, {300.0, 480.0}), TemperatureCurve(16.0)));
  PairProperties p;
  p.restitution = restitution;
  p.sliding_friction = sliding_friction;
  p.conduction = ConductionLaw::radius;
  for (MaterialIndex a = 0; a < 2; ++a)
    for (MaterialIndex b = a; b < 2; ++b) materials.set_pair(a, b, p);
  return materials;
}

/// 2 sqrt(5/6) |beta|, beta = ln e / sqrt(ln^2 e + pi^2) (EDEM, Tsuji).
double damping_factor(double restitution) {
  const double l = std::log(restitution);
  return 2.0 * std::sqrt(5.0 / 6.0) * std::abs(l / std::sqrt(l * l + std::numbers::pi * std::numbers::pi));
}

TEST(SimulationModel, DerivesThePairTablesAndThermalCachesFromTheMaterials) {
  const Simulation sim(two_materials(0.5, 0.4), WallSet{}, settings());
  const SimulationModel& model = sim.model();
  // 1/E* = (1 - nu_a^2)/E_a + (1 - nu_b^2)/E_b with E = 2 G (1 + nu).
  const double e_grain = 2.0 * 1e6 * 1.25, e_steel = 2.0 * 79e9 * 1.3;
  const double e_star = 1.0 / ((1.0 - 0.0625) / e_grain + (1.0 - 0.09) / e_steel);
  EXPECT_NEAR(model.contact(0, 1).effective_youngs_modulus_Pa, e_star, 1e-12 * e_star);
  EXPECT_NEAR(model.contact(1, 0).damping_factor, damping_factor(0.5), 1e-14);
  EXPECT_EQ(model.contact(0, 0).sliding_friction, 0.4);
  // The radius law with S folded in: G = 2 S k_c a.
  EXPECT_EQ(model.conduction(0, 0).radius_factor, 2.0 * 20.0);
  // 1/c where c is constant, 0 (the enthalpy route) where it is a table; k a table or not.
  EXPECT_EQ(model.inv_specific_heat[0], 1.0 / 800.0);
  EXPECT_EQ(model.inv_specific_heat[1], 0.0);
  EXPECT_TRUE(model.conductivity_varies[0]);
  EXPECT_FALSE(model.conductivity_varies[1]);
  EXPECT_EQ(model.settings.heat.time_scale_factor, 20.0);
}

TEST(SimulationModel, NewMaterialsDeriveEveryTableAgain) {
  Simulation sim(two_materials(0.5, 0.4), WallSet{}, settings());
  sim.set_materials(two_materials(0.9, 0.1));  // a stage's overrides
  EXPECT_NEAR(sim.model().contact(0, 1).damping_factor, damping_factor(0.9), 1e-14);
  EXPECT_EQ(sim.model().contact(0, 1).sliding_friction, 0.1);
  EXPECT_EQ(sim.model().materials.pair(0, 1).restitution, 0.9);
  sim.set_materials(two_materials(0.5, 0.4));  // and their undoing at the stage's end
  EXPECT_NEAR(sim.model().contact(0, 1).damping_factor, damping_factor(0.5), 1e-14);
}

TEST(SimulationModel, RefusesANeighbourSkinOfZero) {
  SimulationSettings s = settings();
  s.neighbor_skin_m = 0.0;
  EXPECT_THROW(Simulation(two_materials(0.5, 0.4), WallSet{}, s), InputError);
}

}  // namespace
}  // namespace regodem
