#include "sim/measurement_runner.hpp"

#include <fmt/format.h>

#include <array>
#include <limits>
#include <optional>
#include <span>
#include <stdexcept>

#include "measure/temperature_profile.hpp"
#include "measure/thermal_history.hpp"
#include "sim/simulation.hpp"
#include "sim/time_scale.hpp"

namespace regodem {
namespace {

Vec3 offset_of(const Simulation& sim, const Measurement& m) {
  return m.follow_body >= 0 ? sim.walls.bodies[static_cast<std::size_t>(m.follow_body)].displacement_m : Vec3{};
}

std::optional<double> threshold_of(const Simulation& sim) {
  const HeatSettings& heat = sim.settings().heat;
  if (!heat.enabled || !heat.track_thermal_history) return std::nullopt;
  return heat.thermal_history_threshold_K;
}

void add_temperatures(std::vector<double>& row, const TemperatureStatistics& s) {
  row.insert(row.end(), {s.mean_K, s.min_K, s.max_K});
}

// Each rank's own particles summed, the sums merged over the ranks (sim.merge_over_ranks):
// one process's statistics, the same bits on any rank count.
TemperatureStatistics region_over_ranks(const Simulation& sim, const MeasureRegion& region, const Vec3& offset,
                                        std::optional<double> threshold_K = std::nullopt) {
  TemperatureAccumulator sums = region_sums(sim.particles, region, offset, threshold_K, sim.left_out());
  sim.merge_over_ranks(std::span<TemperatureAccumulator>(&sums, 1));
  return sums.result();
}

BandTemperatures band_over_ranks(const Simulation& sim, const Measurement& m, const Vec3& offset) {
  BandSums sums = band_sums(sim.particles, m.band_in, m.band_out, offset, sim.left_out());
  std::array<TemperatureAccumulator, 2> both{sums.in, sums.out};
  sim.merge_over_ranks(std::span<TemperatureAccumulator>(both));
  return {both[0].result(), both[1].result()};
}

}  // namespace

MeasurementTable measurement_table(const Measurement& m, const Simulation& sim) {
  MeasurementTable table;
  table.name = m.name;
  table.kind = m.kind == MeasurementKind::region ? "region" : m.kind == MeasurementKind::band ? "band" : "profile";
  table.folder = m.kind == MeasurementKind::profile ? "profiles" : "regions";
  std::vector<SeriesColumn>& c = table.columns;
  const bool heat = sim.heat_enabled();
  const bool depth = m.depth_body >= 0;
  const std::vector<SeriesColumn> temperatures{
      {"temperature_mean", "K"}, {"temperature_min", "K"}, {"temperature_max", "K"}};
  switch (m.kind) {
    case MeasurementKind::region:
      // Against depth first where there is one: the paper's Fig. 14 plots the chip zone so.
      if (depth) c.push_back({"depth", "m"});
      c.insert(c.end(), {{"time", "s"}, {"real_time", "s"}});
      if (heat) c.insert(c.end(), temperatures.begin(), temperatures.end());
      c.push_back({"count", "-"});
      if (threshold_of(sim)) c.push_back({"crossed_threshold_fraction", "-"});
      break;
    case MeasurementKind::band:
      if (depth) c.push_back({"depth", "m"});
      c.insert(c.end(), {{"time", "s"}, {"real_time", "s"}, {"T_in", "K"}, {"T_out", "K"}, {"T_d", "K"}, {"count_in", "-"},
                         {"count_out", "-"}});
      break;
    case MeasurementKind::profile:
      // Long form, one row per bin and instant: rows of one instant share their time.
      c.insert(c.end(), {{"time", "s"}, {"real_time", "s"}});
      if (depth) c.push_back({"depth", "m"});
      c.push_back({m.profile.coordinate == ProfileCoordinate::radius ? "radius" : "distance", "m"});
      if (heat) c.insert(c.end(), temperatures.begin(), temperatures.end());
      c.push_back({"count", "-"});
      break;
  }
  return table;
}

double measured_value(const Measurement& m, const Simulation& sim, MeasuredQuantity quantity) {
  const Vec3 offset = offset_of(sim, m);
  if (m.kind == MeasurementKind::band) {
    const BandTemperatures b = band_over_ranks(sim, m, offset);
    return quantity == MeasuredQuantity::T_in    ? b.in.mean_K
           : quantity == MeasuredQuantity::T_out ? b.out.mean_K
                                                 : b.difference_K();
  }
  const TemperatureStatistics s = region_over_ranks(sim, m.region, offset);
  return quantity == MeasuredQuantity::min ? s.min_K : quantity == MeasuredQuantity::max ? s.max_K : s.mean_K;
}

bool target_reached(const MeasurementPlan& plan, const MeasurementTarget& target, const Simulation& sim) {
  const double value = measured_value(plan.items[target.measurement], sim, target.quantity);
  return target.rising ? value >= target.value_K : value <= target.value_K;
}

std::vector<std::vector<double>> measurement_rows(const Measurement& m, const Simulation& sim) {
  const bool heat = sim.heat_enabled();
  const Vec3 offset = offset_of(sim, m);
  std::vector<double> lead;  // depth, time and real time, in the table's order
  const double depth =
      m.depth_body >= 0 ? sim.walls.bodies[static_cast<std::size_t>(m.depth_body)].depth_m() : 0.0;
  if (m.depth_body >= 0 && m.kind != MeasurementKind::profile) lead.push_back(depth);
  lead.push_back(sim.time_s());
  lead.push_back(TimeScale{sim.settings().heat.time_scale_factor}.real_time_s(sim.time_s()));
  if (m.depth_body >= 0 && m.kind == MeasurementKind::profile) lead.push_back(depth);

  std::vector<std::vector<double>> rows;
  switch (m.kind) {
    case MeasurementKind::region: {
      const std::optional<double> threshold = threshold_of(sim);
      const TemperatureStatistics s = region_over_ranks(sim, m.region, offset, threshold);
      std::vector<double> row = lead;
      if (heat) add_temperatures(row, s);
      row.push_back(static_cast<double>(s.count));
      if (threshold) row.push_back(s.crossed_fraction());
      rows.push_back(std::move(row));
      break;
    }
    case MeasurementKind::band: {
      const BandTemperatures b = band_over_ranks(sim, m, offset);
      std::vector<double> row = lead;
      row.insert(row.end(), {b.in.mean_K, b.out.mean_K, b.difference_K(), static_cast<double>(b.in.count),
                             static_cast<double>(b.out.count)});
      rows.push_back(std::move(row));
      break;
    }
    case MeasurementKind::profile: {
      std::vector<TemperatureAccumulator> sums = temperature_profile_sums(sim.particles, m.profile, offset, sim.left_out());
      sim.merge_over_ranks(std::span<TemperatureAccumulator>(sums));
      std::vector<TemperatureStatistics> bins;
      for (const TemperatureAccumulator& bin : sums) bins.push_back(bin.result());
      for (std::size_t k = 0; k < bins.size(); ++k) {
        std::vector<double> row = lead;
        row.push_back(m.profile.bin_centre_m(k));
        if (heat) add_temperatures(row, bins[k]);
        row.push_back(static_cast<double>(bins[k].count));
        rows.push_back(std::move(row));
      }
      break;
    }
  }
  return rows;
}

std::vector<SeriesColumn> thermal_history_columns(const Simulation& sim) {
  if (!threshold_of(sim)) return {};
  return {{"peak_temperature_max", "K"},
          {"crossed_threshold_fraction", "-"},
          {"time_above_threshold_mean", "s"},
          {"time_above_threshold_mean_real", "s"}};  // the same in real time (x S)
}

std::vector<double> thermal_history_row(const Simulation& sim) {
  const std::optional<double> threshold = threshold_of(sim);
  if (!threshold) return {};
  ThermalHistorySums sums = thermal_history_sums(sim.particles, *threshold, sim.left_out());
  sim.merge_over_ranks(std::span<ThermalHistorySums>(&sums, 1));
  const ThermalHistorySummary s = sums.result();
  return {s.peak_temperature_max_K, s.crossed_fraction(), s.time_above_threshold_mean_s,
          TimeScale{sim.settings().heat.time_scale_factor}.real_time_s(s.time_above_threshold_mean_s)};
}

MeasurementRunner::MeasurementRunner(const MeasurementPlan& plan) : plan_(plan) {
  clocks_.reserve(plan_.items.size());
  for (const Measurement& m : plan_.items) clocks_.emplace_back(m.schedule);
}

void MeasurementRunner::announce(const Simulation& sim, RunObserver& observer) const {
  if (plan_.empty()) return;
  std::vector<MeasurementTable> tables;
  for (const Measurement& m : plan_.items) tables.push_back(measurement_table(m, sim));
  observer.measurement_tables(tables);
}

double MeasurementRunner::depth_m(const Simulation& sim, const Measurement& m) const {
  return m.depth_body >= 0 ? sim.walls.bodies[static_cast<std::size_t>(m.depth_body)].depth_m() : 0.0;
}

void MeasurementRunner::take(std::size_t k, const Simulation& sim, double half_step_s, RunObserver& observer) {
  observer.measurement_rows(k, measurement_rows(plan_.items[k], sim));
  clocks_[k].taken(sim.time_s(), half_step_s, depth_m(sim, plan_.items[k]));
}

void MeasurementRunner::with_time_series(const Simulation& sim, RunObserver& observer) {
  for (std::size_t k = 0; k < plan_.items.size(); ++k)
    if (plan_.items[k].schedule.with_time_series()) observer.measurement_rows(k, measurement_rows(plan_.items[k], sim));
}

void MeasurementRunner::before_step(const Simulation& sim, double half_step_s, RunObserver& observer) {
  for (std::size_t k = 0; k < plan_.items.size(); ++k)
    if (clocks_[k].due(sim.time_s(), half_step_s, depth_m(sim, plan_.items[k]))) take(k, sim, half_step_s, observer);
}

bool MeasurementRunner::due(const Simulation& sim, double half_step_s) const {
  for (std::size_t k = 0; k < plan_.items.size(); ++k)
    if (clocks_[k].due(sim.time_s(), half_step_s, depth_m(sim, plan_.items[k]))) return true;
  return false;
}

void MeasurementRunner::at_stage_end(const Simulation& sim, RunObserver& observer) {
  for (std::size_t k = 0; k < plan_.items.size(); ++k)
    if (clocks_[k].due_at_stage_end(sim.time_s())) take(k, sim, 0.0, observer);
}

void MeasurementRunner::count_step() {
  for (MeasurementClock& clock : clocks_) clock.count_step();
}

std::vector<MeasurementClock::State> MeasurementRunner::clock_states() const {
  std::vector<MeasurementClock::State> states;
  states.reserve(clocks_.size());
  for (const MeasurementClock& clock : clocks_) states.push_back(clock.state());
  return states;
}

void MeasurementRunner::restore_clocks(const std::vector<MeasurementClock::State>& states) {
  if (states.size() != clocks_.size())
    throw std::invalid_argument(fmt::format("holds {} measurement clocks, the scenario has {} measurements",
                                            states.size(), clocks_.size()));
  for (std::size_t k = 0; k < clocks_.size(); ++k) clocks_[k].restore(states[k]);
}

}  // namespace regodem
