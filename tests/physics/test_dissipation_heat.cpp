// Heat from dissipation and the energy audit (docs/physics.md, "Friction heat and its partition",
// "Energy audit"). Each test states its analytic result and tolerance before the run:
//  * a grain dragged across a floor at constant speed heats at mu N v (after its spring
//    has taken (mu N)^2 / (2 k_t)), and the partition models split that heat as
//    w_a / (w_a + w_b) with w = 1, k or sqrt(k rho c);
//  * a damped head-on collision heats by the kinetic energy it loses, which is
//    m* v^2 (1 - e^2) / 2 for restitution e;
//  * a damped bond and a bond that breaks heat by the kinetic energy they lose;
//  * a frictional impact and the drilling bed (bonds that break, a feeding and turning
//    paddle, walls of every thermal kind) close their mechanical books, and the bed turns
//    every loss into heat and closes its thermal books.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "drilling_bed.hpp"
#include "physics_fixtures.hpp"

namespace regodem::testing {
namespace {

constexpr double kRadius = 0.5e-3;

double kinetic_energy_J(const Simulation& sim) {
  return sim.translational_kinetic_energy_J() + sim.rotational_kinetic_energy_J();
}

/// A grain held at a fixed overlap on a floor of material b and moved along it at v:
/// the contact slides at constant speed under a constant normal force.
struct Drag {
  double generated_heat_J = 0.0, wall_heat_J = 0.0, particle_heat_J = 0.0;
  double expected_J = 0.0;  // mu N v t - (mu N)^2 / k_t
};

Drag drag(HeatPartitionModel partition, double fixed_share, const SphereMaterial& grain,
          const SphereMaterial& floor_material, bool every_loss = false) {
  const double overlap = 1e-6, speed = 0.01, mu = 0.4;
  PairProperties between;
  between.restitution = 0.5;
  between.sliding_friction = mu;
  MaterialTable materials = two_materials(grain, floor_material, between);
  const double dt = 0.05 * rayleigh_time_for(grain, kRadius);
  WallSet walls;
  walls.add_plane(walls.add_body("floor", {}), {0, 0, 0}, {0, 0, 1}, 1);
  ThermalWall floor;
  floor.mode = WallThermalMode::lumped;  // takes its share of the heat; conducts none
  floor.initial_temperature_K = 1.0;
  floor.heat_capacity_J_per_K = 1.0;
  floor.conductivity_W_per_mK = 0.0;  // k_c = 0: no conduction (the partition weighs the material's k)
  SimulationSettings settings = settings_for(kRadius, dt, {}, 0.1);
  settings.heat.enabled = true;
  // A held grain against a wall has no effective mass and so no damping: its losses are the
  // sliding alone, whether only sliding heats or every loss does.
  settings.heat.friction_heating = !every_loss;
  settings.heat.dissipation_heating = every_loss;
  settings.heat.partition = partition;
  settings.heat.friction_partition = fixed_share;
  Simulation sim(std::move(materials), walls, settings, {floor});
  // From 1 K: a rise of ~1e-4 K in steps of ~1e-8 K keeps its round-off far below 1e-6.
  sim.add_particle(sphere({0, 0, kRadius - overlap}, {speed, 0, 0}, kRadius, grain.density, 1.0));
  sim.particles.inv_mass_per_kg[0] = 0.0;  // held: it moves at v whatever the contact does
  sim.particles.inv_inertia[0] = 0.0;
  const std::uint64_t steps = 20000;
  sim.advance(steps);
  const double normal_force = 4.0 / 3.0 * effective_youngs_modulus(grain, floor_material) * std::sqrt(kRadius) *
                              std::pow(overlap, 1.5);
  const double tangential_stiffness =
      8.0 * effective_shear_modulus(grain, floor_material) * std::sqrt(kRadius * overlap);
  const double t = static_cast<double>(steps) * dt;
  Drag d;
  d.expected_J = mu * normal_force * speed * t - std::pow(mu * normal_force, 2) / tangential_stiffness;
  d.generated_heat_J = sim.thermal_ledger().generated_heat_J;
  d.wall_heat_J = sim.wall_thermal_state[0].generated_heat_J;
  d.particle_heat_J = sphere_mass(grain, kRadius) * grain.specific_heat * (sim.particles.temperature_K[0] - 1.0);
  return d;
}

// The sliding heat within 1e-3 of mu N v t - (mu N)^2/k_t (the step's last slip and the
// spring's rotation are all that can differ); the wall's share to 1e-9 of the model's.
// The same with every loss as heat (heat.dissipation_heating), whose path books the
// contact's dissipated power instead of its sliding power.
TEST(DissipationHeat, ADraggedGrainHeatsAtMuNvSharedByThePartitionModel) {
  SphereMaterial grain, steel;
  grain.conductivity = 10.0, grain.density = 2500.0, grain.specific_heat = 800.0;
  steel.conductivity = 50.0, steel.density = 7800.0, steel.specific_heat = 500.0;
  steel.shear_modulus = 2e8;
  const double e_grain = std::sqrt(10.0 * 2500.0 * 800.0), e_steel = std::sqrt(50.0 * 7800.0 * 500.0);
  struct Case {
    HeatPartitionModel model;
    double fixed_share, expected_particle_share;
  };
  for (const Case& c : {Case{HeatPartitionModel::equal, 0.9, 0.5}, Case{HeatPartitionModel::fixed, 0.3, 0.3},
                        Case{HeatPartitionModel::conductivity, 0.9, 10.0 / 60.0},
                        Case{HeatPartitionModel::effusivity, 0.9, e_grain / (e_grain + e_steel)}}) {
    for (const bool every_loss : {false, true}) {
      const Drag d = drag(c.model, c.fixed_share, grain, steel, every_loss);
      SCOPED_TRACE(std::string(to_string(c.model)) + (every_loss ? ", dissipation_heating" : ", friction_heating"));
      EXPECT_NEAR(d.generated_heat_J / d.expected_J, 1.0, 1e-3);
      EXPECT_NEAR(d.wall_heat_J / d.generated_heat_J, 1.0 - c.expected_particle_share, 1e-9);
      EXPECT_NEAR(d.particle_heat_J / d.generated_heat_J, c.expected_particle_share, 1e-6);
    }
  }
}

/// Two equal spheres meeting head on at a closing speed v, no gravity, no friction.
TEST(DissipationHeat, ADampedCollisionHeatsByTheKineticEnergyItLoses) {
  // Heat = the kinetic energy lost within 1 % (the power is integrated at the half-step
  // velocities, an O(dt / contact time) error at ~200 steps per contact), and that
  // loss m* v^2 (1 - e^2) / 2 within 1 % (the discrete rebound matches e to that).
  SphereMaterial m;
  m.restitution = 0.5;
  const double v = 0.2, dt = 0.02 * rayleigh_time_for(m, kRadius);
  SimulationSettings settings = settings_for(kRadius, dt, {}, 0.1);
  settings.heat.enabled = true;
  settings.heat.dissipation_heating = true;
  Simulation sim(one_material(m), WallSet{}, settings);
  sim.add_particle(sphere({-1.05 * kRadius, 0, 0}, {0.5 * v, 0, 0}, kRadius, m.density, 100.0));
  sim.add_particle(sphere({1.05 * kRadius, 0, 0}, {-0.5 * v, 0, 0}, kRadius, m.density, 100.0));
  const double before_J = kinetic_energy_J(sim);
  // Closing 0.1 R at v/2 each, a contact of a few microseconds, and well apart again.
  sim.advance(static_cast<std::uint64_t>(std::ceil(4.0 * 0.1 * kRadius / v / dt)) + 20000);
  ASSERT_EQ(sim.contact_statistics().particle_contacts, 0u);
  const double lost_J = before_J - kinetic_energy_J(sim);
  const double mass = sphere_mass(m, kRadius), effective_mass = 0.5 * mass;
  EXPECT_NEAR(sim.thermal_ledger().generated_heat_J / lost_J, 1.0, 0.01);
  EXPECT_NEAR(lost_J / (0.5 * effective_mass * v * v * (1.0 - m.restitution * m.restitution)), 1.0, 0.01);
  // Half to each (equal spheres), and the books close.
  for (std::size_t i = 0; i < 2; ++i)
    EXPECT_NEAR(mass * m.specific_heat * (sim.particles.temperature_K[i] - 100.0) /
                    (0.5 * sim.thermal_ledger().generated_heat_J),
                1.0, 1e-6);
  EXPECT_LT(std::abs(sim.energy_audit().relative(sim.mechanical_imbalance_J())), 0.01);
}

/// The same oblique impact on a lumped floor that takes half of every loss (equal
/// partition, no conduction): the wall's heat, the grain's heat and their sum.
struct ImpactHeat {
  double generated_J = 0.0, dissipated_J = 0.0, wall_J = 0.0, particle_J = 0.0;
};

constexpr double kFloorCapacity_J_per_K = 1e-9;

ImpactHeat oblique_impact_heat(RollingModel rolling) {
  SphereMaterial m;
  m.restitution = 0.5;
  m.sliding_friction = 0.3;
  m.rolling_friction = 0.05;
  const double dt = 0.02 * rayleigh_time_for(m, kRadius);
  WallSet walls;
  walls.add_plane(walls.add_body("floor", {}), {0, 0, 0}, {0, 0, 1}, 0);
  ThermalWall floor;
  floor.mode = WallThermalMode::lumped;
  floor.initial_temperature_K = 1.0;
  // C = 1e-9 J/K: the ~1e-8 J it takes raises it by kelvins, so its temperature holds the
  // heat to round-off (on C = 1 J/K the rise, 1e-8 K on 1 K, loses 1e-8 of itself).
  floor.heat_capacity_J_per_K = kFloorCapacity_J_per_K;
  floor.conductivity_W_per_mK = 0.0;  // k_c = 0: it takes its share of the heat, conducts none
  SimulationSettings settings = settings_for(kRadius, dt, {}, 0.1);
  settings.heat.enabled = true;
  settings.heat.dissipation_heating = true;
  settings.heat.partition = HeatPartitionModel::equal;
  MaterialTable materials = one_material(m);
  PairProperties pair = materials.pair(0, 0);
  pair.rolling_model = rolling;
  materials.set_pair(0, 0, pair);
  Simulation sim(std::move(materials), walls, settings, {floor});
  NewParticle p = sphere({0, 0, 1.02 * kRadius}, {0.1, 0, -0.1}, kRadius, m.density, 100.0);
  p.angular_velocity_rad_per_s = {0, -300.0, 0};
  sim.add_particle(p);
  sim.advance(3000);
  EXPECT_EQ(sim.contact_statistics().wall_contacts, 0u);  // it has left the floor
  // The floor's heat is read from its temperature (what its node took).
  return {sim.thermal_ledger().generated_heat_J, sim.energy_audit().dissipated_J,
          (sim.wall_thermal_state[0].temperature_K - 1.0) * kFloorCapacity_J_per_K,
          sphere_mass(m, kRadius) * m.specific_heat * (sim.particles.temperature_K[0] - 100.0)};
}

// Equal partition: the floor takes half of every part of the loss, the part the contact
// pass finds at the half-step velocities and velocity Verlet's end-of-step part alike, to
// 1e-9 of the heat (round-off); the grain the other half to 1e-6 (its temperature steps'
// round-off, as in the collision above); every joule lost is heat to 1e-12. (Before, the
// end-of-step part heated the grain alone: the floor took 0.4839 of the heat here, and in
// the tiny heated drill at S = 10 the drill took 18.2 mJ of the 3.27 mJ generated, the
// grains -14.9 mJ.)
TEST(DissipationHeat, AWallTakesItsShareOfEveryPartOfTheLoss) {
  for (const RollingModel rolling : {RollingModel::relative_spin, RollingModel::own_spin}) {
    SCOPED_TRACE(rolling == RollingModel::own_spin ? "own_spin" : "relative_spin");
    const ImpactHeat h = oblique_impact_heat(rolling);
    ASSERT_GT(h.generated_J, 0.0);
    EXPECT_NEAR(h.generated_J / h.dissipated_J, 1.0, 1e-12);
    EXPECT_NEAR(h.wall_J / h.generated_J, 0.5, 1e-9);
    EXPECT_NEAR(h.particle_J / h.generated_J, 0.5, 1e-6);
  }
}

// Only a wall contact's loss reaches the wall: a grain resting on a lossless floor
// (e = 1, no friction, no rolling friction) is struck obliquely by a second grain (e =
// 0.5, friction, rolling friction, either rolling model). Every joule is lost between the
// grains, so the floor, though it takes half of what its own contacts lose, gets nothing:
// below 1e-12 of the heat (round-off), while the heat itself is the grains' loss to 1e-12.
TEST(DissipationHeat, AWallTakesNothingOfItsGrainsOtherContactsLosses) {
  for (const RollingModel rolling : {RollingModel::relative_spin, RollingModel::own_spin}) {
    SCOPED_TRACE(rolling == RollingModel::own_spin ? "own_spin" : "relative_spin");
    SphereMaterial grain;
    grain.restitution = 0.5;
    grain.sliding_friction = 0.3;
    grain.rolling_friction = 0.05;
    SphereMaterial floor_material = grain;
    PairProperties lossless;
    lossless.restitution = 1.0;
    lossless.sliding_friction = 0.0;
    lossless.rolling_friction = 0.0;
    MaterialTable materials = two_materials(grain, floor_material, lossless);
    PairProperties between_grains = materials.pair(0, 0);
    between_grains.rolling_model = rolling;
    materials.set_pair(0, 0, between_grains);
    const double dt = 0.02 * rayleigh_time_for(grain, kRadius);
    WallSet walls;
    walls.add_plane(walls.add_body("floor", {}), {0, 0, 0}, {0, 0, 1}, 1);
    ThermalWall floor;
    floor.mode = WallThermalMode::lumped;
    floor.initial_temperature_K = 1.0;
    floor.heat_capacity_J_per_K = 1.0;
    floor.conductivity_W_per_mK = 0.0;
    SimulationSettings settings = settings_for(kRadius, dt, {}, 0.1);
    settings.heat.enabled = true;
    settings.heat.dissipation_heating = true;
    settings.heat.partition = HeatPartitionModel::equal;
    Simulation sim(std::move(materials), walls, settings, {floor});
    sim.add_particle(sphere({0, 0, 0.99 * kRadius}, {}, kRadius, grain.density, 100.0));  // pressed on the floor
    NewParticle striker = sphere({0.6 * kRadius, 0, 2.7 * kRadius}, {0, 0, -0.2}, kRadius, grain.density, 100.0);
    striker.angular_velocity_rad_per_s = {0, 300.0, 0};
    sim.add_particle(striker);
    sim.advance(4000);
    const double generated_J = sim.thermal_ledger().generated_heat_J;
    ASSERT_GT(generated_J, 0.0);
    EXPECT_NEAR(generated_J / sim.energy_audit().dissipated_J, 1.0, 1e-12);
    EXPECT_LT(std::abs(sim.wall_thermal_state[0].generated_heat_J), 1e-12 * generated_J);
    EXPECT_LT(std::abs(sim.wall_thermal_state[0].temperature_K - 1.0), 1e-12 * generated_J);  // C = 1 J/K
  }
}

/// A sphere strikes a floor at 45 degrees with backspin, slides, sticks, rolls against
/// rolling friction and leaves; returns |mechanical imbalance| / loss at the end.
double oblique_impact_imbalance(double restitution, double step_fraction,
                                RollingModel rolling = RollingModel::relative_spin) {
  SphereMaterial m;
  m.restitution = restitution;
  m.sliding_friction = 0.3;
  m.rolling_friction = 0.05;
  const double dt = step_fraction * rayleigh_time_for(m, kRadius);
  WallSet walls;
  walls.add_plane(walls.add_body("floor", {}), {0, 0, 0}, {0, 0, 1}, 0);
  SimulationSettings settings = settings_for(kRadius, dt, {}, 0.1);
  settings.heat.enabled = true;
  settings.heat.dissipation_heating = true;
  MaterialTable materials = one_material(m);
  PairProperties pair = materials.pair(0, 0);
  pair.rolling_model = rolling;
  materials.set_pair(0, 0, pair);
  Simulation sim(std::move(materials), walls, settings);
  NewParticle p = sphere({0, 0, 1.02 * kRadius}, {0.1, 0, -0.1}, kRadius, m.density, 100.0);
  p.angular_velocity_rad_per_s = {0, -300.0, 0};
  sim.add_particle(p);
  sim.advance(static_cast<std::uint64_t>(std::ceil(3000.0 * 0.02 / step_fraction)));
  EXPECT_EQ(sim.contact_statistics().wall_contacts, 0u);  // it has left the floor
  return std::abs(sim.mechanical_imbalance_J()) / sim.energy_audit().dissipated_J;
}

// A frictional impact with rolling friction, either rolling model, strongly damped or
// not, closes its books within 0.1 % at 0.02 and 0.005 of the Rayleigh step. (With the
// losses at the half-step velocities alone they missed by 0.3 % at e = 0.9 and 3.4 % at
// e = 0.5: velocity Verlet's end-of-step part of them is Simulation::book_end_of_step_losses.)
TEST(EnergyAudit, AFrictionalImpactClosesItsBooks) {
  for (const RollingModel rolling : {RollingModel::relative_spin, RollingModel::own_spin})
    for (const double restitution : {0.5, 0.9})
      for (const double step : {0.02, 0.005}) {
        SCOPED_TRACE(::testing::Message() << (rolling == RollingModel::own_spin ? "own spin" : "relative spin")
                                          << ", e = " << restitution << ", step " << step);
        EXPECT_LT(oblique_impact_imbalance(restitution, step, rolling), 1e-3);
      }
}

/// Two bonded spheres, pulled apart at a relative speed v, no gravity. The bond is far
/// stiffer than the contacts: the step resolves its period as the contact tests resolve
/// theirs (omega dt ~ 0.02).
Simulation bonded_pair(double damping_ratio, double strength_Pa, double v) {
  SphereMaterial m;
  const double dt = 0.002 * rayleigh_time_for(m, kRadius);
  SimulationSettings settings = settings_for(kRadius, dt, {}, 0.1);
  settings.heat.enabled = true;
  settings.heat.dissipation_heating = true;
  Simulation sim(one_material(m), WallSet{}, settings);
  BondParameters bond;
  bond.normal_stiffness_Pa_per_m = 1e12;
  bond.shear_stiffness_Pa_per_m = 4e11;
  bond.tensile_strength_Pa = strength_Pa;
  bond.shear_strength_Pa = strength_Pa;
  bond.damping_ratio = damping_ratio;
  sim.configure_bonds({bond}, {0});
  sim.add_particle(sphere({-1.0 * kRadius, 0, 0}, {-0.5 * v, 0, 0}, kRadius, m.density, 100.0));
  sim.add_particle(sphere({1.0 * kRadius, 0, 0}, {0.5 * v, 0, 0}, kRadius, m.density, 100.0));
  EXPECT_EQ(sim.form_bonds(0.01), 1u);  // before any step: at rest length
  return sim;
}

TEST(DissipationHeat, ADampedBondAndABrokenBondHeatByWhatTheyTake) {
  // Damped (zeta = 0.3, unbreakable): the vibration dies out; heat = the starting
  // kinetic energy within 1 % (what is left vibrating after 60 periods is ~1e-40 of it;
  // the half-step velocities of the damping power are a first-order error, zeta omega dt
  // ~ 0.6 % here: docs/physics.md, "Energy audit").
  {
    Simulation sim = bonded_pair(0.3, 1e12, 0.02);
    const double before_J = kinetic_energy_J(sim);
    sim.advance(20000);
    EXPECT_NEAR(sim.thermal_ledger().generated_heat_J / before_J, 1.0, 0.01);
    EXPECT_LT(std::abs(sim.energy_audit().relative(sim.mechanical_imbalance_J())), 0.01);
  }
  // Undamped and weak: it breaks while stretching; the energy it stored is heat, and
  // equals the kinetic energy the pair lost within 1 %.
  {
    Simulation sim = bonded_pair(0.0, 1e4, 0.02);  // breaks at about a third of the energy it could store
    const double before_J = kinetic_energy_J(sim);
    sim.advance(2000);
    ASSERT_EQ(sim.bond_counts().broken(), 1u);
    const double lost_J = before_J - kinetic_energy_J(sim);
    ASSERT_GT(lost_J, 1e-3 * before_J);
    EXPECT_NEAR(sim.thermal_ledger().generated_heat_J / lost_J, 1.0, 0.01);
    EXPECT_LT(std::abs(sim.mechanical_imbalance_J()) / lost_J, 0.01);
  }
}

// The drilling bed (bonds that break and are damped, the paddle feeding and turning,
// grains falling into the cup, sliding and rolling, a lumped cup and fixed floor and
// paddle) with every loss as heat: the thermal books close to 1e-9 and the heat generated
// is what was dissipated to 1e-9, whichever rolling model; the paddle did work on the
// bed; the mechanical books close within 5 % of the turnover at 0.1 of the Rayleigh step,
// and what is left is the integrator's: at half the step, less than half of it.
struct BedBooks {
  double relative_imbalance = 0.0;
};

BedBooks drilled_bed_books(RollingModel rolling, double rayleigh_fraction) {
  Simulation sim = make_drilling_bed({.dissipation_heating = true,
                                      .partition = HeatPartitionModel::conductivity,
                                      .bond_damping_ratio = 0.1,
                                      .rolling_model = rolling,
                                      .rayleigh_fraction = rayleigh_fraction});
  const double steps_per_base_step = 0.1 / rayleigh_fraction;  // the same simulated time
  sim.advance(static_cast<std::uint64_t>(std::lround(300 * steps_per_base_step)));
  EXPECT_GT(sim.form_bonds(0.05), 20u);
  sim.advance(static_cast<std::uint64_t>(std::lround(1200 * steps_per_base_step)));
  EXPECT_GT(sim.bond_counts().broken(), 0u);
  const EnergyAudit& audit = sim.energy_audit();
  EXPECT_GT(audit.wall_work_by_body_J[2], 0.0);
  EXPECT_LT(std::abs(sim.energy_imbalance_J()) / sim.thermal_energy_J(), 1e-9);
  EXPECT_NEAR(sim.thermal_ledger().generated_heat_J / audit.dissipated_J, 1.0, 1e-9);
  return {audit.relative(sim.mechanical_imbalance_J())};
}

TEST(EnergyAudit, TheDrillingBedTurnsEveryLossIntoHeatAndClosesItsBooks) {
  for (const RollingModel rolling : {RollingModel::relative_spin, RollingModel::own_spin}) {
    SCOPED_TRACE(rolling == RollingModel::own_spin ? "own spin" : "relative spin");
    const BedBooks coarse = drilled_bed_books(rolling, 0.1), fine = drilled_bed_books(rolling, 0.05);
    EXPECT_LT(std::abs(coarse.relative_imbalance), 0.05);
    EXPECT_LT(std::abs(fine.relative_imbalance), 0.5 * std::abs(coarse.relative_imbalance));
  }
}

// The drill as a thermal body (issue 21): the paddle a lumped rod of 4 segments that
// takes its share of every loss, conducts along itself, radiates to 100 K and is held at
// 150 K at its top. Stated before the run: the thermal books close to 1e-9 with what the
// rod radiated and took through its end; the paddle's own heat, sum C_s (T_s - 150 K), is
// what its contacts gave it (generated less conducted out) plus its end's less its
// radiation, to 1e-9 of those flows; it heated above its held end, so its end took heat
// out, and it radiated; the segment that cuts (the tip, 0) is warmer than the held one.
TEST(DrillThermalBody, ASegmentedPaddleKeepsItsBooksAndHeatsAtItsTip) {
  Simulation sim = make_drilling_bed({.dissipation_heating = true,
                                      .partition = HeatPartitionModel::conductivity,
                                      .bond_damping_ratio = 0.1,
                                      .rod_drill = true});
  sim.advance(300);
  EXPECT_GT(sim.form_bonds(0.05), 20u);
  sim.advance(1200);
  EXPECT_LT(std::abs(sim.energy_imbalance_J()) / sim.thermal_energy_J(), 1e-9);
  const ThermalWallState& paddle = sim.wall_thermal_state[2];
  const WallRod& rod = sim.model().wall_thermal[2].rod;
  ASSERT_EQ(paddle.segment_temperature_K.size(), 4u);
  double stored_J = 0.0;
  for (std::size_t s = 0; s < 4; ++s)
    stored_J += rod.segment_heat_capacity_J_per_K[s] * (paddle.segment_temperature_K[s] - 150.0);
  const double flows_J = std::abs(paddle.generated_heat_J) + std::abs(paddle.heat_to_particles_J) +
                         std::abs(paddle.held_end_heat_in_J) + std::abs(paddle.radiated_heat_J);
  EXPECT_NEAR(stored_J,
              paddle.generated_heat_J - paddle.heat_to_particles_J + paddle.held_end_heat_in_J - paddle.radiated_heat_J,
              1e-9 * flows_J);
  EXPECT_GT(paddle.generated_heat_J, 0.0);
  EXPECT_LT(paddle.held_end_heat_in_J, 0.0);
  EXPECT_GT(paddle.radiated_heat_J, 0.0);
  EXPECT_GT(paddle.segment_temperature_K[0], paddle.segment_temperature_K[3]);
  for (double t : paddle.segment_temperature_K) EXPECT_GE(paddle.peak_temperature_K, t);
}

}  // namespace
}  // namespace regodem::testing
