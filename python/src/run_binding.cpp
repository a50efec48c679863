// Runs from Python (docs/python.md, "Running"). A Run is `regodem run` (app/run_session):
// the same output directory, time series, checkpoints and summary. The runner works in a
// thread of its own and parks at a step boundary when the steps it was given are done
// (or its stage ended, when asked), so that Python can read and change the state between
// calls and the run goes on exactly as an unbroken one. Progress callbacks and Ctrl-C
// are handled on Python's thread while the runner works.
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <limits>
#include <memory>
#include <mutex>
#include <numeric>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "bindings.hpp"
#include "commands.hpp"
#include "core/error.hpp"
#include "run_session.hpp"
#include "sim/run_checkpoint.hpp"
#include "sim/simulation.hpp"
#include "sim/stage_plan.hpp"

namespace py = pybind11;

namespace regodem::python {
namespace {

using app::ResumeChoice;
using app::RunEnding;
using app::RunOptions;
using app::RunSession;

constexpr std::uint64_t unlimited = std::numeric_limits<std::uint64_t>::max();

/// Watches a run from its thread: parks it when its step budget is spent or, when asked,
/// when its stage ended; keeps the latest progress, sample and measurement rows for Python.
class PausingObserver final : public RunObserver {
 public:
  enum class Wake { parked, done, progress, timeout };

  // The runner's side.
  void columns(const std::vector<SeriesColumn>& columns) override {
    const std::lock_guard lock(mutex_);
    columns_ = columns;
  }
  void stage_started(const StageInfo& stage) override {
    const std::lock_guard lock(mutex_);
    stage_ = stage;
    inside_stage_ = true;
  }
  void progress(const ProgressSnapshot& snapshot) override {
    const std::lock_guard lock(mutex_);
    pending_progress_ = snapshot;
    changed_.notify_all();
  }
  double progress_interval_s() const override { return 0.5; }
  void sample(const std::vector<double>& row) override {
    const std::lock_guard lock(mutex_);
    last_row_ = row;
  }
  void stage_finished(const StageInfo& stage, StageResult /*result*/, const std::string& /*message*/) override {
    const std::lock_guard lock(mutex_);
    stage_ = stage;
    inside_stage_ = false;
  }
  void measurement_tables(const std::vector<MeasurementTable>& tables) override {
    const std::lock_guard lock(mutex_);
    tables_ = tables;
    rows_.assign(tables.size(), {});
  }
  void measurement_rows(std::size_t table, const std::vector<std::vector<double>>& rows) override {
    const std::lock_guard lock(mutex_);
    if (table < rows_.size()) rows_[table] = rows;
  }
  void checkpoint(const RunState& state) override {
    if (state.reason != CheckpointReason::stage_end) return;
    // After the last stage the run ends: run_stage() returns with its summary written.
    if (state.position.stage >= state.plan.stages.size()) return;
    std::unique_lock lock(mutex_);
    if (stop_at_stage_end_) {
      stop_at_stage_end_ = false;
      park(lock);
    }
  }
  void before_step(const Simulation& /*sim*/) override {
    std::unique_lock lock(mutex_);
    if (budget_ == 0) park(lock);
    if (budget_ != unlimited) --budget_;
  }
  void runner_done() {
    const std::lock_guard lock(mutex_);
    done_ = true;
    changed_.notify_all();
  }

  // Python's side.
  /// Lets the runner go on for `steps` more steps (unlimited: to the end), parking at
  /// the end of the stage too when `stop_at_stage_end`.
  void go(std::uint64_t steps, bool stop_at_stage_end) {
    const std::lock_guard lock(mutex_);
    budget_ = steps;
    stop_at_stage_end_ = stop_at_stage_end;
    parked_ = false;
    ++generation_;
    changed_.notify_all();
  }
  Wake wait(std::chrono::milliseconds timeout, std::optional<ProgressSnapshot>& progress) {
    std::unique_lock lock(mutex_);
    changed_.wait_for(lock, timeout, [&] { return parked_ || done_ || pending_progress_.has_value(); });
    progress = std::exchange(pending_progress_, std::nullopt);
    if (done_) return Wake::done;
    if (parked_) return Wake::parked;
    return progress ? Wake::progress : Wake::timeout;
  }
  bool done() const {
    const std::lock_guard lock(mutex_);
    return done_;
  }
  void wait_done() {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return done_; });
  }

  // Read while the runner is parked or done.
  std::optional<StageInfo> stage() const {
    const std::lock_guard lock(mutex_);
    return stage_;
  }
  bool inside_stage() const {
    const std::lock_guard lock(mutex_);
    return inside_stage_;
  }
  std::vector<SeriesColumn> columns() const {
    const std::lock_guard lock(mutex_);
    return columns_;
  }
  std::vector<double> last_row() const {
    const std::lock_guard lock(mutex_);
    return last_row_;
  }
  std::vector<MeasurementTable> tables() const {
    const std::lock_guard lock(mutex_);
    return tables_;
  }
  std::vector<std::vector<std::vector<double>>> rows() const {
    const std::lock_guard lock(mutex_);
    return rows_;
  }

 private:
  /// Waits until Python says go on (called with the lock held).
  void park(std::unique_lock<std::mutex>& lock) {
    parked_ = true;
    const std::uint64_t generation = generation_;
    changed_.notify_all();
    changed_.wait(lock, [&] { return generation_ != generation; });
  }

  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::uint64_t budget_ = 0;
  bool stop_at_stage_end_ = false;
  bool parked_ = false;
  bool done_ = false;
  std::uint64_t generation_ = 0;
  std::optional<ProgressSnapshot> pending_progress_;
  std::vector<SeriesColumn> columns_;
  std::vector<double> last_row_;
  std::optional<StageInfo> stage_;
  bool inside_stage_ = false;
  std::vector<MeasurementTable> tables_;
  std::vector<std::vector<std::vector<double>>> rows_;
};

py::dict progress_dict(const ProgressSnapshot& s) {
  py::dict d;
  d["stage"] = s.stage.name;
  d["stage_index"] = s.stage.index;
  d["stages"] = s.stage.count;
  d["time_s"] = s.time_s;
  d["step"] = s.step;
  d["particles"] = s.particles;
  d["wall_s"] = s.wall_s;
  d["particle_steps_per_s"] = s.particle_steps_per_s;
  d["estimated_remaining_s"] = s.estimated_remaining_s >= 0.0 ? py::cast(s.estimated_remaining_s) : py::none();
  return d;
}

py::array_t<double> vec3_array(const std::vector<Vec3>& field, const std::vector<std::size_t>& order) {
  py::array_t<double> a({static_cast<py::ssize_t>(order.size()), py::ssize_t{3}});
  auto r = a.mutable_unchecked<2>();
  for (std::size_t k = 0; k < order.size(); ++k) {
    const Vec3& v = field[order[k]];
    const auto row = static_cast<py::ssize_t>(k);
    r(row, 0) = v.x, r(row, 1) = v.y, r(row, 2) = v.z;
  }
  return a;
}

template <typename T>
py::array_t<T> scalar_array(const std::vector<T>& field, const std::vector<std::size_t>& order) {
  py::array_t<T> a(static_cast<py::ssize_t>(order.size()));
  auto r = a.template mutable_unchecked<1>();
  for (std::size_t k = 0; k < order.size(); ++k) r(static_cast<py::ssize_t>(k)) = field[order[k]];
  return a;
}

py::tuple vec3_tuple(const Vec3& v) { return py::make_tuple(v.x, v.y, v.z); }

Vec3 vec3_from_row(const py::detail::unchecked_reference<double, 2>& r, py::ssize_t row) {
  return {r(row, 0), r(row, 1), r(row, 2)};
}

const char* thermal_mode_name(WallThermalMode mode) {
  switch (mode) {
    case WallThermalMode::adiabatic: return "adiabatic";
    case WallThermalMode::fixed: return "fixed";
    case WallThermalMode::lumped: return "lumped";
  }
  return "adiabatic";
}

std::string status_name(RunStatus status) { return std::string(to_string(status)); }

class PythonRun {
 public:
  /// A new run (resume empty) or the continuation of the run in `resume`'s directory.
  PythonRun(RunOptions options, std::optional<std::string> scenario_text, bool quiet,
            std::optional<ResumeChoice> resume)
      : resume_(std::move(resume)) {
    const ThreadChoice choice = app::choose_run_threads(options.threads);
    if (!choice.note.empty() && !quiet) fmt::print(stderr, "regodem: note: {}\n", choice.note);
    options.threads = choice.threads;
    threads_ = choice.threads;
    py::gil_scoped_release release;  // reading and building can take a while
    session_ = std::make_unique<RunSession>(options, resume_ ? &resume_->point : nullptr, std::move(scenario_text));
    session_->begin(quiet ? nullptr : stderr);
  }
  PythonRun(const PythonRun&) = delete;
  PythonRun& operator=(const PythonRun&) = delete;
  ~PythonRun() { close(); }

  /// Ends the run where it stands: a run that has not ended stops as on Ctrl-C (a
  /// checkpoint, summary.json with status "interrupted"), so it can be resumed.
  void close() {
    if (finished_) return;
    set_stop_cause("Run.close()");
    if (!started_) {
      stop_requested_ = true;  // stops at the first step boundary: a checkpoint at the start
      start_runner();
    }
    stop_and_wait();
  }

  /// Runs `steps` more steps (mechanical or static-bed), or to the end.
  std::string advance(std::uint64_t steps, bool stop_at_stage_end, const py::object& progress) {
    if (stepping_) throw InputError("the run is stepping already: step(), run_stage() and run() cannot be called "
                                    "from the progress callback");
    if (finished_) return status();
    if (steps == 0 && !stop_at_stage_end) return status();
    observer_.go(steps, stop_at_stage_end);
    if (!started_) start_runner();
    stepping_ = true;
    for (;;) {
      std::optional<ProgressSnapshot> snapshot;
      PausingObserver::Wake wake;
      {
        py::gil_scoped_release release;
        wake = observer_.wait(std::chrono::milliseconds(100), snapshot);
      }
      const char* cause = "an exception in the progress callback";
      try {
        if (snapshot && !progress.is_none()) progress(progress_dict(*snapshot));
        cause = "KeyboardInterrupt";
        if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      } catch (...) {
        // Ctrl-C, or the callback raised: the run stops as the command line's does on
        // Ctrl-C (a checkpoint and summary), then the exception goes on.
        set_stop_cause(cause);
        stop_and_wait();
        stepping_ = false;
        throw;
      }
      if (wake == PausingObserver::Wake::done) {
        join_runner();
        break;
      }
      if (wake == PausingObserver::Wake::parked) break;
    }
    stepping_ = false;
    if (finished_ && ending_.status == RunStatus::failed)
      throw SimulationError(fmt::format("{} ({})", ending_.outcome.message, final_line_));
    return status();
  }

  std::string status() const {
    if (finished_) return status_name(ending_.status);
    return started_ ? "paused" : "ready";
  }
  bool finished() const { return finished_; }
  const std::string& final_line() const { return final_line_; }
  std::string message() const { return finished_ ? ending_.outcome.message : ""; }
  std::string directory() const { return session_->directory().string(); }
  int threads() const { return threads_; }

  double time_s() const {
    readable();
    return simulation().time_s();
  }
  std::uint64_t step() const {
    readable();
    return simulation().step_count();
  }

  py::object stage() const {
    readable();
    const std::optional<StageInfo> s = observer_.stage();
    if (!s) return py::none();
    py::dict d;
    d["name"] = s->name;
    d["index"] = s->index;
    d["count"] = s->count;
    d["start_time_s"] = s->start_time_s;
    d["running"] = observer_.inside_stage();
    return d;
  }

  py::dict particles() const {
    readable();
    const ParticleStore& p = simulation().particles;
    const std::vector<std::size_t> order = by_id();
    py::dict d;
    d["id"] = scalar_array(p.id, order);
    d["radius_m"] = scalar_array(p.radius_m, order);
    d["mass_kg"] = scalar_array(p.mass_kg, order);
    d["position_m"] = vec3_array(p.position_m, order);
    d["velocity_m_per_s"] = vec3_array(p.velocity_m_per_s, order);
    d["angular_velocity_rad_per_s"] = vec3_array(p.angular_velocity_rad_per_s, order);
    d["force_N"] = vec3_array(p.force_N, order);
    d["material"] = scalar_array(p.material, order);
    d["region"] = scalar_array(p.region, order);
    if (simulation().heat_enabled()) {
      d["temperature_K"] = scalar_array(p.temperature_K, order);
      if (p.peak_temperature_K.size() == p.size()) d["peak_temperature_K"] = scalar_array(p.peak_temperature_K, order);
      if (p.time_above_threshold_s.size() == p.size())
        d["time_above_threshold_s"] = scalar_array(p.time_above_threshold_s, order);
    }
    return d;
  }

  std::vector<std::string> material_names() const {
    readable();
    std::vector<std::string> names;
    const MaterialTable& materials = simulation().model().materials;
    for (std::size_t m = 0; m < materials.size(); ++m) names.push_back(materials[static_cast<MaterialIndex>(m)].name);
    return names;
  }
  std::vector<std::string> region_names() {
    readable();
    return session_->prepared().plan().region_names;
  }

  py::list walls() const {
    readable();
    const Simulation& sim = simulation();
    py::list walls;
    for (std::size_t b = 0; b < sim.walls.bodies.size(); ++b) {
      const WallBody& wall = sim.walls.bodies[b];
      py::dict d;
      d["name"] = wall.name;
      d["force_N"] = vec3_tuple(wall.force_N);
      d["torque_N_m"] = vec3_tuple(wall.torque_N_m);
      d["displacement_m"] = vec3_tuple(wall.displacement_m);
      // The pose: the mesh as placed at the start -> now, x = R x0 + t (mesh walls turn and
      // move by it; an analytic wall's shape is placed in the world and only its displacement moves).
      d["position_m"] = vec3_tuple(wall.pose.translation_m);
      py::array_t<double> rotation({py::ssize_t{3}, py::ssize_t{3}});
      auto r = rotation.mutable_unchecked<2>();
      for (py::ssize_t i = 0; i < 3; ++i)
        for (py::ssize_t j = 0; j < 3; ++j)
          r(i, j) = wall.pose.rotation[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
      d["rotation"] = rotation;
      if (wall.fed()) d["depth_m"] = wall.depth_m();
      if (sim.keeps_energy_audit() && b < sim.wall_work_J().size()) d["work_J"] = sim.wall_work_J()[b];
      if (sim.heat_enabled() && b < sim.wall_thermal_state.size()) {
        const ThermalWallState& w = sim.wall_thermal_state[b];
        const WallThermalMode mode = sim.model().wall_thermal[b].mode;
        d["thermal"] = thermal_mode_name(mode);
        if (mode != WallThermalMode::adiabatic) {
          d["temperature_K"] = w.temperature_K;
          d["heat_to_particles_J"] = w.heat_to_particles_J;
        }
        if (mode == WallThermalMode::lumped) {
          d["peak_temperature_K"] = w.peak_temperature_K;
          d["generated_heat_J"] = w.generated_heat_J;
          if (!w.segment_temperature_K.empty()) d["segment_temperatures_K"] = w.segment_temperature_K;
        }
      }
      walls.append(d);
    }
    return walls;
  }

  /// The time series' last row, column by column ("name [unit]" keys as in the CSV).
  py::dict sample() const {
    readable();
    py::dict d;
    const std::vector<SeriesColumn> columns = observer_.columns();
    const std::vector<double> row = observer_.last_row();
    for (std::size_t c = 0; c < columns.size() && c < row.size(); ++c) d[py::str(header(columns[c]))] = row[c];
    return d;
  }

  /// Each measurement's last rows (one for a region or band, one per bin for a profile).
  py::dict measurements() const {
    readable();
    py::dict d;
    const std::vector<MeasurementTable> tables = observer_.tables();
    const auto rows = observer_.rows();
    for (std::size_t t = 0; t < tables.size(); ++t) {
      py::dict table;
      table["kind"] = tables[t].kind;
      std::vector<std::string> names;
      for (const SeriesColumn& c : tables[t].columns) names.push_back(header(c));
      table["columns"] = names;
      const std::vector<std::vector<double>>& r = rows[t];
      py::array_t<double> values({static_cast<py::ssize_t>(r.size()), static_cast<py::ssize_t>(names.size())});
      auto v = values.mutable_unchecked<2>();
      for (std::size_t i = 0; i < r.size(); ++i)
        for (std::size_t c = 0; c < names.size(); ++c)
          v(static_cast<py::ssize_t>(i), static_cast<py::ssize_t>(c)) =
              c < r[i].size() ? r[i][c] : std::numeric_limits<double>::quiet_NaN();
      table["rows"] = values;
      d[py::str(tables[t].name)] = table;
    }
    return d;
  }

  py::dict energy() const {
    readable();
    const Simulation& sim = simulation();
    py::dict d;
    if (sim.heat_enabled()) {
      const ThermalLedger& ledger = sim.thermal_ledger();
      d["thermal_energy_J"] = sim.thermal_energy_J();
      d["thermal_reference_J"] = ledger.reference_energy_J;
      d["boundary_heat_in_J"] = ledger.boundary_heat_in_J;
      d["generated_heat_J"] = ledger.generated_heat_J;
      d["thermal_imbalance_J"] = sim.energy_imbalance_J();
    }
    d["kinetic_energy_J"] = sim.translational_kinetic_energy_J() + sim.rotational_kinetic_energy_J();
    if (sim.keeps_energy_audit()) {
      const EnergyAudit& audit = sim.energy_audit();
      d["mechanical_energy_J"] = sim.mechanical_energy_J();
      d["wall_work_J"] = audit.wall_work_J;
      d["dissipated_J"] = audit.dissipated_J;
      d["exchanged_J"] = audit.exchanged_J;
      d["spring_source_J"] = audit.spring_source_J;
      d["mechanical_imbalance_J"] = sim.mechanical_imbalance_J();
    }
    return d;
  }

  void set_temperatures(const py::array_t<std::uint64_t, py::array::forcecast>& ids,
                        const py::array_t<double, py::array::forcecast>& temperatures_K) {
    writable();
    const std::vector<std::size_t> index = indices_of(ids);
    const auto t = temperatures_K.unchecked<1>();
    if (static_cast<std::size_t>(t.shape(0)) != index.size())
      throw InputError(fmt::format("set_temperatures: {} ids but {} temperatures", index.size(), t.shape(0)));
    for (std::size_t k = 0; k < index.size(); ++k)
      mutable_simulation().set_particle_temperature_K(index[k], t(static_cast<py::ssize_t>(k)));
  }

  void set_velocities(const py::array_t<std::uint64_t, py::array::forcecast>& ids,
                      const py::array_t<double, py::array::forcecast>& velocities_m_per_s,
                      const std::optional<py::array_t<double, py::array::forcecast>>& angular_rad_per_s) {
    writable();
    const std::vector<std::size_t> index = indices_of(ids);
    const auto v = velocities_m_per_s.unchecked<2>();
    if (static_cast<std::size_t>(v.shape(0)) != index.size() || v.shape(1) != 3)
      throw InputError(fmt::format("set_velocities: {} ids need velocities of shape ({}, 3)", index.size(),
                                   index.size()));
    std::optional<py::detail::unchecked_reference<double, 2>> w;
    if (angular_rad_per_s) {
      w.emplace(angular_rad_per_s->unchecked<2>());
      if (static_cast<std::size_t>(w->shape(0)) != index.size() || w->shape(1) != 3)
        throw InputError(fmt::format("set_velocities: {} ids need spins of shape ({}, 3)", index.size(), index.size()));
    }
    Simulation& sim = mutable_simulation();
    for (std::size_t k = 0; k < index.size(); ++k) {
      const auto row = static_cast<py::ssize_t>(k);
      const Vec3 spin = w ? vec3_from_row(*w, row) : sim.particles.angular_velocity_rad_per_s[index[k]];
      sim.set_particle_velocity(index[k], vec3_from_row(v, row), spin);
    }
  }

 private:
  static std::string header(const SeriesColumn& c) { return fmt::format("{} [{}]", c.name, c.unit); }

  const Simulation& simulation() const { return session_->prepared().simulation(); }
  Simulation& mutable_simulation() { return session_->prepared().simulation(); }

  void readable() const {
    if (stepping_)
      throw InputError("the run is stepping: read its state after step(), run_stage() or run() returns, not from "
                       "the progress callback");
  }
  void writable() {
    readable();
    if (finished_) throw InputError(fmt::format("the run has ended ({}): its state can no longer be changed", status()));
    // A resumed run restores its checkpoint when its runner starts: start it now (it parks
    // at its first step boundary), so that a change is made to the state it goes on from.
    if (!started_ && resume_) {
      observer_.go(0, false);
      start_runner();
      for (std::optional<ProgressSnapshot> ignored;;) {
        py::gil_scoped_release release;
        const PausingObserver::Wake wake = observer_.wait(std::chrono::milliseconds(100), ignored);
        if (wake == PausingObserver::Wake::parked || wake == PausingObserver::Wake::done) break;
      }
      if (observer_.done()) {
        join_runner();
        throw InputError(fmt::format("the resumed run has ended ({}): its state can no longer be changed", status()));
      }
    }
    if (started_ && observer_.inside_stage())
      if (const std::optional<StageInfo> s = observer_.stage();
          s && session_->prepared().plan().stages.at(s->index).freezes_mechanics())
        throw InputError(fmt::format(
            "stage '{}' is a static-bed stage, which steps a frozen contact network: change the state between "
            "stages (run_stage()) or in a coupled stage",
            s->name));
  }

  void set_stop_cause(const std::string& cause) {
    const std::lock_guard lock(cause_mutex_);
    stop_cause_ = cause;
  }
  std::string stop_cause() const {
    const std::lock_guard lock(cause_mutex_);
    return stop_cause_;
  }

  std::vector<std::size_t> by_id() const {
    const ParticleStore& p = simulation().particles;
    std::vector<std::size_t> order(p.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return p.id[a] < p.id[b]; });
    return order;
  }

  std::vector<std::size_t> indices_of(const py::array_t<std::uint64_t, py::array::forcecast>& ids) const {
    const ParticleStore& p = simulation().particles;
    const std::vector<std::size_t> order = by_id();
    const auto id = ids.unchecked<1>();
    std::vector<std::size_t> index;
    index.reserve(static_cast<std::size_t>(id.shape(0)));
    for (py::ssize_t k = 0; k < id.shape(0); ++k) {
      const std::uint64_t wanted = id(k);
      const auto it = std::lower_bound(order.begin(), order.end(), wanted,
                                       [&](std::size_t i, std::uint64_t v) { return p.id[i] < v; });
      if (it == order.end() || p.id[*it] != wanted)
        throw InputError(fmt::format("no particle has id {} (the run holds {})", wanted, p.size()));
      index.push_back(*it);
    }
    return index;
  }

  void start_runner() {
    started_ = true;
    runner_ = std::thread([this] {
      omp_set_num_threads(threads_);  // a thread's own OpenMP setting
      ending_ = session_->run(stop_requested_, &observer_);
      try {
        final_line_ = session_->finish(ending_, stop_cause());
      } catch (const std::exception& error) {  // summary.json could not be written
        final_line_ = fmt::format("regodem: the run ended but its summary could not be written: {}", error.what());
      }
      observer_.runner_done();
    });
  }
  void join_runner() {
    if (runner_.joinable()) runner_.join();
    finished_ = true;
    session_->release_directory();  // a new run (or a resume) may use it now
  }
  /// Asks the runner to stop, lets it go to its next check and waits for its end.
  void stop_and_wait() {
    stop_requested_ = true;
    observer_.go(unlimited, false);
    {
      py::gil_scoped_release release;
      observer_.wait_done();
    }
    join_runner();
  }

  std::optional<ResumeChoice> resume_;  // before session_, which points into it
  std::unique_ptr<RunSession> session_;
  PausingObserver observer_;
  std::atomic<bool> stop_requested_{false};
  mutable std::mutex cause_mutex_;  // the cause is set by Python while the runner may be finishing
  std::string stop_cause_ = "a stop request";
  std::thread runner_;
  int threads_ = 1;
  bool started_ = false;
  bool stepping_ = false;
  bool finished_ = false;
  RunEnding ending_;
  std::string final_line_;
};

RunOptions run_options(const std::string& path, const std::vector<std::string>& overrides, const std::string& output,
                       int threads, bool overwrite, double checkpoint_every_s) {
  RunOptions options;
  options.scenario_path = path;
  options.overrides = overrides;
  options.output_directory = output;
  options.threads = threads;
  options.overwrite = overwrite;
  options.checkpoint_every_s = checkpoint_every_s;
  return options;
}

}  // namespace

void bind_run(py::module_& m) {
  py::class_<PythonRun>(m, "Run", "A run of a scenario into its output directory (see regodem.Run)")
      .def(py::init([](const std::string& path, const std::optional<std::string>& text,
                       const std::vector<std::string>& overrides, const std::string& output, int threads,
                       bool overwrite, double checkpoint_every_s, bool quiet) {
             return std::make_unique<PythonRun>(run_options(path, overrides, output, threads, overwrite, checkpoint_every_s),
                                                text, quiet, std::nullopt);
           }),
           py::arg("path"), py::arg("text"), py::arg("overrides"), py::arg("output"), py::arg("threads"),
           py::arg("overwrite"), py::arg("checkpoint_every_s"), py::arg("quiet"))
      .def_static(
          "resume",
          [](const std::string& directory, int threads, double checkpoint_every_s, bool quiet) {
            app::ResumeOptions options{directory, threads, checkpoint_every_s};
            ResumeChoice choice = app::choose_resume(options, [quiet](const std::string& text) {
              if (!quiet) fmt::print(stderr, "regodem: {}\n", text);
            });
            if (choice.completed) throw InputError(choice.completed_message);
            const RunOptions run = choice.run;
            return std::make_unique<PythonRun>(run, std::nullopt, quiet, std::move(choice));
          },
          py::arg("directory"), py::arg("threads"), py::arg("checkpoint_every_s"), py::arg("quiet"))
      .def("advance", &PythonRun::advance, py::arg("steps"), py::arg("stop_at_stage_end"), py::arg("progress"))
      .def("close", &PythonRun::close)
      .def_property_readonly("status", &PythonRun::status)
      .def_property_readonly("finished", &PythonRun::finished)
      .def_property_readonly("final_line", &PythonRun::final_line)
      .def_property_readonly("message", &PythonRun::message)
      .def_property_readonly("directory", &PythonRun::directory)
      .def_property_readonly("threads", &PythonRun::threads)
      .def_property_readonly("time_s", &PythonRun::time_s)
      .def_property_readonly("step", &PythonRun::step)
      .def_property_readonly("stage", &PythonRun::stage)
      .def_property_readonly("material_names", &PythonRun::material_names)
      .def_property_readonly("region_names", &PythonRun::region_names)
      .def("particles", &PythonRun::particles)
      .def("walls", &PythonRun::walls)
      .def("sample", &PythonRun::sample)
      .def("measurements", &PythonRun::measurements)
      .def("energy", &PythonRun::energy)
      .def("set_temperatures", &PythonRun::set_temperatures, py::arg("ids"), py::arg("temperatures_K"))
      .def("set_velocities", &PythonRun::set_velocities, py::arg("ids"), py::arg("velocities_m_per_s"),
           py::arg("angular_velocities_rad_per_s") = py::none());
}

}  // namespace regodem::python
