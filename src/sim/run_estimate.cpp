#include "sim/run_estimate.hpp"
#include "sim/stage_runner.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <numeric>
#include <optional>
#include <unordered_map>

#include <fmt/format.h>

#include "core/error.hpp"
#include "geometry/mesh_inside.hpp"
#include "sim/geometric_packing.hpp"
#include "sim/simulation.hpp"
#include "sim/stage_plan.hpp"
#include "sim/static_heat_stepper.hpp"

namespace regodem {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

/// Steps to cover `span_s` at `step_s`, as the stage runner counts them.
std::uint64_t steps_to_cover(double span_s, double step_s) {
  if (span_s <= 0.0) return 0;
  const double steps = std::ceil(span_s / step_s - 1e-9);
  // A static-bed stage's default step is known only from the sampled bed: its count is
  // checked here (the plan's were when it was built), so that no count can overflow.
  if (!(steps <= max_steps_per_stage))
    throw InputError(fmt::format("a stage would take {:.3g} steps of {:.4g} s for its {:.4g} s; at most {:.0e} steps a "
                                 "stage can be run",
                                 steps, step_s, span_s, max_steps_per_stage));
  return static_cast<std::uint64_t>(steps);
}

/// When a fed wall reaches `depth_m` after `start_s` (simulated, from the run's start),
/// with its motion as built: the feed starts at motion.start_s, stops at stop_s or after
/// max_travel_m. Negative when it never gets there.
double time_to_depth_s(const WallBody& wall, double depth_m, double start_s) {
  const WallMotion& m = wall.motion;
  const double speed = norm(m.velocity_m_per_s);
  if (!(speed > 0.0)) return -1.0;
  const double travel_at = [&](double t) {
    const double moving_s = std::max(0.0, std::min(t, m.stop_s) - m.start_s);
    return std::min(m.max_travel_m, wall.travel_m + speed * moving_s);
  }(start_s);
  const double to_go = depth_m - (wall.depth_at_start_m + travel_at);
  if (to_go <= 0.0) return 0.0;
  if (travel_at + to_go > m.max_travel_m * (1.0 + 1e-12)) return -1.0;
  const double reached_s = std::max(start_s, m.start_s) + to_go / speed;
  return reached_s > m.stop_s ? -1.0 : reached_s - start_s;
}

/// The particles a new site would overlap: a hash grid of cells as wide as the largest diameter.
class Occupancy {
 public:
  Occupancy(const ParticleStore& particles, double max_radius_m) : cell_(2.0 * max_radius_m) {
    for (std::size_t i = 0; i < particles.size(); ++i) add(particles.position_m[i], particles.radius_m[i]);
  }
  void add(const Vec3& x, double r) {
    cells_[key(cell_of(x.x), cell_of(x.y), cell_of(x.z))].push_back(centres_.size());
    centres_.push_back(x);
    radii_.push_back(r);
  }
  /// Whether a sphere there overlaps one held by more than `overlap_fraction` of their radii.
  bool overlaps(const Vec3& x, double r, double overlap_fraction) const {
    const long cx = cell_of(x.x), cy = cell_of(x.y), cz = cell_of(x.z);
    for (long dz = -1; dz <= 1; ++dz)
      for (long dy = -1; dy <= 1; ++dy)
        for (long dx = -1; dx <= 1; ++dx) {
          const auto found = cells_.find(key(cx + dx, cy + dy, cz + dz));
          if (found == cells_.end()) continue;
          for (std::size_t k : found->second) {
            const double reach = (r + radii_[k]) * (1.0 - overlap_fraction);
            if (norm2(centres_[k] - x) < reach * reach) return true;
          }
        }
    return false;
  }

 private:
  long cell_of(double c) const { return static_cast<long>(std::floor(c / cell_)); }
  static std::int64_t key(long x, long y, long z) { return (x * 73856093L) ^ (y * 19349663L) ^ (z * 83492791L); }
  double cell_;
  std::unordered_map<std::int64_t, std::vector<std::size_t>> cells_;
  std::vector<Vec3> centres_;
  std::vector<double> radii_;
};

/// Whether a sphere there cuts into a wall by more than `overlap_fraction` of its
/// diameter; a mesh wall (a drill) keeps its whole bounding box free, as placed.
bool hits_a_wall(const WallSet& walls, const Vec3& x, double r, double overlap_fraction) {
  for (const WallPrimitive& w : walls.primitives) {
    const WallProximity p = closest_wall_point(w, x);
    if (p.candidate && p.distance_m < r * (1.0 - 2.0 * overlap_fraction)) return true;
  }
  for (const MeshWall& mesh : walls.meshes) {
    const Aabb box = mesh.mesh.bounding_box();
    const RigidPose& pose = walls.bodies[mesh.body].pose;
    const Vec3 local = pose.to_reference(x);
    if (local.x > box.lo_m.x - r && local.y > box.lo_m.y - r && local.z > box.lo_m.z - r &&
        local.x < box.hi_m.x + r && local.y < box.hi_m.y + r && local.z < box.hi_m.z + r)
      return true;
  }
  return false;
}

/// Layers fill against gravity; without gravity, along a cylinder's axis or up z.
Vec3 packing_up(const Simulation& sim, const InsertionRegion& region) {
  const Vec3 g = sim.settings().gravity_m_per_s2;
  if (norm2(g) > 0.0) return normalized(g) * -1.0;
  return region.shape == InsertionShape::box ? Vec3{0, 0, 1} : region.axis;
}

/// Puts an insertion's particles in place at once: as listed for a file, on the
/// geometric packing otherwise. Returns how many it placed.
std::size_t place_insertion(Simulation& sim, const Insertion& ins, const EstimateOptions& options) {
  if (!ins.from_file.empty()) {
    for (const NewParticle& p : ins.from_file) sim.add_particle(p);
    return ins.from_file.size();
  }
  double max_radius = 0.0;
  for (double r : sim.particles.radius_m) max_radius = std::max(max_radius, r);
  for (const SizeClass& c : ins.sizes) max_radius = std::max(max_radius, c.radius_m);
  const Occupancy taken(sim.particles, max_radius);
  PackingOptions packing_options;
  packing_options.solid_fraction = options.solid_fraction;
  packing_options.overlap_fraction = options.overlap_fraction;
  packing_options.up = packing_up(sim, ins.region);
  const SiteIsFree free = [&](const Vec3& x, double r) {
    return !taken.overlaps(x, r, options.overlap_fraction) && !hits_a_wall(sim.walls, x, r, options.overlap_fraction);
  };
  Packing packing = pack_region(ins.region, ins.sizes, ins.target_count, packing_options, free);
  if (norm2(sim.settings().gravity_m_per_s2) > 0.0 && !packing.spheres.empty()) {
    // Onto the floor or the bed below, as the pour would land; no lower than the domain.
    const Vec3& up = packing_options.up;
    const Domain& domain = sim.settings().domain;
    double domain_low = 1e300, lowest = 1e300;
    for (int corner = 0; corner < 8; ++corner)
      domain_low = std::min(domain_low, dot(Vec3{corner & 1 ? domain.max_m.x : domain.min_m.x,
                                                 corner & 2 ? domain.max_m.y : domain.min_m.y,
                                                 corner & 4 ? domain.max_m.z : domain.min_m.z},
                                            up));
    for (const PackedSphere& s : packing.spheres) lowest = std::min(lowest, dot(s.centre_m, up) - s.radius_m);
    drop_onto_support(packing.spheres, up, lowest - domain_low, free);
  }
  for (const PackedSphere& s : packing.spheres) {
    NewParticle p;  // at rest: a bed, not a pour
    p.position_m = s.centre_m;
    p.radius_m = s.radius_m;
    p.density_kg_per_m3 = ins.density_kg_per_m3;
    p.material = ins.material;
    p.region = ins.tag;
    p.temperature_K = ins.temperature.at(s.centre_m);
    sim.add_particle(p);
  }
  return packing.spheres.size();
}

const char* end_name(const Stage& stage) {
  return stage.ends_on_measurement() ? "measurement"
         : stage.ends_at_depth()     ? "depth"
         : stage.until_settled       ? "settled"
                                     : "time";
}

/// Times up to options.sample_steps calls of `step` after the warm-up; fills the
/// sample fields of `cost`.
template <class Step>
void time_sample(StageCost& cost, std::size_t particles, const EstimateOptions& options, const NeighborList& lists,
                 Step&& step) {
  for (std::uint64_t w = 0; w < options.warmup_steps; ++w) step();
  cost.resident_bytes = resident_set_bytes();
  const std::uint64_t builds_before = lists.rebuild_count();
  const auto start = Clock::now();
  std::uint64_t done = 0;
  double elapsed = 0.0;
  while (done < options.sample_steps) {
    step();
    ++done;
    elapsed = seconds_since(start);
    if (elapsed >= options.sample_seconds) break;
  }
  cost.sampled = true;
  cost.sample_particles = particles;
  cost.sample_steps = done;
  cost.sample_wall_s = elapsed;
  cost.particle_steps_per_s = elapsed > 0.0 ? static_cast<double>(particles * done) / elapsed : 0.0;
  cost.builds_per_step = static_cast<double>(lists.rebuild_count() - builds_before) / static_cast<double>(done);
}

/// Whether a wall's motion is under way at some time in [start_s, end_s).
bool walls_move_during(const Simulation& sim, double start_s, double end_s) {
  const double slack_s = 1e-9 * (end_s - start_s);  // stage ends add up with round-off
  for (const WallBody& wall : sim.walls.bodies)
    if (wall.motion.moves() && wall.motion.start_s < end_s - slack_s && wall.motion.stop_s > start_s + slack_s &&
        end_s > start_s)
      return true;
  return false;
}

/// Takes out the particles a wall has moved into (by more than a tenth of their radius,
/// so that a bed resting on a floor keeps its bottom layer), and those inside a mesh.
/// Returns how many.
std::size_t clear_walls(Simulation& sim) {
  const ParticleStore& p = sim.particles;
  std::vector<char> remove(p.size(), 0);
  std::size_t count = 0;
  MeshTouchFinder finder;
  std::vector<MeshTouch> touches;
  for (const MeshWall& mesh : sim.walls.meshes) {
    std::vector<std::uint32_t> every(mesh.mesh.triangle_count());
    std::iota(every.begin(), every.end(), 0u);
    const RigidPose& pose = sim.walls.bodies[mesh.body].pose;
    const Aabb box = mesh.mesh.bounding_box();
    for (std::size_t i = 0; i < p.size(); ++i) {
      const double r = p.radius_m[i];
      const Vec3 local = pose.to_reference(p.position_m[i]);
      if (local.x < box.lo_m.x - r || local.y < box.lo_m.y - r || local.z < box.lo_m.z - r ||
          local.x > box.hi_m.x + r || local.y > box.hi_m.y + r || local.z > box.hi_m.z + r)
        continue;
      finder.find(mesh, pose, every.data(), static_cast<std::uint32_t>(every.size()), p.position_m[i], 0.9 * r,
                  touches);
      if (!touches.empty() || point_inside(mesh.mesh, local)) remove[i] = 1;
    }
  }
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (const WallPrimitive& w : sim.walls.primitives) {
      const WallProximity near = closest_wall_point(w, p.position_m[i]);
      if (near.candidate && near.distance_m < 0.9 * p.radius_m[i]) remove[i] = 1;
    }
    count += remove[i] ? 1 : 0;
  }
  sim.remove_particles(remove);
  return count;
}

/// Simulated time at the end of stage s, by the plan's durations and bounds.
double plan_end_s(const std::vector<StageCost>& costs, std::size_t s) {
  double end_s = 0.0;
  for (std::size_t k = 0; k <= s; ++k) end_s += costs[k].simulated_s;
  return end_s;
}

/// Events of a periodic schedule within a stage: by time, by steps, or by a wall's depth
/// (counted for a stage that ends at a depth, from the surface down; elsewhere not known).
std::uint64_t periodic_events(const SnapshotSchedule& schedule, const Stage& stage, const StageCost& cost) {
  const auto per = [](double span, double interval) {
    return interval > 0.0 ? static_cast<std::uint64_t>(std::ceil(span / interval)) : std::uint64_t{0};
  };
  switch (schedule.trigger) {
    case SnapshotSchedule::Trigger::none: return 0;
    case SnapshotSchedule::Trigger::time: return per(cost.simulated_s, schedule.interval_s);
    case SnapshotSchedule::Trigger::steps:
      return schedule.every_steps > 0 ? cost.steps / schedule.every_steps : 0;
    case SnapshotSchedule::Trigger::depth:
      return stage.ends_at_depth() ? per(stage.depth_m, schedule.depth_interval_m) : 0;
  }
  return 0;
}

/// What a run over ranks does between steps in this stage, at most (StageRunner; events
/// at one step share one): gather every particle on every rank (snapshots, insertion
/// attempts, bond forming, the end), or merge each rank's sums (samples, measurements,
/// the checks of a measured end).
struct PlannedEvents {
  std::uint64_t gathers = 0;
  std::uint64_t samples = 0;
  double merged_statistics = 0.0;  // regions' and profile bins' sums merged, over the stage
  std::uint64_t measurement_merges = 0;
};

PlannedEvents planned_events(const Stage& stage, const StageCost& cost, const StagePlan& plan, std::size_t s,
                             double start_s) {
  PlannedEvents events;
  if (stage.freezes_mechanics()) {
    events.gathers = 1;  // gathered for the whole stage
    return events;
  }
  // The time series' samples, at the runner's default interval when none is given.
  double sample_interval = plan.sample_interval_s > 0.0 ? plan.sample_interval_s
                           : stage.until_settled         ? 0.01
                                                         : cost.simulated_s / 100.0;
  sample_interval = std::max(sample_interval, cost.step_s);
  events.samples = 1 + static_cast<std::uint64_t>(std::ceil(cost.simulated_s / sample_interval));  // + the end
  // The end, the snapshots, every kSamplesPerGather-th sample.
  events.gathers = 1 + periodic_events(plan.snapshots, stage, cost) +
                   (events.samples + static_cast<std::uint64_t>(kSamplesPerGather) - 1) /
                       static_cast<std::uint64_t>(kSamplesPerGather);
  for (const Measurement& m : plan.measurements.items) {
    std::uint64_t takes = periodic_events(m.schedule.periodic, stage, cost);
    for (const double t : m.schedule.at_times_s) takes += t >= start_s && t < start_s + cost.simulated_s ? 1 : 0;
    if (stage.ends_at_depth()) takes += m.schedule.at_depths_m.size();  // as the periodic ones by depth
    if (m.schedule.with_time_series()) takes += events.samples;
    const double statistics = m.kind == MeasurementKind::profile ? static_cast<double>(m.profile.bin_count())
                              : m.kind == MeasurementKind::band  ? 2.0
                                                                 : 1.0;
    events.measurement_merges += takes;
    events.merged_statistics += static_cast<double>(takes) * statistics;
  }
  for (const Insertion& ins : plan.insertions)
    if (ins.stage == s)
      events.gathers += ins.rate_per_s > 0.0 && ins.interval_s > 0.0
                            ? static_cast<std::uint64_t>(std::ceil(cost.simulated_s / ins.interval_s))
                            : 1;
  if (stage.ends_on_measurement()) events.measurement_merges += cost.steps / 64;  // the target checked every 64 steps
  if (stage.form_bonds) ++events.gathers;
  return events;
}

/// The stage's sampled bed cut over each of options.ranks, and its cost there.
void project_over_ranks(StageCost& cost, const Simulation& sim, const StagePlan& plan, std::size_t s, double start_s,
                        const EstimateOptions& options) {
  if (!cost.sampled || cost.particle_steps_per_s <= 0.0) return;
  const Stage& stage = plan.stages[s];
  const CodeTraffic traffic =
      code_traffic(sim.bonds_configured(), sim.settings().lost_particles == LostParticles::remove);
  // A gathered particle: its fields, its contact count and contact histories, its bonds.
  const double n = static_cast<double>(sim.particles.size());
  const ContactStatistics& contacts = sim.contact_statistics();
  const double gathered_bytes_per_particle =
      static_cast<double>(traffic.gathered_bytes_per_particle + sizeof(std::uint32_t)) +
      static_cast<double>(contacts.particle_contacts + contacts.wall_contacts) / n *
          static_cast<double>(traffic.bytes_per_history_entry) +
      static_cast<double>(sim.bonds().size()) / n * static_cast<double>(traffic.bytes_per_bond);
  OneProcessStep one;
  one.particles = static_cast<double>(cost.particles);
  one.step_s = one.particles / cost.particle_steps_per_s;
  one.builds_per_step = cost.builds_per_step;
  const Domain& domain = sim.settings().domain;
  const std::vector<double> work = sim.particle_work();
  const PlannedEvents events = planned_events(stage, cost, plan, s, start_s);
  for (const int ranks : options.ranks) {
    StageOverRanks over;
    over.gathers = events.gathers;
    if (stage.freezes_mechanics()) {  // a static bed is stepped gathered, as one process
      over.step.ranks = ranks;
      over.step.efficiency = 1.0 / ranks;
      over.predicted_wall_s = cost.predicted_wall_s;
    } else {
      const RankShares shares = cut_into_bricks(Brick{domain.min_m, domain.max_m}, sim.particles.position_m,
                                                sim.particles.radius_m, work, sim.ghost_skin_m(), ranks);
      over.step = project_step(shares, one, options.network, traffic);
      over.gather_s = project_gather_s(one.particles, gathered_bytes_per_particle, ranks, one.step_s, options.network);
      over.merge_s =
          static_cast<double>(events.samples) *
              project_merge_s(traffic.collectives_per_sample, static_cast<double>(traffic.merged_bytes_per_sample),
                              ranks, options.network) +
          static_cast<double>(events.measurement_merges) *
              project_merge_s(traffic.collectives_per_measurement, 0.0, ranks, options.network) +
          project_merge_s(0, events.merged_statistics * static_cast<double>(traffic.merged_bytes_per_statistic), ranks,
                          options.network);
      over.predicted_wall_s = static_cast<double>(cost.steps) * over.step.step_s +
                              static_cast<double>(events.gathers) * over.gather_s + over.merge_s;
    }
    cost.over_ranks.push_back(over);
  }
}

}  // namespace

const char* step_count_name(StepCount basis) {
  switch (basis) {
    case StepCount::exact: return "exact";
    case StepCount::upper_bound: return "upper_bound";
    case StepCount::assumed: return "assumed";
  }
  return "exact";
}

double resident_set_bytes() {
  std::ifstream statm("/proc/self/statm");
  double pages_total = 0.0, pages_resident = 0.0;
  if (!(statm >> pages_total >> pages_resident)) return 0.0;
  return pages_resident * static_cast<double>(::sysconf(_SC_PAGESIZE));
}

std::vector<StageCost> plan_stage_costs(const Simulation& sim, const StagePlan& plan, const EstimateOptions& options) {
  std::vector<StageCost> costs;
  std::size_t particles = sim.particles.size();
  double stage_start_s = sim.time_s();
  for (std::size_t s = 0; s < plan.stages.size(); ++s) {
    const Stage& stage = plan.stages[s];
    StageCost cost;
    cost.name = stage.name;
    cost.end = end_name(stage);
    cost.static_bed = stage.freezes_mechanics();
    for (const Insertion& ins : plan.insertions)
      if (ins.stage == s) particles += ins.target_count;
    cost.particles = particles;
    cost.step_s = cost.static_bed ? stage.thermal_time_step_s : sim.time_step_s();

    if (stage.ends_at_depth()) {
      const WallBody& wall = sim.walls.bodies[static_cast<std::size_t>(stage.depth_body)];
      const double span_s = time_to_depth_s(wall, stage.depth_m, stage_start_s);
      if (span_s < 0.0) {
        cost.basis = StepCount::assumed;
        cost.simulated_s = std::max(stage.min_duration_s, options.unbounded_duration_s);
        cost.note = fmt::format("wall '{}' stops feeding before a depth of {:.4g} m: the run would fail; counted "
                                "as {:.4g} s",
                                wall.name, stage.depth_m, cost.simulated_s);
      } else {
        cost.simulated_s = span_s;
      }
    } else if (stage.until_settled || stage.ends_on_measurement()) {
      if (std::isfinite(stage.max_duration_s)) {
        cost.basis = StepCount::upper_bound;
        cost.simulated_s = stage.max_duration_s;
        cost.note = fmt::format("at most max_duration {:.4g} s", stage.max_duration_s);
      } else {
        cost.basis = StepCount::assumed;
        cost.simulated_s = std::max(stage.min_duration_s, options.unbounded_duration_s);
        cost.note = fmt::format("no max_duration: cannot be bounded; assumed {:.4g} s", cost.simulated_s);
      }
    } else {
      cost.simulated_s = stage.duration_s;
    }
    if (!cost.static_bed && cost.basis == StepCount::exact && !stage.ends_at_depth())
      cost.steps = static_cast<std::uint64_t>(std::llround(cost.simulated_s / cost.step_s));  // as the runner
    else if (cost.step_s > 0.0)
      cost.steps = steps_to_cover(cost.simulated_s, cost.step_s);
    stage_start_s += cost.simulated_s;
    costs.push_back(std::move(cost));
  }
  return costs;
}

RunEstimate estimate_run(Simulation& sim, const StagePlan& plan, const EstimateOptions& options,
                         const std::function<void(const std::string&)>& progress) {
  auto say = [&](const std::string& line) {
    if (progress) progress(line);
  };
  RunEstimate estimate;
  estimate.stages = plan_stage_costs(sim, plan, options);
  bool broken = false;  // a failed sample leaves the state unusable for the next
  for (std::size_t s = 0; s < plan.stages.size() && !broken; ++s) {
    const Stage& stage = plan.stages[s];
    StageCost& cost = estimate.stages[s];
    const std::string who = fmt::format("stage {}/{} '{}'", s + 1, plan.stages.size(), stage.name);
    try {
      std::size_t planned = 0, placed = 0;
      for (const Insertion& ins : plan.insertions)
        if (ins.stage == s) planned += ins.target_count, placed += place_insertion(sim, ins, options);
      if (planned > 0)
        say(fmt::format("{}: placed {} of its {} new particles at solid fraction {:.3g}{}", who, placed, planned,
                        options.solid_fraction, placed < planned ? " (their regions are full)" : ""));
      if (stage.form_bonds) {
        const BondFormation& f = *stage.form_bonds;
        const std::size_t formed = sim.form_bonds(f.gap_fraction, f.materials, f.regions);
        say(fmt::format("{}: formed {} bonds", who, formed));
      }
      const std::size_t n = sim.particles.size();
      if (n == 0) {
        cost.note = "no particles: nothing to time";
        continue;
      }
      if (stage.freezes_mechanics()) {
        const auto setup_start = Clock::now();
        StaticHeatStepper stepper(sim, stage);
        cost.setup_wall_s = seconds_since(setup_start);
        if (cost.step_s <= 0.0) {
          cost.step_s = stepper.time_step_s();
          cost.steps = steps_to_cover(cost.simulated_s, cost.step_s);
        }
        say(fmt::format("{}: static bed, heat step {:.4g} s, timing up to {} heat steps on {} particles", who,
                        cost.step_s, options.sample_steps, n));
        time_sample(cost, n, options, sim.neighbor_list(), [&] { stepper.advance(stepper.time_step_s()); });
      } else if (!walls_move_during(sim, plan_end_s(estimate.stages, s) - cost.simulated_s,
                                    plan_end_s(estimate.stages, s))) {
        say(fmt::format("{}: timing up to {} steps on {} particles", who, options.sample_steps, n));
        time_sample(cost, n, options, sim.neighbor_list(), [&] { sim.step(); });
      } else {
        // Walls move in this stage (a drill feeds): a step costs more once it is in the
        // bed, so the stage is timed in the middle of each third, the walls where they
        // will be then, the particles in their way taken out (the hole).
        const double end_s = plan_end_s(estimate.stages, s), start_s = end_s - cost.simulated_s;
        EstimateOptions third = options;
        third.sample_steps = std::max<std::uint64_t>(1, options.sample_steps / 3);
        third.sample_seconds = options.sample_seconds / 3.0;
        double seconds_per_particle_step = 0.0, resident = 0.0;
        std::size_t removed = 0;
        StageCost part;
        for (int p = 0; p < 3; ++p) {
          const double at_s = start_s + cost.simulated_s * (2.0 * p + 1.0) / 6.0;
          if (at_s > sim.time_s()) {
            sim.jump_to(at_s);
            removed += clear_walls(sim);
          }
          say(fmt::format("{}: moving walls at t = {:.4g} s, timing up to {} steps on {} particles", who, at_s,
                          third.sample_steps, sim.particles.size()));
          time_sample(part, sim.particles.size(), third, sim.neighbor_list(), [&] { sim.step(); });
          seconds_per_particle_step += 1.0 / part.particle_steps_per_s / 3.0;
          cost.builds_per_step += part.builds_per_step / 3.0;
          resident = std::max(resident, part.resident_bytes);
          cost.sample_steps += part.sample_steps;
          cost.sample_wall_s += part.sample_wall_s;
        }
        cost.sampled = true;
        cost.sample_particles = sim.particles.size();
        cost.particle_steps_per_s = 1.0 / seconds_per_particle_step;
        cost.resident_bytes = resident;
        cost.note += fmt::format("{}walls move: timed at 3 times in the stage with the walls where they will be "
                                 "({} particles in their way removed)",
                                 cost.note.empty() ? "" : "; ", removed);
      }
      cost.predicted_wall_s =
          cost.setup_wall_s + static_cast<double>(cost.steps) * static_cast<double>(cost.particles) / cost.particle_steps_per_s;
      const ContactStatistics& contacts = sim.contact_statistics();
      const double per_particle =
          (2.0 * static_cast<double>(contacts.particle_contacts) + static_cast<double>(contacts.wall_contacts)) /
          static_cast<double>(n);
      say(fmt::format("{}: {} steps in {:.3g} s, {:.3g} particle-steps/s; {:.2f} contacts per particle, "
                      "max overlap {:.2g} of a diameter, {} neighbour-list builds so far",
                      who, cost.sample_steps, cost.sample_wall_s, cost.particle_steps_per_s, per_particle,
                      sim.max_overlap_fraction(), sim.neighbor_list().rebuild_count()));
      if (!options.ranks.empty())
        project_over_ranks(cost, sim, plan, s, plan_end_s(estimate.stages, s) - cost.simulated_s, options);
    } catch (const std::exception& e) {  // a blow-up, a bond or heat step the bed refuses
      cost.note = fmt::format("sample failed: {}", e.what());
      say(fmt::format("{}: {}", who, cost.note));
      broken = true;
    }
  }
  estimate.over_ranks_wall_s.assign(options.ranks.size(), 0.0);
  estimate.over_ranks_gather_s.assign(options.ranks.size(), 0.0);
  for (const StageCost& cost : estimate.stages)
    for (std::size_t k = 0; k < cost.over_ranks.size(); ++k) {
      estimate.over_ranks_wall_s[k] += cost.over_ranks[k].predicted_wall_s;
      estimate.over_ranks_gather_s[k] += static_cast<double>(cost.over_ranks[k].gathers) * cost.over_ranks[k].gather_s;
    }
  for (const StageCost& cost : estimate.stages) {
    estimate.steps += cost.steps;
    estimate.predicted_wall_s += cost.predicted_wall_s;
    estimate.peak_resident_bytes = std::max(estimate.peak_resident_bytes, cost.resident_bytes);
    estimate.upper_bound = estimate.upper_bound || cost.basis == StepCount::upper_bound;
    estimate.assumed = estimate.assumed || cost.basis == StepCount::assumed;
    estimate.complete = estimate.complete && (cost.sampled || cost.particles == 0);
  }
  return estimate;
}

}  // namespace regodem
