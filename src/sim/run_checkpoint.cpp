#include "sim/run_checkpoint.hpp"

#include <fmt/format.h>

#include "io/checkpoint_file.hpp"
#include "sim/measurement_runner.hpp"
#include "sim/simulation.hpp"

namespace regodem {
namespace {
constexpr const char* kRun = "RUNP";
constexpr const char* kMeasurements = "MEAS";

void put_clock(ByteWriter& w, const SnapshotClock::State& clock) {
  w.put(static_cast<std::uint8_t>(clock.taken_any));
  for (double v : {clock.last_time_s, clock.next_time_s, clock.next_depth_m}) w.put(v);
  w.put(clock.steps_since);
}

SnapshotClock::State get_clock(ByteReader& r) {
  SnapshotClock::State clock;
  clock.taken_any = r.get<std::uint8_t>() != 0;
  for (double* v : {&clock.last_time_s, &clock.next_time_s, &clock.next_depth_m}) r.get(*v);
  r.get(clock.steps_since);
  return clock;
}
}  // namespace

void save_run_state(Checkpoint& checkpoint, const RunState& state) {
  state.sim.save_state(checkpoint);
  ByteWriter w;
  const RunPosition& p = state.position;
  w.put(static_cast<std::uint64_t>(state.plan.stages.size()));
  w.put(static_cast<std::uint64_t>(p.stage));
  w.put(static_cast<std::uint8_t>(p.inside_stage));
  for (double v : {p.stage_start_time_s, p.planned_end_time_s}) w.put(v);
  w.put(p.done);
  w.put(p.planned_steps);
  for (double v : {p.step_s, p.sample_interval_s, p.next_sample_s, p.last_sampled_time_s, p.particle_steps}) w.put(v);
  for (std::uint64_t word : state.rng.state()) w.put(word);
  put_clock(w, state.snapshots.state());
  w.put(static_cast<std::uint64_t>(state.plan.insertions.size()));
  for (const Insertion& ins : state.plan.insertions) {
    w.put_string(ins.name);
    w.put(static_cast<std::uint64_t>(ins.inserted));
    std::vector<std::uint64_t> per_class(ins.inserted_per_class.begin(), ins.inserted_per_class.end());
    w.put_vector(per_class);
    w.put(ins.start_time_s);
    w.put(static_cast<std::uint64_t>(ins.attempts));
    w.put(static_cast<std::int32_t>(ins.fruitless_attempts));
    w.put(static_cast<std::uint8_t>(ins.finished));
  }
  checkpoint.add(kRun, 1, std::move(w));
  ByteWriter m;
  const std::vector<MeasurementClock::State> clocks =
      state.measurements != nullptr ? state.measurements->clock_states() : std::vector<MeasurementClock::State>{};
  m.put(static_cast<std::uint64_t>(clocks.size()));
  for (const MeasurementClock::State& clock : clocks) {
    put_clock(m, clock.periodic);
    m.put(clock.next);
  }
  checkpoint.add(kMeasurements, 1, std::move(m));
}

bool run_completed(const Checkpoint& checkpoint) {
  ByteReader r = checkpoint.reader(kRun);
  const auto stages = r.get<std::uint64_t>();
  const auto stage = r.get<std::uint64_t>();
  return stage >= stages && r.get<std::uint8_t>() == 0;
}

RunPosition restore_run_state(const Checkpoint& checkpoint, StagePlan& plan, Rng& rng, SnapshotClock& snapshots,
                              MeasurementRunner& measurements) {
  ByteReader r = checkpoint.reader(kRun);
  RunPosition p;
  const auto stages = r.get<std::uint64_t>();
  if (stages != plan.stages.size()) r.fail(fmt::format("has {} stages, the scenario {}", stages, plan.stages.size()));
  p.stage = r.get<std::uint64_t>();
  p.inside_stage = r.get<std::uint8_t>() != 0;
  if (p.stage > stages || (p.inside_stage && p.stage == stages)) r.fail("stands at a stage the scenario does not have");
  r.get(p.stage_start_time_s);
  r.get(p.planned_end_time_s);
  r.get(p.done);
  r.get(p.planned_steps);
  for (double* v : {&p.step_s, &p.sample_interval_s, &p.next_sample_s, &p.last_sampled_time_s, &p.particle_steps})
    r.get(*v);
  std::array<std::uint64_t, 4> words{};
  for (std::uint64_t& word : words) r.get(word);
  rng.set_state(words);
  snapshots.restore(get_clock(r));
  if (r.get<std::uint64_t>() != plan.insertions.size()) r.fail("has another number of insertions than the scenario");
  for (Insertion& ins : plan.insertions) {
    const std::string name = r.get_string();
    if (name != ins.name) r.fail(fmt::format("has insertion '{}' where the scenario has '{}'", name, ins.name));
    ins.inserted = r.get<std::uint64_t>();
    std::vector<std::uint64_t> per_class;
    r.get_vector(per_class);
    ins.inserted_per_class.assign(per_class.begin(), per_class.end());
    r.get(ins.start_time_s);
    ins.attempts = r.get<std::uint64_t>();
    ins.fruitless_attempts = r.get<std::int32_t>();
    ins.finished = r.get<std::uint8_t>() != 0;
  }
  ByteReader m = checkpoint.reader(kMeasurements);
  std::vector<MeasurementClock::State> clocks(m.get<std::uint64_t>());
  for (MeasurementClock::State& clock : clocks) {
    clock.periodic = get_clock(m);
    m.get(clock.next);
  }
  try {
    measurements.restore_clocks(clocks);
  } catch (const std::invalid_argument& error) {
    m.fail(error.what());
  }
  return p;
}

}  // namespace regodem
