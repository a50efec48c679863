#include "run_recorder.hpp"

#include <fmt/format.h>

#include "sim/run_checkpoint.hpp"

namespace regodem::app {
namespace {

constexpr const char* kOutputs = "OUTP";

void save_entries(ByteWriter& w, const std::vector<PvdCollection::Entry>& entries) {
  w.put(static_cast<std::uint64_t>(entries.size()));
  for (const PvdCollection::Entry& e : entries) {
    w.put(e.time_s);
    w.put_string(e.file);
  }
}

std::vector<PvdCollection::Entry> read_entries(ByteReader& r) {
  std::vector<PvdCollection::Entry> entries(r.get<std::uint64_t>());
  for (PvdCollection::Entry& e : entries) {
    r.get(e.time_s);
    e.file = r.get_string();
  }
  return entries;
}

template <class T>
void save_optional(ByteWriter& w, const std::optional<T>& value) {
  w.put(static_cast<std::uint8_t>(value.has_value()));
  w.put(value ? static_cast<double>(*value) : 0.0);
}

template <class T>
std::optional<T> read_optional(ByteReader& r) {
  const bool present = r.get<std::uint8_t>() != 0;
  const auto value = r.get<double>();
  if (!present) return std::nullopt;
  return static_cast<T>(value);
}

}  // namespace

RunRecorder::RunRecorder(std::filesystem::path time_series_path, ProgressDisplay& display,
                         const std::vector<std::string>& planned_stage_names)
    : time_series_path_(std::move(time_series_path)), display_(display) {
  stages_.resize(planned_stage_names.size());
  for (std::size_t i = 0; i < stages_.size(); ++i) stages_[i].name = planned_stage_names[i];
}

void RunRecorder::columns(const std::vector<SeriesColumn>& columns) {
  if (continue_time_series_)
    time_series_ = std::make_unique<CsvTimeSeriesWriter>(time_series_path_, columns.size(),
                                                         continue_time_series_->first, continue_time_series_->second);
  else
    time_series_ = std::make_unique<CsvTimeSeriesWriter>(time_series_path_, columns);
}

bool RunRecorder::checkpoint_due() { return checkpoints_ != nullptr && checkpoints_->due(); }

void RunRecorder::checkpoint(const RunState& state) {
  if (checkpoints_ == nullptr) return;
  try {
    Checkpoint c;
    save_run_state(c, state);
    save_identity(c, identity_);
    ByteWriter w;
    w.put(static_cast<std::uint64_t>(time_series_ ? time_series_->bytes_written() : 0));
    w.put(static_cast<std::uint64_t>(time_series_ ? time_series_->rows_written() : 0));
    w.put(static_cast<std::uint64_t>(bond_breaks_ ? bond_breaks_->bytes_written() : 0));
    w.put(static_cast<std::uint64_t>(bond_breaks_ ? bond_breaks_->rows_written() : 0));
    w.put(static_cast<std::uint64_t>(snapshots_ ? snapshots_->series().count() : 0));
    save_entries(w, snapshots_ ? snapshots_->series().particles().entries() : std::vector<PvdCollection::Entry>{});
    save_entries(w, snapshots_ ? snapshots_->series().walls().entries() : std::vector<PvdCollection::Entry>{});
    w.put(static_cast<std::uint64_t>(stages_.size()));
    for (const StageSummary& s : stages_) {
      w.put_string(s.name);
      save_optional(w, s.result);
      save_optional(w, s.start_time_s);
      save_optional(w, s.end_time_s);
      save_optional(w, s.wall_time_s);
      w.put_string(s.message);
    }
    w.put(static_cast<std::uint64_t>(notices_.size()));
    for (const std::string& n : notices_) w.put_string(n);
    // Measurement files: where each stands, and its last sample for summary.json.
    w.put(static_cast<std::uint64_t>(measurement_writers_.size()));
    for (std::size_t k = 0; k < measurement_writers_.size(); ++k) {
      w.put(static_cast<std::uint64_t>(measurement_writers_[k]->bytes_written()));
      w.put(static_cast<std::uint64_t>(measurement_writers_[k]->rows_written()));
      w.put(static_cast<std::uint64_t>(measurement_finals_[k].samples));
      w.put(static_cast<std::uint64_t>(measurement_finals_[k].last_rows.size()));
      for (const std::vector<double>& row : measurement_finals_[k].last_rows) w.put_vector(row);
    }
    c.add(kOutputs, 1, std::move(w));
    checkpoints_->write(c);
    checkpoint_failure_.clear();
  } catch (const std::exception& error) {
    // The run goes on: a checkpoint is a safety net, not a result.
    checkpoint_failure_ = error.what();
    notice(fmt::format("could not write a checkpoint: {}", error.what()));
  }
}

void RunRecorder::resume_outputs(const Checkpoint& checkpoint) {
  // Everything is read first: a section that does not read leaves the files as they are.
  ByteReader r = checkpoint.reader(kOutputs);
  const auto series_bytes = r.get<std::uint64_t>();
  const auto series_rows = r.get<std::uint64_t>();
  const auto breaks_bytes = r.get<std::uint64_t>();
  const auto breaks_rows = r.get<std::uint64_t>();
  const auto snapshot_count = r.get<std::uint64_t>();
  std::vector<PvdCollection::Entry> particles = read_entries(r), walls = read_entries(r);
  std::vector<StageSummary> stages(r.get<std::uint64_t>());
  std::optional<std::size_t> last_started;
  for (std::size_t k = 0; k < stages.size(); ++k) {
    StageSummary& s = stages[k];
    s.name = r.get_string();
    s.result = read_optional<StageResult>(r);
    s.start_time_s = read_optional<double>(r);
    s.end_time_s = read_optional<double>(r);
    s.wall_time_s = read_optional<double>(r);
    s.message = r.get_string();
    if (s.start_time_s) last_started = k;
  }
  std::vector<std::string> notices(r.get<std::uint64_t>());
  for (std::string& n : notices) n = r.get_string();
  std::vector<MeasurementContinuation> measurements(r.get<std::uint64_t>());
  for (MeasurementContinuation& m : measurements) {
    m.bytes = r.get<std::uint64_t>();
    m.rows = r.get<std::uint64_t>();
    m.samples = r.get<std::uint64_t>();
    m.last_rows.resize(r.get<std::uint64_t>());
    for (std::vector<double>& row : m.last_rows) r.get_vector(row);
  }

  std::error_code error;
  if (series_bytes > 0 && (std::filesystem::file_size(time_series_path_, error) < series_bytes || error))
    throw CheckpointError(fmt::format("'{}' is shorter than the {} bytes checkpoint '{}' knew: it cannot be continued",
                                      time_series_path_.string(), series_bytes, checkpoint.source));
  if (series_bytes > 0) continue_time_series_ = std::make_pair(std::uintmax_t{series_bytes}, std::size_t{series_rows});
  if (!bond_breaks_path_.empty()) {
    if (breaks_bytes > 0)
      bond_breaks_ = std::make_unique<CsvTimeSeriesWriter>(bond_breaks_path_, 9, breaks_bytes, breaks_rows);
    else
      std::filesystem::remove(bond_breaks_path_);  // breaks after the checkpoint: they happen again
  }
  if (snapshots_ != nullptr) snapshots_->series().restore(snapshot_count, std::move(particles), std::move(walls));
  stages_ = std::move(stages);
  last_started_index_ = last_started;
  notices_ = std::move(notices);
  continue_measurements_ = std::move(measurements);
}

void RunRecorder::stage_started(const StageInfo& stage) {
  if (stage.index >= stages_.size()) stages_.resize(stage.index + 1);
  // A stage ends where the next begins; the observer interface reports no end time.
  // (A resumed run starts its current stage again: that is no end.)
  if (last_started_index_ && *last_started_index_ != stage.index && !stages_[*last_started_index_].end_time_s) {
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
    const std::size_t k = measurement_writers_.size();
    if (k < continue_measurements_.size()) {  // a resumed run: cut back to the checkpoint and go on
      const MeasurementContinuation& m = continue_measurements_[k];
      measurement_writers_.push_back(
          std::make_unique<CsvTimeSeriesWriter>(measurements_directory_ / relative, table.columns.size(), m.bytes, m.rows));
      measurement_finals_.push_back({table, relative.generic_string(), m.samples, m.last_rows});
    } else {
      measurement_writers_.push_back(
          std::make_unique<CsvTimeSeriesWriter>(measurements_directory_ / relative, table.columns));
      measurement_finals_.push_back({table, relative.generic_string(), 0, {}});
    }
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
