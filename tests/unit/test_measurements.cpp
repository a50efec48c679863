// Measurements on hand-placed particles with known temperatures and positions: region
// statistics, the paper's bands (T_in, T_out, T_d, Eq. 3-5), profiles (Figs. 3, 13a), a
// region riding on a moving wall, and the thermal history on a prescribed path.
// Sums of a few exact binary fractions: expected values are exact to 1e-12 K.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "measure/measure_region.hpp"
#include "measure/temperature_profile.hpp"
#include "measure/thermal_history.hpp"
#include "sim/measurement_runner.hpp"
#include "sim/simulation.hpp"

namespace regodem {
namespace {

constexpr double kTolerance_K = 1e-12;

ParticleStore store_of(const std::vector<std::pair<Vec3, double>>& particles) {
  ParticleStore store;
  for (const auto& [x, t] : particles) {
    NewParticle p;
    p.position_m = x;
    p.radius_m = 1e-4;
    p.density_kg_per_m3 = 1000.0;
    p.temperature_K = t;
    store.add(p);
  }
  return store;
}

TEST(MeasureRegion, CylinderCountsCentresInsideWithMeanMinMax) {
  // Three inside (r = 0, 3 mm, 5 mm at z = 1..9 mm), three outside (r 6 mm, z -1 mm, z 11 mm).
  const ParticleStore p = store_of({{{0, 0, 0.001}, 100.0},
                                    {{0.003, 0, 0.005}, 200.0},
                                    {{0, -0.005, 0.009}, 330.0},
                                    {{0.006, 0, 0.005}, 1000.0},
                                    {{0, 0, -0.001}, 1000.0},
                                    {{0, 0, 0.011}, 1000.0}});
  MeasureRegion r;
  r.shape = MeasureShape::cylinder;
  r.radius_m = 0.005;
  r.length_m = 0.010;
  const TemperatureStatistics s = region_statistics(p, r);
  EXPECT_EQ(s.count, 3u);
  EXPECT_NEAR(s.mean_K, 210.0, kTolerance_K);
  EXPECT_EQ(s.min_K, 100.0);
  EXPECT_EQ(s.max_K, 330.0);
}

TEST(MeasureRegion, AnnulusLeavesOutTheHoleAndBoxItsOutside) {
  const ParticleStore p = store_of({{{0.001, 0, 0.001}, 1000.0},   // in the hole (r 1 mm < 2 mm)
                                    {{0.003, 0, 0.001}, 150.0},    // r 3 mm
                                    {{0, 0.0035, 0.002}, 250.0},   // r 3.5 mm
                                    {{0.005, 0, 0.001}, 1000.0}}); // r 5 mm > 4 mm
  MeasureRegion annulus;
  annulus.shape = MeasureShape::annulus;
  annulus.inner_radius_m = 0.002;
  annulus.radius_m = 0.004;
  annulus.length_m = 0.003;
  const TemperatureStatistics a = region_statistics(p, annulus);
  EXPECT_EQ(a.count, 2u);
  EXPECT_NEAR(a.mean_K, 200.0, kTolerance_K);

  MeasureRegion box;
  box.shape = MeasureShape::box;
  box.min_m = {0.0025, -0.001, 0.0};
  box.max_m = {0.006, 0.001, 0.002};
  const TemperatureStatistics b = region_statistics(p, box);
  EXPECT_EQ(b.count, 2u);  // x = 3 mm and 5 mm
  EXPECT_NEAR(b.mean_K, 575.0, kTolerance_K);
}

TEST(MeasureRegion, EmptyRegionHasCountZeroAndNaNTemperatures) {
  const ParticleStore p = store_of({{{1, 1, 1}, 100.0}});
  MeasureRegion r;
  r.shape = MeasureShape::cylinder;
  r.radius_m = 0.001;
  r.length_m = 0.001;
  const TemperatureStatistics s = region_statistics(p, r);
  EXPECT_EQ(s.count, 0u);
  EXPECT_TRUE(std::isnan(s.mean_K));
  EXPECT_TRUE(std::isnan(s.crossed_fraction()));
}

// The paper's matching cell: T_in and T_out within 2 mm on each side of a sieve disk
// 10 mm from the heat source (Eq. 3-5). Hot side: z < 10 mm (behind the +z normal).
TEST(BandTemperatures, PlaneBandsGiveTinToutAndTheirDifference) {
  const ParticleStore p = store_of({{{0, 0, 0.0085}, 400.0},   // 1.5 mm behind: in
                                    {{0, 0, 0.0095}, 500.0},   // 0.5 mm behind: in
                                    {{0, 0, 0.0070}, 900.0},   // 3 mm behind: neither
                                    {{0, 0, 0.0105}, 250.0},   // 0.5 mm in front: out
                                    {{0, 0, 0.0115}, 150.0},   // 1.5 mm in front: out
                                    {{0.02, 0, 0.0105}, 0.0}});  // beyond the disk's 15 mm radius
  const Vec3 point{0, 0, 0.010}, normal{0, 0, 1};
  const BandTemperatures b = band_temperatures(p, plane_band(point, normal, 0.002, false, 0.015),
                                               plane_band(point, normal, 0.002, true, 0.015));
  EXPECT_EQ(b.in.count, 2u);
  EXPECT_EQ(b.out.count, 2u);
  EXPECT_NEAR(b.in.mean_K, 450.0, kTolerance_K);
  EXPECT_NEAR(b.out.mean_K, 200.0, kTolerance_K);
  EXPECT_NEAR(b.difference_K(), 250.0, kTolerance_K);
}

// The drilling sieve: a cylinder of radius 11 mm; T_in inside (r 9..11 mm), T_out
// outside (r 11..13 mm), only along its length.
TEST(BandTemperatures, CylinderBandsSplitAtTheSurfaceRadius) {
  const ParticleStore p = store_of({{{0.010, 0, 0.05}, 300.0},    // r 10 mm: in
                                    {{0, 0.0095, 0.05}, 320.0},   // r 9.5 mm: in
                                    {{0.005, 0, 0.05}, 999.0},    // r 5 mm: too far in
                                    {{0.012, 0, 0.05}, 200.0},    // r 12 mm: out
                                    {{0.012, 0, 0.15}, 999.0}});  // above the sieve's 120 mm
  const BandTemperatures b =
      band_temperatures(p, cylinder_band({0, 0, 0}, {0, 0, 1}, 0.011, 0.120, 0.002, false),
                        cylinder_band({0, 0, 0}, {0, 0, 1}, 0.011, 0.120, 0.002, true));
  EXPECT_EQ(b.in.count, 2u);
  EXPECT_EQ(b.out.count, 1u);
  EXPECT_NEAR(b.in.mean_K, 310.0, kTolerance_K);
  EXPECT_NEAR(b.difference_K(), 110.0, kTolerance_K);
}

TEST(TemperatureProfile, DistanceFromAPlaneInBins) {
  // Bins of 1 mm over [0, 3 mm]: [0,1) holds 100 and 200, [1,2) none, [2,3] holds 400.
  const ParticleStore p = store_of({{{0, 0, 0.0002}, 100.0},
                                    {{0.01, 0.01, 0.0008}, 200.0},
                                    {{0, 0, 0.0025}, 400.0},
                                    {{0, 0, 0.0040}, 999.0},
                                    {{0, 0, -0.0001}, 999.0}});
  ProfileGeometry g;
  g.coordinate = ProfileCoordinate::plane_distance;
  g.direction = {0, 0, 1};
  g.min_m = 0.0;
  g.max_m = 0.003;
  g.bin_m = 0.001;
  ASSERT_EQ(g.bin_count(), 3u);
  EXPECT_NEAR(g.bin_centre_m(1), 0.0015, 1e-15);
  const std::vector<TemperatureStatistics> bins = temperature_profile(p, g);
  ASSERT_EQ(bins.size(), 3u);
  EXPECT_EQ(bins[0].count, 2u);
  EXPECT_NEAR(bins[0].mean_K, 150.0, kTolerance_K);
  EXPECT_EQ(bins[1].count, 0u);
  EXPECT_TRUE(std::isnan(bins[1].mean_K));
  EXPECT_EQ(bins[2].count, 1u);
  EXPECT_NEAR(bins[2].mean_K, 400.0, kTolerance_K);
}

TEST(TemperatureProfile, RadiusFromAnAxisWithinADepthSlab) {
  // Axis down from the surface at z = 100 mm; the slab 24..26 mm deep (Fig. 13a at 25 mm).
  const ParticleStore p = store_of({{{0.001, 0, 0.075}, 300.0},   // depth 25 mm, r 1 mm
                                    {{0, 0.0015, 0.0755}, 310.0}, // depth 24.5 mm, r 1.5 mm
                                    {{0.003, 0, 0.0745}, 200.0},  // depth 25.5 mm, r 3 mm
                                    {{0.001, 0, 0.070}, 999.0}}); // depth 30 mm: outside the slab
  ProfileGeometry g;
  g.coordinate = ProfileCoordinate::radius;
  g.origin_m = {0, 0, 0.100};
  g.direction = {0, 0, -1};
  g.slab_min_m = 0.024;
  g.slab_max_m = 0.026;
  g.min_m = 0.0;
  g.max_m = 0.004;
  g.bin_m = 0.002;
  const std::vector<TemperatureStatistics> bins = temperature_profile(p, g);
  ASSERT_EQ(bins.size(), 2u);
  EXPECT_EQ(bins[0].count, 2u);
  EXPECT_NEAR(bins[0].mean_K, 305.0, kTolerance_K);
  EXPECT_EQ(bins[1].count, 1u);
  EXPECT_NEAR(bins[1].mean_K, 200.0, kTolerance_K);
}

TEST(TemperatureProfile, LastBinOfARangeThatIsNotWholeBinsIsNarrower) {
  ProfileGeometry g;
  g.min_m = 0.0;
  g.max_m = 0.0025;
  g.bin_m = 0.001;
  EXPECT_EQ(g.bin_count(), 3u);
  EXPECT_NEAR(g.bin_centre_m(2), 0.00225, 1e-15);
}

// T(t) = 150 + 100 sin(pi t / P) K over one period P, sampled at steps dt: above
// 203.15 K for P - 2 (P/pi) asin(53.15/100); the peak is 250 K at t = P/2. The
// threshold time is checked within one step (the bound); with the crossing
// interpolated it is far closer.
TEST(ThermalHistory, TimeAboveThresholdOnAPrescribedPathMatchesTheAnalyticTime) {
  const double period_s = 10.0, dt_s = 0.01, threshold_K = kDefaultThermalThreshold_K;
  const auto path = [&](double t) { return 150.0 + 100.0 * std::sin(std::numbers::pi * t / period_s); };
  double peak_K = path(0.0), above_s = 0.0;
  const int steps = static_cast<int>(std::lround(period_s / dt_s));
  for (int k = 0; k < steps; ++k)
    record_thermal_history(path(k * dt_s), path((k + 1) * dt_s), dt_s, threshold_K, peak_K, above_s);
  const double expected_s = period_s - 2.0 * period_s / std::numbers::pi * std::asin((threshold_K - 150.0) / 100.0);
  EXPECT_NEAR(above_s, expected_s, dt_s);
  EXPECT_NEAR(above_s, expected_s, 1e-3 * dt_s);  // the interpolation of the crossings
  EXPECT_EQ(peak_K, 250.0);                       // t = P/2 is step 500
}

TEST(ThermalHistory, SummaryCountsParticlesThatPeakedAboveTheThreshold) {
  ParticleStore p = store_of({{{0, 0, 0}, 100.0}, {{0, 0, 0}, 150.0}, {{0, 0, 0}, 180.0}, {{0, 0, 0}, 300.0}});
  p.peak_temperature_K = {100.0, 250.0, 180.0, 300.0};
  p.time_above_threshold_s = {0.0, 2.0, 0.0, 6.0};
  const ThermalHistorySummary s = thermal_history_summary(p, 203.15);
  EXPECT_EQ(s.crossed, 2u);
  EXPECT_EQ(s.crossed_fraction(), 0.5);
  EXPECT_EQ(s.peak_temperature_max_K, 300.0);
  EXPECT_EQ(s.time_above_threshold_mean_s, 2.0);
  EXPECT_EQ(s.time_above_threshold_max_s, 6.0);
  // Region statistics count the crossed among the region's particles.
  MeasureRegion all;
  all.shape = MeasureShape::box;
  all.min_m = {-1, -1, -1};
  all.max_m = {1, 1, 1};
  EXPECT_EQ(region_statistics(p, all, {}, 203.15).crossed_fraction(), 0.5);
}

// A run over MPI ranks measures each rank's own particles (the ghosts left out) and merges
// the sums, sent between ranks as doubles: the statistics of all the particles, the same
// bits as one pass over them.
TEST(MeasureRegion, PartialSumsLeaveOutTheFlaggedAndMergeIntoTheWhole) {
  ParticleStore p = store_of({{{0, 0, 0}, 100.1}, {{0, 0, 0}, 150.3}, {{0, 0, 0}, 180.7}, {{0, 0, 0}, 300.9},
                              {{0, 0, 0}, 250.2}});
  p.peak_temperature_K = {100.1, 250.0, 180.7, 300.9, 260.0};
  p.time_above_threshold_s = {0.0, 2.0, 0.0, 6.0, 0.5};
  MeasureRegion all;
  all.shape = MeasureShape::box;
  all.min_m = {-1, -1, -1};
  all.max_m = {1, 1, 1};
  const TemperatureStatistics whole = region_statistics(p, all, {}, 203.15);
  const ThermalHistorySummary whole_history = thermal_history_summary(p, 203.15);
  // "Rank A" holds particles 0, 2, 4 as its own, "rank B" 1 and 3; each sees the others as ghosts.
  const std::vector<std::uint8_t> ghosts_of_a{0, 1, 0, 1, 0}, ghosts_of_b{1, 0, 1, 0, 1};
  const TemperatureAccumulator a = region_sums(p, all, {}, 203.15, ghosts_of_a);
  const TemperatureAccumulator b = region_sums(p, all, {}, 203.15, ghosts_of_b);
  EXPECT_EQ(a.result().count, 3u);
  EXPECT_EQ(b.result().count, 2u);
  std::vector<double> message;
  b.append_to(message);
  a.append_to(message);  // in either order
  thermal_history_sums(p, 203.15, ghosts_of_b).append_to(message);
  thermal_history_sums(p, 203.15, ghosts_of_a).append_to(message);
  std::size_t at = 0;
  TemperatureAccumulator merged = TemperatureAccumulator::read_from(message, at);
  merged.merge(TemperatureAccumulator::read_from(message, at));
  ThermalHistorySums history = ThermalHistorySums::read_from(message, at);
  history.merge(ThermalHistorySums::read_from(message, at));
  EXPECT_EQ(at, message.size());
  const TemperatureStatistics m = merged.result();
  EXPECT_EQ(m.count, whole.count);
  EXPECT_EQ(m.crossed, whole.crossed);
  EXPECT_EQ(m.mean_K, whole.mean_K);
  EXPECT_EQ(m.min_K, 100.1);
  EXPECT_EQ(m.max_K, 300.9);
  const ThermalHistorySummary h = history.result();
  EXPECT_EQ(h.particles, 5u);
  EXPECT_EQ(h.crossed, whole_history.crossed);
  EXPECT_EQ(h.peak_temperature_max_K, 300.9);
  EXPECT_EQ(h.time_above_threshold_mean_s, whole_history.time_above_threshold_mean_s);
  EXPECT_EQ(h.time_above_threshold_max_s, 6.0);
  // An empty partial (a rank without particles in the region) changes nothing.
  TemperatureAccumulator with_empty = merged;
  with_empty.merge(TemperatureAccumulator{});
  EXPECT_EQ(with_empty.result().min_K, 100.1);
  EXPECT_EQ(with_empty.result().count, 5u);
}

TEST(ThermalHistory, FieldsFollowTheParticlesThroughPermutation) {
  ParticleStore p = store_of({{{0, 0, 0}, 100.0}, {{1, 0, 0}, 200.0}});
  p.peak_temperature_K = {111.0, 222.0};
  p.time_above_threshold_s = {1.0, 2.0};
  p.permute({1, 0});
  EXPECT_EQ(p.id[0], 1u);
  EXPECT_EQ(p.peak_temperature_K[0], 222.0);
  EXPECT_EQ(p.time_above_threshold_s[0], 2.0);
}

// A region on a drill fed downwards at 10 mm/s: after 0.5 s it sits 5 mm lower and
// holds the particles there; the depth column is the wall's travel.
TEST(MeasurementRunner, RegionMovesWithATranslatingWall) {
  MaterialTable materials;
  Material grain;
  grain.name = "grain";
  grain.density_kg_per_m3 = 1000.0;
  grain.shear_modulus_Pa = 1e6;
  grain.poisson_ratio = 0.25;
  materials.add(grain);
  materials.set_pair(0, 0, PairProperties{});
  WallSet walls;
  WallMotion feed;
  feed.velocity_m_per_s = {0, 0, -0.01};
  const std::uint32_t drill = walls.add_body("drill", feed);
  walls.add_disk(drill, {0.04, 0.04, 0.04}, {0, 0, 1}, 0.002, 0);  // far from the particles
  SimulationSettings settings;
  settings.domain = {{-0.05, -0.05, -0.05}, {0.05, 0.05, 0.05}};
  settings.gravity_m_per_s2 = {};
  settings.time_step_s = 1e-3;
  settings.neighbor_skin_m = 1e-4;
  settings.min_particle_radius_m = 5e-4;
  Simulation sim(materials, walls, settings);
  for (int k = 0; k < 10; ++k) {  // a column at z = 0.5, 1.5, ..., 9.5 mm, far apart
    NewParticle p;
    p.position_m = {0, 0, 0.0005 + 0.001 * k};
    p.radius_m = 2e-4;
    p.density_kg_per_m3 = 1000.0;
    sim.add_particle(p);
  }
  Measurement m;
  m.name = "near_bit";
  m.kind = MeasurementKind::region;
  m.region.shape = MeasureShape::cylinder;
  m.region.base_m = {0, 0, 0.006};  // 6..10 mm at the start: 4 particles
  m.region.radius_m = 0.001;
  m.region.length_m = 0.004;
  m.follow_body = static_cast<int>(drill);
  m.depth_body = static_cast<int>(drill);
  const MeasurementTable table = measurement_table(m, sim);
  ASSERT_EQ(table.columns.size(), 4u);  // heat off: depth, time, real_time, count
  EXPECT_EQ(table.columns[0].name, "depth");
  EXPECT_EQ(table.columns[2].name, "real_time");
  EXPECT_EQ(table.columns[3].name, "count");
  EXPECT_EQ(measurement_rows(m, sim).at(0).at(3), 4.0);
  for (int s = 0; s < 500; ++s) sim.step();  // 0.5 s: 5 mm down, the region spans 1..5 mm
  const std::vector<std::vector<double>> rows = measurement_rows(m, sim);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_NEAR(rows[0][0], 0.005, 1e-12);
  EXPECT_NEAR(rows[0][1], 0.5, 1e-12);
  EXPECT_EQ(rows[0][2], rows[0][1]);  // S = 1: real time is the simulated time
  EXPECT_EQ(rows[0][3], 4.0);  // z = 1.5, 2.5, 3.5, 4.5 mm
  m.follow_body = -1;
  EXPECT_EQ(measurement_rows(m, sim).at(0).at(3), 4.0);  // fixed: still the particles at 6.5..9.5 mm
  m.region.base_m = {0, 0, 0.0};
  m.region.length_m = 0.0021;
  EXPECT_EQ(measurement_rows(m, sim).at(0).at(3), 2.0);
}

TEST(MeasurementClock, ListedTimesAreTakenOnceEachOnTheFirstStepPastThem) {
  MeasurementSchedule schedule;
  schedule.at_times_s = {0.25, 0.5};
  MeasurementClock clock(schedule);
  int taken = 0;
  for (int k = 0; k <= 10; ++k) {
    const double t = 0.1 * k;
    if (clock.due(t, 0.04, 0.0)) {
      ++taken;
      EXPECT_TRUE(k == 3 || k == 5) << k;  // 0.3 s (first at or past 0.25 s) and 0.5 s
      clock.taken(t, 0.04, 0.0);
    }
  }
  EXPECT_EQ(taken, 2);
  EXPECT_FALSE(clock.due_at_stage_end(1.0));
}

TEST(MeasurementClock, EveryDepthReusesTheSnapshotTrigger) {
  MeasurementSchedule schedule;
  schedule.periodic.trigger = SnapshotSchedule::Trigger::depth;
  schedule.periodic.depth_interval_m = 0.001;
  MeasurementClock clock(schedule);
  int taken = 0;
  for (int k = 0; k <= 100; ++k) {  // 0.1 mm per step to 10 mm: at 0, 1, ..., 10 mm
    const double depth = 1e-4 * k;
    if (clock.due(k * 0.01, 0.005, depth)) {
      ++taken;
      clock.taken(k * 0.01, 0.005, depth);
    }
    clock.count_step();
  }
  EXPECT_EQ(taken, 11);
}

}  // namespace
}  // namespace regodem
