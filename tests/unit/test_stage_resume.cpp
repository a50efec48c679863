// The stage runner resumed from a checkpoint taken inside a stage: a coupled stage and
// a static-bed heat stage (its own, larger step), each stopped part-way by a stop
// request, resumed in a freshly built run and compared, sample for sample, with the
// run that was not stopped.
#include <atomic>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "io/checkpoint_file.hpp"
#include "scenario/scenario_builder.hpp"
#include "scenario/scenario_reader.hpp"
#include "sim/run_checkpoint.hpp"

namespace regodem {
namespace {

/// Records the samples; asks to stop once a sample of `stop_stage` passes `stop_time_s`,
/// and keeps the checkpoint the runner then hands over.
class Recorder : public RunObserver {
 public:
  Recorder(std::atomic<bool>& stop, int stop_stage, double stop_time_s)
      : stop_(stop), stop_stage_(stop_stage), stop_time_s_(stop_time_s) {}
  void sample(const std::vector<double>& row) override {
    rows.push_back(row);
    if (static_cast<int>(row[2]) == stop_stage_ && row[0] > stop_time_s_) stop_.store(true);
  }
  void checkpoint(const RunState& state) override {
    if (state.reason != CheckpointReason::interrupted) return;
    saved.emplace();
    save_run_state(*saved, state);
  }
  std::vector<std::vector<double>> rows;
  std::optional<Checkpoint> saved;

 private:
  std::atomic<bool>& stop_;
  int stop_stage_;
  double stop_time_s_;
};

ScenarioSpec small_scenario() {
  // Two stages: a coupled fall, then a static bed heated for 200 s with explicit steps.
  std::vector<std::string> overrides{"stages.heat.duration=200 s", "output.interval=2 s",
                                     "output.snapshots.interval=100 s"};
  return read_scenario_file(std::string(REGODEM_SOURCE_DIR) + "/tests/data/scenarios/snapshots_small.yaml", overrides);
}

void check_resume_inside(int stage, double stop_time_s) {
  const ScenarioSpec spec = small_scenario();
  std::atomic<bool> never{false};
  Recorder whole(never, -1, 0.0);
  PreparedRun full = PreparedRun::build(spec, 1);
  ASSERT_TRUE(full.run(whole, never).completed);

  std::atomic<bool> stop{false};
  Recorder first(stop, stage, stop_time_s);
  PreparedRun cut = PreparedRun::build(spec, 1);
  const RunOutcome stopped = cut.run(first, stop);
  ASSERT_TRUE(stopped.interrupted);
  ASSERT_TRUE(first.saved.has_value());
  const Checkpoint loaded = decode_checkpoint(encode_checkpoint(*first.saved), "in memory");

  std::atomic<bool> go_on{false};
  Recorder second(go_on, -1, 0.0);
  PreparedRun resumed = PreparedRun::build(spec, 1);
  ASSERT_TRUE(resumed.resume(loaded, second, go_on).completed);

  // The first part's samples up to the checkpoint, then the resumed ones: the whole run.
  std::vector<std::vector<double>> joined;
  const double checkpoint_time = second.rows.empty() ? 0.0 : second.rows.front()[0];
  for (const auto& row : first.rows)
    if (row[0] < checkpoint_time) joined.push_back(row);
  joined.insert(joined.end(), second.rows.begin(), second.rows.end());
  ASSERT_EQ(joined.size(), whole.rows.size());
  for (std::size_t k = 0; k < joined.size(); ++k) ASSERT_EQ(joined[k], whole.rows[k]) << "sample " << k;
}

TEST(StageResume, InsideACoupledStage) { check_resume_inside(0, 0.012); }

TEST(StageResume, InsideAStaticBedStage) { check_resume_inside(1, 60.0); }

}  // namespace
}  // namespace regodem
