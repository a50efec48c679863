// Results are deterministic for a fixed seed and thread count: two runs of the same
// pour are bit-for-bit identical, with two threads (force sums in a fixed order).
#include <gtest/gtest.h>

#include <atomic>

#include "scenario/scenario_builder.hpp"
#include "sim/simulation.hpp"

namespace regodem {
namespace {

class Quiet : public RunObserver {};

ScenarioSpec small_pour() {
  ScenarioSpec spec;
  spec.name = "determinism";
  spec.file = "determinism.yaml";
  spec.seed = 17;
  spec.domain.min_m = {-0.006, -0.006, -0.001};
  spec.domain.max_m = {0.006, 0.006, 0.02};
  spec.materials.push_back({"grain", 3000.0, 1e7, 0.25, {}});
  InteractionSpec pair;
  pair.material_a = pair.material_b = "grain";
  pair.restitution = 0.3;
  pair.sliding_friction = 0.5;
  pair.rolling_friction = 0.1;
  spec.interactions.push_back(pair);
  WallSpec cup;
  cup.name = "cup";
  cup.shape = WallShape::cylinder;
  cup.radius_m = 0.005;
  cup.length_m = 0.018;
  cup.cap_bottom = true;
  spec.walls.push_back(cup);
  InsertionSpec in;
  in.name = "grains";
  in.material = "grain";
  in.region.shape = RegionShape::cylinder;
  in.region.base_m = {0, 0, 0.002};
  in.region.length_m = 0.015;
  in.region.radius_m = 0.0049;
  in.sizes = {{0.3e-3, 0.6}, {0.6e-3, 0.4}};
  in.amount = 600;
  in.rate_per_s = 20000;
  in.interval_s = 0.005;
  spec.insertions.push_back(in);
  StageSpec stage;
  stage.name = "pour";
  stage.duration_s = 0.08;
  spec.stages.push_back(stage);
  return spec;
}

TEST(Determinism, SameSeedAndThreadsGiveIdenticalState) {
  std::vector<Vec3> first;
  for (int run_index = 0; run_index < 2; ++run_index) {
    PreparedRun run = PreparedRun::build(small_pour(), 2);
    Quiet quiet;
    std::atomic<bool> stop{false};
    ASSERT_TRUE(run.run(quiet, stop).completed);
    const ParticleStore& p = run.simulation().particles;
    ASSERT_GT(run.simulation().contact_statistics().particle_contacts, 100u);
    if (run_index == 0) {
      first = p.position_m;
      continue;
    }
    ASSERT_EQ(p.position_m.size(), first.size());
    for (std::size_t i = 0; i < first.size(); ++i) ASSERT_EQ(p.position_m[i], first[i]) << "particle " << i;
  }
}

}  // namespace
}  // namespace regodem
