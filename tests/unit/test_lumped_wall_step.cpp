// A lumped wall's own heat paths (thermal/lumped_wall_step.hpp) against their analytic
// solutions, and a mesh cut along its axis (geometry/mesh_axial_segments.hpp). The
// tolerances are set from explicit Euler's error, n (G dt / C)^2 / 2 of the exponent.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/error.hpp"
#include "geometry/mesh_axial_segments.hpp"
#include "thermal/lumped_wall_step.hpp"

namespace regodem {
namespace {

std::vector<double> run(std::vector<double> temperature_K, const std::vector<double>& capacity,
                        const std::vector<double>& area, const std::vector<double>& contact_W, const WallRod& rod,
                        double dt_s, int steps, WallBoundaryHeat* total = nullptr, double time_scale = 1.0) {
  for (int k = 0; k < steps; ++k) {
    const WallBoundaryHeat h = step_lumped_wall(temperature_K, capacity, area, contact_W, rod, dt_s, time_scale);
    if (total) {
      total->radiated_J += h.radiated_J;
      total->held_end_in_J += h.held_end_in_J;
    }
  }
  return temperature_K;
}

TEST(LumpedWallStep, OneNodeWithNoExchangesIsTheOldUpdate) {
  std::vector<double> t{100.0};
  const double q = 0.3, dt = 1e-3, c = 0.7;
  step_lumped_wall(t, std::vector<double>{c}, std::vector<double>{0.0}, std::vector<double>{q}, WallRod{}, dt, 1.0);
  EXPECT_EQ(t[0], 100.0 + q * dt / c);
}

// C dT/dt = G_h (T_h - T): T_h + (T0 - T_h) exp(-G_h t / C); at t = C / G_h, 1e-3 of
// the initial difference (G dt / C = 1e-3 over 1000 steps: 5e-4 in the exponent).
TEST(LumpedWallStep, AHeldEndRelaxesTheNodeExponentially) {
  WallRod rod;
  rod.held_end_K = 200.0;
  rod.held_end_conductance_W_per_K = 2.0;
  const double c = 4.0, tau = c / 2.0, dt = tau * 1e-3;
  WallBoundaryHeat heat;
  const auto t = run({100.0}, {c}, {0.0}, {0.0}, rod, dt, 1000, &heat);
  const double expected = 200.0 - 100.0 * std::exp(-1.0);
  EXPECT_NEAR(t[0], expected, 1e-3 * 100.0);
  EXPECT_NEAR(heat.held_end_in_J, c * (t[0] - 100.0), 1e-12 * c * 100.0);  // all of it came through the end
}

// Two linked nodes: C1 T1 + C2 T2 is kept to round-off, and T1 - T2 decays as
// exp(-G (1/C1 + 1/C2) t): 1e-3 of the initial difference after one time constant.
TEST(LumpedWallStep, TwoLinkedNodesShareTheirHeatAndRelax) {
  WallRod rod;
  rod.link_conductance_W_per_K = 0.5;
  rod.segment_heat_capacity_J_per_K = {1.0, 3.0};
  rod.segment_area_m2 = {0.0, 0.0};
  const double rate = 0.5 * (1.0 / 1.0 + 1.0 / 3.0), dt = 1e-3 / rate;
  const auto t = run({300.0, 100.0}, {1.0, 3.0}, {0.0, 0.0}, {0.0, 0.0}, rod, dt, 1000);
  EXPECT_NEAR(1.0 * t[0] + 3.0 * t[1], 600.0, 1e-12 * 600.0);
  EXPECT_NEAR(t[0] - t[1], 200.0 * std::exp(-1.0), 1e-3 * 200.0);
}

// Radiation to 0 K: C dT/dt = -eps sigma A T^4, so 1/T^3 = 1/T0^3 + 3 eps sigma A t / C.
// Run until T0 / 2 by the formula; 1e-3 of T0 (the step takes 1e-4 of T per step).
TEST(LumpedWallStep, RadiationToColdSpaceCoolsAsTheQuarticLaw) {
  WallRod rod;
  rod.emissivity = 0.8;
  rod.surroundings_K = 0.0;
  const double c = 1.0, area = 0.01, t0 = 400.0;
  const double b = rod.emissivity * kStefanBoltzmann_W_per_m2K4 * area;
  const double t_end = (1.0 / std::pow(t0 / 2, 3) - 1.0 / std::pow(t0, 3)) * c / (3.0 * b);
  const int steps = 20000;
  WallBoundaryHeat heat;
  const auto t = run({t0}, {c}, {area}, {0.0}, rod, t_end / steps, steps, &heat);
  EXPECT_NEAR(t[0], t0 / 2, 1e-3 * t0);
  EXPECT_NEAR(heat.radiated_J, c * (t0 - t[0]), 1e-12 * c * t0);  // what it lost went out as radiation
}

// Radiation to surroundings at T_a: C dT/dt = -eps sigma A (T^4 - T_a^4), whose solution
// is F(T) = F(T0) - eps sigma A t / C with F(T) = [ln((T - T_a)/(T + T_a)) - 2 atan(T/T_a)]
// / (4 T_a^3). From 400 K to 250 K with T_a = 200 K: 1e-3 of T0, as above. A node at the
// surroundings' temperature neither cools nor warms (a wrong sign of T_a^4 would cool it
// by tens of kelvin here).
TEST(LumpedWallStep, RadiationToWarmSurroundingsFollowsTheExactQuarticLaw) {
  WallRod rod;
  rod.emissivity = 0.8;
  rod.surroundings_K = 200.0;
  const double c = 1.0, area = 0.01, t0 = 400.0, t1 = 250.0, ta = rod.surroundings_K;
  const double b = rod.emissivity * kStefanBoltzmann_W_per_m2K4 * area / c;
  const auto f = [ta](double t) { return (std::log((t - ta) / (t + ta)) - 2.0 * std::atan(t / ta)) / (4 * ta * ta * ta); };
  const double t_end = (f(t0) - f(t1)) / b;
  const int steps = 20000;
  WallBoundaryHeat heat;
  const auto t = run({t0}, {c}, {area}, {0.0}, rod, t_end / steps, steps, &heat);
  EXPECT_NEAR(t[0], t1, 1e-3 * t0);
  EXPECT_NEAR(heat.radiated_J, c * (t0 - t[0]), 1e-12 * c * t0);
  WallBoundaryHeat none;
  const auto still = run({ta}, {c}, {area}, {0.0}, rod, t_end / steps, steps, &none);
  EXPECT_NEAR(still[0], ta, 1e-9 * ta);
  EXPECT_NEAR(none.radiated_J, 0.0, 1e-12 * c * t0);
}

// Every exchange of the wall (the links, the held end, radiation) runs S times faster at
// a time-scale factor S, as the contact conductances do; the contacts' heat is passed in
// already scaled and is not scaled again. So S = 20 over t / 20 ends where S = 1 ends
// over t, to round-off: each step has the same increments (G S)(dt / S). A third node
// heated by its contacts gains Q dt / C a step whatever S is.
TEST(LumpedWallStep, EveryExchangeRunsSTimesFasterAtATimeScaleFactor) {
  WallRod rod;
  rod.link_conductance_W_per_K = 0.5;
  rod.held_end_K = 150.0;
  rod.held_end_conductance_W_per_K = 2.0;
  rod.emissivity = 0.5;
  rod.surroundings_K = 40.0;
  const std::vector<double> capacity{1.0, 2.0, 3.0}, area{0.01, 0.01, 0.01}, no_contacts{0.0, 0.0, 0.0};
  const std::vector<double> start{300.0, 200.0, 100.0};
  const double dt = 1e-4;
  WallBoundaryHeat real, compressed;
  const auto t1 = run(start, capacity, area, no_contacts, rod, dt, 2000, &real, 1.0);
  const auto t20 = run(start, capacity, area, no_contacts, rod, dt / 20.0, 2000, &compressed, 20.0);
  for (int s = 0; s < 3; ++s) EXPECT_NEAR(t20[s], t1[s], 1e-12 * 300.0) << "node " << s;
  EXPECT_NEAR(compressed.radiated_J, real.radiated_J, 1e-12 * std::abs(real.radiated_J));
  EXPECT_NEAR(compressed.held_end_in_J, real.held_end_in_J, 1e-12 * std::abs(real.held_end_in_J));
  EXPECT_GT(std::abs(t1[0] - start[0]), 1.0);  // the exchanges did act
  // The contacts' heat: one isolated node, S = 20, 100 steps of Q dt / C.
  const auto heated = run({100.0}, {2.0}, {0.0}, {0.5}, WallRod{}, 1e-3, 100, nullptr, 20.0);
  EXPECT_NEAR(heated[0], 100.0 + 100 * 0.5 * 1e-3 / 2.0, 1e-12 * 100.0);
}

// A rod heated at its tip (node 0) and held at its far end: the steady state is
// T_s = T_h + Q (1 / G_h + (N - 1 - s) / G), as resistances in series. Run 50 slowest
// time constants (an upper bound C N^2 / G): 1e-6 of the rise.
TEST(LumpedWallStep, ARodHeatedAtItsTipHoldsTheSeriesResistanceProfile) {
  constexpr int n = 5;
  WallRod rod;
  rod.link_conductance_W_per_K = 1.0;
  rod.held_end_K = 150.0;
  rod.held_end_conductance_W_per_K = 2.0;
  rod.segment_heat_capacity_J_per_K.assign(n, 0.2);
  rod.segment_area_m2.assign(n, 0.0);
  const double q = 3.0;
  std::vector<double> contact(n, 0.0);
  contact[0] = q;
  const double dt = 0.2 * lumped_wall_stability_limit_s(rod.segment_heat_capacity_J_per_K, rod, 1.0);
  const int steps = static_cast<int>(50.0 * 0.2 * n * n / 1.0 / dt);
  const auto t = run(std::vector<double>(n, 150.0), rod.segment_heat_capacity_J_per_K, rod.segment_area_m2, contact,
                     rod, dt, steps);
  const double rise = q * (1.0 / 2.0 + (n - 1) / 1.0);
  for (int s = 0; s < n; ++s)
    EXPECT_NEAR(t[s], 150.0 + q * (1.0 / 2.0 + (n - 1 - s) / 1.0), 1e-6 * rise) << "segment " << s;
}

TEST(LumpedWallStep, AStepTooLongForTheRadiationIsRefused) {
  WallRod rod;
  rod.emissivity = 1.0;
  std::vector<double> t{3000.0};
  EXPECT_THROW(step_lumped_wall(t, std::vector<double>{1e-6}, std::vector<double>{1.0}, std::vector<double>{0.0}, rod,
                                1e-3, 1.0),
               SimulationError);
}

TEST(LumpedWallStep, TheStabilityLimitIsTheLightestNodesCapacityOverItsConductances) {
  WallRod rod;
  rod.link_conductance_W_per_K = 2.0;
  rod.held_end_K = 100.0;
  rod.held_end_conductance_W_per_K = 4.0;
  // Nodes: 1 (one link), 1 (two links), 3 (a link and the held end): 1/2, 1/4, 3/6.
  EXPECT_DOUBLE_EQ(lumped_wall_stability_limit_s(std::vector<double>{1.0, 1.0, 3.0}, rod, 1.0), 0.25);
  EXPECT_DOUBLE_EQ(lumped_wall_stability_limit_s(std::vector<double>{1.0, 1.0, 3.0}, rod, 10.0), 0.025);
}

// The unit cube cut in two along z: the bottom and the lower triangle of each side in
// the first slice, the top and the upper ones in the second: 3 m^2 each.
TEST(MeshAxialSegments, AUnitCubeCutInTwoAlongItsHeight) {
  TriangleMesh cube;
  cube.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  cube.triangles = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                    {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  const MeshAxialSegments cut = split_mesh_along_axis(cube, {0, 0, 2}, 2);
  EXPECT_DOUBLE_EQ(cut.length_m, 1.0);
  ASSERT_EQ(cut.area_m2.size(), 2u);
  EXPECT_DOUBLE_EQ(cut.area_m2[0], 3.0);
  EXPECT_DOUBLE_EQ(cut.area_m2[1], 3.0);
  EXPECT_EQ(cut.triangle_segment[0], 0);  // bottom
  EXPECT_EQ(cut.triangle_segment[2], 1);  // top
  // Upside down, the top is the first slice.
  EXPECT_EQ(split_mesh_along_axis(cube, {0, 0, -1}, 2).triangle_segment[2], 0);
  EXPECT_THROW(split_mesh_along_axis(cube, {0, 0, 1}, 7), InputError);  // a slice with no triangle
  EXPECT_THROW(split_mesh_along_axis(cube, {0, 0, 0}, 2), InputError);
}

}  // namespace
}  // namespace regodem
