#include "run_recorder.hpp"

namespace regodem::app {

RunRecorder::RunRecorder(std::filesystem::path time_series_path, ProgressDisplay& display,
                         const std::vector<std::string>& planned_stage_names)
    : time_series_path_(std::move(time_series_path)), display_(display) {
  stages_.resize(planned_stage_names.size());
  for (std::size_t i = 0; i < stages_.size(); ++i) stages_[i].name = planned_stage_names[i];
}

void RunRecorder::columns(const std::vector<SeriesColumn>& columns) {
  time_series_ = std::make_unique<CsvTimeSeriesWriter>(time_series_path_, columns);
}

void RunRecorder::stage_started(const StageInfo& stage) {
  if (stage.index >= stages_.size()) stages_.resize(stage.index + 1);
  // A stage ends where the next begins; the observer interface reports no end time.
  if (last_started_index_ && !stages_[*last_started_index_].end_time_s) {
    stages_[*last_started_index_].end_time_s = stage.start_time_s;
  }
  StageSummary& record = stages_[stage.index];
  record.name = stage.name;
  record.start_time_s = stage.start_time_s;
  current_stage_ = stage;
  last_started_index_ = stage.index;
  stage_wall_start_ = Clock::now();
  display_.stage_started(stage);
}

void RunRecorder::progress(const ProgressSnapshot& snapshot) {
  last_snapshot_ = snapshot;
  display_.update(snapshot);
}

void RunRecorder::sample(const std::vector<double>& row) {
  if (time_series_) time_series_->write_row(row);
}

void RunRecorder::snapshot(const Simulation& sim) {
  if (snapshots_ != nullptr) snapshots_->write(sim);
}

void RunRecorder::bonds_broken(const std::vector<BondBreakEvent>& events) {
  if (bond_breaks_path_.empty()) return;
  if (!bond_breaks_)
    bond_breaks_ = std::make_unique<CsvTimeSeriesWriter>(
        bond_breaks_path_, std::vector<SeriesColumn>{{"time", "s"},
                                                     {"x", "m"},
                                                     {"y", "m"},
                                                     {"z", "m"},
                                                     {"mode", "1 tension, 2 shear"},
                                                     {"particle_i", "id"},
                                                     {"particle_j", "id"},
                                                     {"tensile_stress", "Pa"},
                                                     {"shear_stress", "Pa"}});
  for (const BondBreakEvent& e : events)
    bond_breaks_->write_row(std::vector<double>{e.time_s, e.position_m.x, e.position_m.y, e.position_m.z,
                                                static_cast<double>(e.mode), static_cast<double>(e.particle_i),
                                                static_cast<double>(e.particle_j), e.tensile_stress_Pa,
                                                e.shear_stress_Pa});
}

void RunRecorder::measurement_tables(const std::vector<MeasurementTable>& tables) {
  if (measurements_directory_.empty()) return;
  for (const MeasurementTable& table : tables) {
    const std::filesystem::path relative = std::filesystem::path(table.folder) / (table.name + ".csv");
    std::filesystem::create_directories(measurements_directory_ / table.folder);
    measurement_writers_.push_back(std::make_unique<CsvTimeSeriesWriter>(measurements_directory_ / relative, table.columns));
    measurement_finals_.push_back({table, relative.generic_string(), 0, {}});
  }
}

void RunRecorder::measurement_rows(std::size_t table, const std::vector<std::vector<double>>& rows) {
  if (table >= measurement_writers_.size()) return;
  for (const std::vector<double>& row : rows) measurement_writers_[table]->write_row(row);
  MeasurementFinal& final_values = measurement_finals_[table];
  ++final_values.samples;
  final_values.last_rows = rows;
}

void RunRecorder::notice(const std::string& message) {
  notices_.push_back(message);
  display_.notice(message);
}

void RunRecorder::stage_finished(const StageInfo& stage, StageResult result,
                                 const std::string& message) {
  if (stage.index >= stages_.size()) stages_.resize(stage.index + 1);
  StageSummary& record = stages_[stage.index];
  record.result = result;
  record.message = message;
  record.wall_time_s = std::chrono::duration<double>(Clock::now() - stage_wall_start_).count();
  display_.stage_finished(stage, result);
}

std::vector<StageSummary> RunRecorder::stage_summaries(double final_time_s,
                                                      StageResult result_if_unfinished) const {
  std::vector<StageSummary> summaries = stages_;
  if (last_started_index_) {
    StageSummary& last = summaries[*last_started_index_];
    if (!last.end_time_s) last.end_time_s = final_time_s;
    if (!last.result) last.result = result_if_unfinished;
  }
  return summaries;
}

}  // namespace regodem::app
