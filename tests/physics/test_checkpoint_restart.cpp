// Checkpoint and restart of a Simulation (issue 8): N steps in one go against N/2
// steps, a checkpoint through its file bytes, a fresh simulation restored from it and
// N/2 more. Positions, velocities, angular velocities, temperatures, contact history
// (particle, wall and mesh springs), bonds and the walls must agree bit for bit, with
// one thread and with two. The bed has what a drilling run has: a lumped cup, a fixed-
// temperature floor, a mesh "drill" that feeds and turns, friction heating and bonds.
// The same bed on 1, 2 and 3 threads must also agree bit for bit (the force pass sums in
// an order that does not depend on the thread count), and so must a checkpoint written
// on 2 threads and resumed on 1 or 3.
#include <gtest/gtest.h>

#include "drilling_bed.hpp"
#include "geometry/triangle_mesh.hpp"
#include "io/checkpoint_file.hpp"

namespace regodem::testing {
namespace {



Simulation make_bed(int threads) { return make_drilling_bed({.threads = threads}); }

struct Phase {
  std::uint64_t settle_steps, bonded_steps;
};

void run_first_part(Simulation& sim, const Phase& phase) {
  sim.advance(phase.settle_steps);
  EXPECT_GT(sim.form_bonds(0.05), 20u);
}

void expect_identical(const Simulation& a, const Simulation& b) {
  ASSERT_EQ(a.particles.size(), b.particles.size());
  EXPECT_EQ(a.time_s(), b.time_s());
  EXPECT_EQ(a.step_count(), b.step_count());
  for (std::size_t i = 0; i < a.particles.size(); ++i) {
    ASSERT_EQ(a.particles.id[i], b.particles.id[i]) << i;
    ASSERT_EQ(a.particles.position_m[i], b.particles.position_m[i]) << "particle " << a.particles.id[i];
    ASSERT_EQ(a.particles.velocity_m_per_s[i], b.particles.velocity_m_per_s[i]) << "particle " << a.particles.id[i];
    ASSERT_EQ(a.particles.angular_velocity_rad_per_s[i], b.particles.angular_velocity_rad_per_s[i]) << i;
    ASSERT_EQ(a.particles.temperature_K[i], b.particles.temperature_K[i]) << "particle " << a.particles.id[i];
    ASSERT_EQ(a.particles.force_N[i], b.particles.force_N[i]) << i;
  }
  const NeighborList &na = a.neighbor_list(), &nb = b.neighbor_list();
  EXPECT_EQ(na.partner, nb.partner);
  ASSERT_EQ(na.tangential_history_m.size(), nb.tangential_history_m.size());
  for (std::size_t k = 0; k < na.tangential_history_m.size(); ++k)
    ASSERT_EQ(na.tangential_history_m[k], nb.tangential_history_m[k]) << "pair entry " << k;
  ASSERT_EQ(na.wall_tangential_history_m.size(), nb.wall_tangential_history_m.size());
  for (std::size_t k = 0; k < na.wall_tangential_history_m.size(); ++k)
    ASSERT_EQ(na.wall_tangential_history_m[k], nb.wall_tangential_history_m[k]) << "wall entry " << k;
  ASSERT_EQ(na.mesh_tangential_history_m.size(), nb.mesh_tangential_history_m.size());
  for (std::size_t k = 0; k < na.mesh_tangential_history_m.size(); ++k)
    ASSERT_EQ(na.mesh_tangential_history_m[k], nb.mesh_tangential_history_m[k]) << "mesh entry " << k;
  EXPECT_EQ(na.rebuild_count(), nb.rebuild_count());
  for (std::size_t w = 0; w < a.wall_thermal_state.size(); ++w) {
    EXPECT_EQ(a.wall_thermal_state[w].temperature_K, b.wall_thermal_state[w].temperature_K) << w;
    EXPECT_EQ(a.wall_thermal_state[w].heat_to_particles_J, b.wall_thermal_state[w].heat_to_particles_J) << w;
    EXPECT_EQ(a.wall_thermal_state[w].segment_temperature_K, b.wall_thermal_state[w].segment_temperature_K) << w;
    EXPECT_EQ(a.wall_thermal_state[w].radiated_heat_J, b.wall_thermal_state[w].radiated_heat_J) << w;
    EXPECT_EQ(a.wall_thermal_state[w].held_end_heat_in_J, b.wall_thermal_state[w].held_end_heat_in_J) << w;
    EXPECT_EQ(a.walls.bodies[w].pose.translation_m, b.walls.bodies[w].pose.translation_m) << w;
    EXPECT_EQ(a.walls.bodies[w].pose.rotation, b.walls.bodies[w].pose.rotation) << w;
    EXPECT_EQ(a.walls.bodies[w].force_N, b.walls.bodies[w].force_N) << w;
  }
  EXPECT_EQ(a.bonds().id_i, b.bonds().id_i);
  EXPECT_EQ(a.bond_counts().broken(), b.bond_counts().broken());
  for (std::size_t k = 0; k < a.bonds().size(); ++k) {
    ASSERT_EQ(a.bonds().loads_of(k).normal_force_N, b.bonds().loads_of(k).normal_force_N) << "bond " << k;
    ASSERT_EQ(a.bonds().loads_of(k).shear_force_N, b.bonds().loads_of(k).shear_force_N) << "bond " << k;
  }
  EXPECT_EQ(a.thermal_ledger().boundary_heat_in_J, b.thermal_ledger().boundary_heat_in_J);
  EXPECT_EQ(a.thermal_ledger().generated_heat_J, b.thermal_ledger().generated_heat_J);
  EXPECT_EQ(a.energy_audit().wall_work_by_body_J, b.energy_audit().wall_work_by_body_J);
  EXPECT_EQ(a.energy_audit().dissipated_J, b.energy_audit().dissipated_J);
  EXPECT_EQ(a.energy_audit().exchanged_J, b.energy_audit().exchanged_J);
  EXPECT_EQ(a.energy_audit().spring_source_J, b.energy_audit().spring_source_J);
  EXPECT_EQ(a.energy_audit().wall_work_J, b.energy_audit().wall_work_J);
  EXPECT_EQ(a.elastic_energy_J(), b.elastic_energy_J());
  EXPECT_EQ(a.fastest_impact().key, b.fastest_impact().key);
  EXPECT_EQ(a.fastest_impact().approach_speed_m_per_s, b.fastest_impact().approach_speed_m_per_s);
  EXPECT_EQ(a.fastest_impact().wall_body, b.fastest_impact().wall_body);
  EXPECT_EQ(a.fastest_impact().time_s, b.fastest_impact().time_s);
}

void check_restart(int threads, const Phase& phase) {
  Simulation whole = make_bed(threads);
  run_first_part(whole, phase);
  whole.advance(phase.bonded_steps);

  Simulation first = make_bed(threads);
  run_first_part(first, phase);
  first.advance(phase.bonded_steps / 2);
  Checkpoint saved;
  first.save_state(saved);
  const std::string bytes = encode_checkpoint(saved);
  const Checkpoint loaded = decode_checkpoint(bytes, "in memory");

  Simulation resumed = make_bed(threads);  // as `regodem resume` builds it: from the scenario
  resumed.restore_state(loaded);
  resumed.advance(phase.bonded_steps - phase.bonded_steps / 2);

  // The run did what it should test: contacts with every kind of wall, sliding, bonds.
  EXPECT_GT(whole.neighbor_list().rebuild_count(), 2u);
  EXPECT_GT(whole.contact_statistics().particle_contacts, 20u);
  EXPECT_GT(whole.walls.bodies[2].travel_m, 0.0);
  bool mesh_spring = false;
  for (const Vec3& s : whole.neighbor_list().mesh_tangential_history_m) mesh_spring = mesh_spring || s != Vec3{};
  EXPECT_TRUE(mesh_spring) << "the paddle touches no particle";
  EXPECT_GT(whole.bonds().size(), 0u);
  expect_identical(whole, resumed);
}

TEST(CheckpointRestart, OneThreadBitForBit) { check_restart(1, {400, 1200}); }

// Shorter: two threads on a small bed spend most of their time synchronising.
TEST(CheckpointRestart, TwoThreadsBitForBit) { check_restart(2, {300, 400}); }

TEST(ThreadCount, OneTwoAndThreeThreadsRunBitForBitAlike) {
  const Phase phase{300, 500};
  Simulation one = make_bed(1), two = make_bed(2), three = make_bed(3);
  for (Simulation* sim : {&one, &two, &three}) {
    run_first_part(*sim, phase);
    sim->advance(phase.bonded_steps);
  }
  EXPECT_EQ(two.force_pass_threads(), 2);
  EXPECT_EQ(three.force_pass_threads(), 3);
  EXPECT_GT(one.bond_counts().broken(), 0u);  // the paddle broke bonds: every pass was exercised
  expect_identical(one, two);
  expect_identical(one, three);
}

// Every loss as heat, shared by effusivity, with damped bonds and EDEM's own-spin rolling,
// and the paddle a lumped rod of segments: the passes that only dissipation heating and a
// segmented wall take, on 1, 2 and 3 threads.
Simulation make_dissipating_bed(int threads) {
  return make_drilling_bed({.threads = threads,
                            .dissipation_heating = true,
                            .partition = HeatPartitionModel::effusivity,
                            .bond_damping_ratio = 0.2,
                            .rolling_model = RollingModel::own_spin,
                            .rod_drill = true});
}

TEST(ThreadCount, DissipationHeatingRunsBitForBitAlike) {
  const Phase phase{300, 400};
  const auto bed = make_dissipating_bed;
  Simulation one = bed(1), two = bed(2), three = bed(3);
  for (Simulation* sim : {&one, &two, &three}) {
    run_first_part(*sim, phase);
    sim->advance(phase.bonded_steps);
  }
  EXPECT_EQ(three.force_pass_threads(), 3);
  EXPECT_GT(one.bond_counts().broken(), 0u);
  EXPECT_GT(one.thermal_ledger().generated_heat_J, 0.0);
  expect_identical(one, two);
  expect_identical(one, three);
}

/// A bed run whole on 2 threads against the same bed checkpointed half-way and resumed
/// on each of `resume_threads`; returns the whole run.
Simulation expect_resumed_alike(Simulation (*bed)(int), std::initializer_list<int> resume_threads) {
  const Phase phase{300, 400};
  Simulation whole = bed(2);
  run_first_part(whole, phase);
  whole.advance(phase.bonded_steps);

  Simulation first = bed(2);
  run_first_part(first, phase);
  first.advance(phase.bonded_steps / 2);
  Checkpoint saved;
  first.save_state(saved);
  const Checkpoint loaded = decode_checkpoint(encode_checkpoint(saved), "in memory");
  for (const int threads : resume_threads) {
    Simulation resumed = bed(threads);
    resumed.restore_state(loaded);
    resumed.advance(phase.bonded_steps - phase.bonded_steps / 2);
    EXPECT_EQ(resumed.force_pass_threads(), threads);
    expect_identical(whole, resumed);
  }
  return whole;
}

TEST(ThreadCount, ACheckpointFromTwoThreadsGoesOnBitForBitOnOneAndThree) { expect_resumed_alike(make_bed, {1, 3}); }

// The segmented paddle's temperatures, and the heat its rod radiated and took through
// its held end, go on from a checkpoint as if never stopped.
TEST(CheckpointRestart, ASegmentedDrillGoesOnBitForBit) {
  const Simulation whole = expect_resumed_alike(make_dissipating_bed, {1});
  ASSERT_EQ(whole.wall_thermal_state[2].segment_temperature_K.size(), 4u);
  EXPECT_NE(whole.wall_thermal_state[2].segment_temperature_K[0], 150.0);
}

TEST(CheckpointRestart, SavingDoesNotDisturbTheRun) {
  Simulation a = make_bed(1), b = make_bed(1);
  a.advance(300);
  Checkpoint c;
  a.save_state(c);
  a.advance(300);
  b.advance(600);
  expect_identical(a, b);
}

TEST(CheckpointRestart, AnotherWallLayoutIsRefused) {
  Simulation a = make_bed(1);
  a.advance(10);
  Checkpoint c;
  a.save_state(c);
  SphereMaterial m;
  WallSet walls;
  walls.add_plane(walls.add_body("floor", {}), {0, 0, -0.004}, {0, 0, 1}, 0);
  Simulation other(one_material(m), walls, a.settings(), {});
  try {
    other.restore_state(decode_checkpoint(encode_checkpoint(c), "x.ckpt"));
    FAIL() << "restored into other walls";
  } catch (const CheckpointError& e) {
    EXPECT_NE(std::string(e.what()).find("x.ckpt"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("wall"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace regodem::testing
