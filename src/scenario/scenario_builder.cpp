#include "scenario/scenario_builder.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>

#include "core/error.hpp"
#include "io/particle_csv_reader.hpp"
#include "sim/simulation.hpp"
#include "sim/stage_plan.hpp"
#include "sim/stage_runner.hpp"
#include "sim/time_step.hpp"

namespace regodem {

struct PreparedRun::Impl {
  std::unique_ptr<Simulation> simulation;
  StagePlan plan;
  double rayleigh_time_s = 0.0;
  std::vector<std::string> description;
};

namespace {

[[noreturn]] void fail(const SourceLocation& where, const std::string& message) {
  throw InputError(fmt::format("{}: {}", where.describe(), message));
}

MaterialIndex material_index(const MaterialTable& table, const std::string& name, const SourceLocation& where) {
  const int index = table.find(name);
  if (index < 0) fail(where, fmt::format("material '{}' is not defined in `materials`", name));
  return static_cast<MaterialIndex>(index);
}

/// Pair properties: those given for the pair; for a wall material with none given,
/// those of the particle material with itself (DESIGN.md section 3).
void fill_pair_table(MaterialTable& table, const ScenarioSpec& spec, const std::vector<char>& particle_material) {
  const std::size_t n = table.size();
  std::vector<char> given(n * n, 0);
  for (const InteractionSpec& in : spec.interactions) {
    const MaterialIndex a = material_index(table, in.material_a, in.where);
    const MaterialIndex b = material_index(table, in.material_b, in.where);
    PairProperties p;
    p.restitution = in.restitution;
    p.sliding_friction = in.sliding_friction;
    p.rolling_friction = in.rolling_friction;
    p.clamp_attractive_normal_force = in.clamp_attractive_normal_force;
    table.set_pair(a, b, p);
    given[a * n + b] = given[b * n + a] = 1;
  }
  for (std::size_t a = 0; a < n; ++a) {
    if (!particle_material[a]) continue;
    if (!given[a * n + a])
      fail(spec.materials[a].where,
           fmt::format("particles of material '{}' meet each other, but `interactions` has no entry for "
                       "[{}, {}]",
                       table[static_cast<MaterialIndex>(a)].name, table[static_cast<MaterialIndex>(a)].name,
                       table[static_cast<MaterialIndex>(a)].name));
    for (std::size_t b = 0; b < n; ++b) {
      if (given[a * n + b]) continue;
      if (particle_material[b])
        fail(spec.materials[b].where,
             fmt::format("particles of materials '{}' and '{}' can meet, but `interactions` has no entry for them",
                         table[static_cast<MaterialIndex>(a)].name, table[static_cast<MaterialIndex>(b)].name));
      table.set_pair(static_cast<MaterialIndex>(a), static_cast<MaterialIndex>(b),
                     table.pair(static_cast<MaterialIndex>(a), static_cast<MaterialIndex>(a)));
    }
  }
}

bool parallel(const Vec3& a, const Vec3& b) { return norm(cross(normalized(a), normalized(b))) < 1e-9; }

WallMotion wall_motion(const WallSpec& w) {
  WallMotion m;
  m.velocity_m_per_s = w.motion.velocity_m_per_s;
  m.angular_velocity_rad_per_s = w.motion.angular_velocity_rad_per_s;
  m.axis_point_m = w.motion.axis_point_m;
  m.start_s = w.motion.start_s;
  m.stop_s = w.motion.stop_s;
  if (norm2(m.angular_velocity_rad_per_s) == 0.0) return m;
  // Analytic shapes may only spin about their own symmetry axis (their shape then
  // stays put); turning them any other way needs a mesh wall.
  const Vec3 axis = normalized(w.normal);
  if (!parallel(m.angular_velocity_rad_per_s, axis))
    fail(w.where, fmt::format("wall '{}': an analytic {} may only rotate about its own axis/normal", w.name,
                              w.shape == WallShape::plane ? "plane" : (w.shape == WallShape::disk ? "disk" : "cylinder")));
  if (w.shape != WallShape::plane) {
    const Vec3 offset = m.axis_point_m - w.point_m;
    if (norm(offset - axis * dot(offset, axis)) > 1e-9 * std::max(1.0, w.radius_m))
      fail(w.where, fmt::format("wall '{}': the rotation axis must pass through the wall's own axis", w.name));
  } else {
    m.axis_point_m = w.point_m + axis * dot(m.axis_point_m - w.point_m, axis);
  }
  return m;
}

InsertionRegion insertion_region(const RegionSpec& r) {
  InsertionRegion out;
  out.shape = r.shape == RegionShape::box ? InsertionShape::box
                                          : (r.shape == RegionShape::cylinder ? InsertionShape::cylinder
                                                                              : InsertionShape::annulus);
  out.min_m = r.min_m;
  out.max_m = r.max_m;
  out.base_m = r.base_m;
  out.axis = normalized(r.axis);
  out.length_m = r.length_m;
  out.radius_m = r.radius_m;
  out.inner_radius_m = r.inner_radius_m;
  return out;
}

std::size_t stage_index(const ScenarioSpec& spec, const std::string& name, const SourceLocation& where) {
  if (name.empty()) return 0;
  for (std::size_t s = 0; s < spec.stages.size(); ++s)
    if (spec.stages[s].name == name) return s;
  fail(where, fmt::format("no stage is named '{}'", name));
}

double sphere_volume(double r) { return 4.0 / 3.0 * std::numbers::pi * r * r * r; }

Insertion build_insertion(const ScenarioSpec& spec, const InsertionSpec& in, const MaterialTable& materials,
                          std::vector<std::string>& tags) {
  Insertion ins;
  ins.name = in.name;
  ins.material = material_index(materials, in.material, in.where);
  ins.density_kg_per_m3 = materials[ins.material].density_kg_per_m3;
  const std::string tag = in.region_tag.empty() ? in.name : in.region_tag;
  auto found = std::find(tags.begin(), tags.end(), tag);
  if (found == tags.end()) found = tags.insert(tags.end(), tag);
  ins.tag = static_cast<RegionTag>(found - tags.begin());
  ins.stage = stage_index(spec, in.stage, in.where);
  ins.velocity_m_per_s = in.initial_velocity_m_per_s;

  if (!in.from_file.empty()) {
    std::filesystem::path path(in.from_file);
    if (path.is_relative()) path = std::filesystem::path(spec.file).parent_path() / path;
    for (const ParticleRecord& r : read_particle_csv(path.string())) {
      NewParticle p;
      p.position_m = r.position_m;
      p.velocity_m_per_s = r.velocity_m_per_s;
      p.radius_m = r.radius_m;
      p.density_kg_per_m3 = ins.density_kg_per_m3;
      p.material = ins.material;
      p.region = ins.tag;
      ins.from_file.push_back(p);
    }
    ins.target_count = ins.from_file.size();
    return ins;
  }

  ins.region = insertion_region(in.region);
  // Number fractions from the given fractions (by number, or by mass: n_k ~ m_k / v_k).
  double total = 0.0;
  for (const SizeClassSpec& c : in.sizes) {
    const double share = in.fractions_by_mass ? c.fraction / sphere_volume(c.radius_m) : c.fraction;
    ins.sizes.push_back({c.radius_m, share});
    total += share;
  }
  double mean_volume = 0.0;
  for (SizeClass& c : ins.sizes) {
    c.number_fraction /= total;
    mean_volume += c.number_fraction * sphere_volume(c.radius_m);
  }
  switch (in.amount_kind) {
    case InsertAmount::count: ins.target_count = static_cast<std::size_t>(std::llround(in.amount)); break;
    case InsertAmount::solid_fraction:
      ins.target_count = static_cast<std::size_t>(std::llround(in.amount * ins.region.volume_m3() / mean_volume));
      break;
    case InsertAmount::mass:
      ins.target_count = static_cast<std::size_t>(std::llround(in.amount / (ins.density_kg_per_m3 * mean_volume)));
      break;
  }
  ins.rate_per_s = in.rate_per_s;
  ins.interval_s = in.interval_s > 0.0 ? in.interval_s : 0.01;
  return ins;
}

}  // namespace

PreparedRun::PreparedRun() : impl_(std::make_unique<Impl>()) {}
PreparedRun::PreparedRun(PreparedRun&&) noexcept = default;
PreparedRun& PreparedRun::operator=(PreparedRun&&) noexcept = default;
PreparedRun::~PreparedRun() = default;

PreparedRun PreparedRun::build(const ScenarioSpec& spec, int threads) {
  if (threads < 1) throw InputError(fmt::format("--threads must be at least 1, got {}", threads));
  PreparedRun run;
  Impl& impl = *run.impl_;
  std::vector<std::string>& lines = impl.description;

  MaterialTable materials;
  for (const MaterialSpec& m : spec.materials)
    materials.add({m.name, m.density_kg_per_m3, m.shear_modulus_Pa, m.poisson_ratio});

  // Insertions first: they say which materials are particles and which sizes occur.
  std::vector<std::string> tags;
  std::vector<char> particle_material(materials.size(), 0);
  double min_radius = std::numeric_limits<double>::infinity();
  double min_rayleigh = std::numeric_limits<double>::infinity();
  for (const InsertionSpec& in : spec.insertions) {
    Insertion ins = build_insertion(spec, in, materials, tags);
    particle_material[ins.material] = 1;
    const Material& m = materials[ins.material];
    auto consider = [&](double r) {
      min_radius = std::min(min_radius, r);
      min_rayleigh = std::min(min_rayleigh, rayleigh_time_s(r, m.density_kg_per_m3, m.shear_modulus_Pa, m.poisson_ratio));
    };
    for (const SizeClass& c : ins.sizes) consider(c.radius_m);
    for (const NewParticle& p : ins.from_file) consider(p.radius_m);
    if (ins.from_file.empty())
      lines.push_back(fmt::format("insertion '{}': {} particles of '{}' ({} size class{}){}, during stage '{}'",
                                  ins.name, ins.target_count, m.name, ins.sizes.size(), ins.sizes.size() == 1 ? "" : "es",
                                  ins.rate_per_s > 0 ? fmt::format(" at {:.4g} /s", ins.rate_per_s) : " all at once",
                                  spec.stages[ins.stage].name));
    else
      lines.push_back(fmt::format("insertion '{}': {} particles of '{}' from {}", ins.name, ins.target_count, m.name,
                                  in.from_file));
    impl.plan.insertions.push_back(std::move(ins));
  }
  if (impl.plan.insertions.empty()) fail(SourceLocation{spec.file, 0, 0, "insertions"}, "no insertions: there would be no particles");
  fill_pair_table(materials, spec, particle_material);

  WallSet walls;
  for (const WallSpec& w : spec.walls) {
    const MaterialIndex material =
        w.material.empty() ? MaterialIndex{0} : material_index(materials, w.material, w.where);
    const std::uint32_t body = walls.add_body(w.name, wall_motion(w));
    switch (w.shape) {
      case WallShape::plane: walls.add_plane(body, w.point_m, w.normal, material); break;
      case WallShape::disk: walls.add_disk(body, w.point_m, w.normal, w.radius_m, material); break;
      case WallShape::cylinder:
        walls.add_cylinder(body, w.point_m, w.normal, w.radius_m, w.length_m, w.side != CylinderSide::outside,
                           w.side != CylinderSide::inside, w.cap_bottom, w.cap_top, material);
        break;
    }
  }
  lines.push_back(fmt::format("walls: {} ({} analytic primitives)", walls.bodies.size(), walls.primitives.size()));

  impl.rayleigh_time_s = min_rayleigh;
  double dt = spec.time_step_s > 0.0 ? spec.time_step_s : spec.rayleigh_fraction * min_rayleigh;
  if (spec.time_step_s > 0.0 && spec.time_step_s > spec.max_rayleigh_fraction * min_rayleigh)
    fail(SourceLocation{spec.file, 0, 0, "time_step"},
         fmt::format("the time step {:.4g} s is above the stable limit {:.4g} s ({} x the Rayleigh time {:.4g} s "
                     "of the smallest particle, radius {:.4g} m); use at most that, e.g. `time_step: auto` for "
                     "{} x the Rayleigh time",
                     spec.time_step_s, spec.max_rayleigh_fraction * min_rayleigh, spec.max_rayleigh_fraction,
                     min_rayleigh, min_radius, spec.rayleigh_fraction));
  if (spec.time_step_s <= 0.0 && spec.rayleigh_fraction > spec.max_rayleigh_fraction)
    fail(SourceLocation{spec.file, 0, 0, "rayleigh_fraction"},
         fmt::format("rayleigh_fraction {} is above the stable limit {}", spec.rayleigh_fraction,
                     spec.max_rayleigh_fraction));
  lines.insert(lines.begin(), fmt::format("time step {:.4g} s = {:.3g} x the Rayleigh time {:.4g} s of the smallest "
                                          "particle (radius {:.4g} m)",
                                          dt, dt / min_rayleigh, min_rayleigh, min_radius));

  SimulationSettings settings;
  settings.domain = {spec.domain.min_m, spec.domain.max_m};
  settings.gravity_m_per_s2 = spec.gravity_m_per_s2;
  settings.time_step_s = dt;
  settings.neighbor_skin_m = spec.neighbor_skin_m > 0.0 ? spec.neighbor_skin_m : 0.2 * min_radius;
  settings.min_particle_radius_m = min_radius;
  settings.threads = threads;
  impl.simulation = std::make_unique<Simulation>(std::move(materials), std::move(walls), settings);

  for (const StageSpec& st : spec.stages) {
    Stage stage;
    stage.name = st.name;
    stage.until_settled = st.end == StageEnd::settled;
    stage.duration_s = st.duration_s;
    stage.settled_kinetic_energy_J = st.settled_kinetic_energy_J;
    stage.min_duration_s = st.min_duration_s;
    stage.max_duration_s = st.max_duration_s;
    for (const OverrideSpec& o : st.overrides) {
      PairOverride po;
      if (!o.material_a.empty()) {
        po.material_a = material_index(impl.simulation->materials, o.material_a, o.where);
        po.material_b = material_index(impl.simulation->materials, o.material_b.empty() ? o.material_a : o.material_b, o.where);
      }
      po.restitution = o.restitution;
      po.sliding_friction = o.sliding_friction;
      po.rolling_friction = o.rolling_friction;
      stage.overrides.push_back(po);
    }
    lines.push_back(stage.until_settled
                        ? fmt::format("stage '{}': until settled (kinetic energy per particle < {:.3g} J), at most {:.4g} s",
                                      stage.name, stage.settled_kinetic_energy_J, stage.max_duration_s)
                        : fmt::format("stage '{}': {:.4g} s ({:.0f} steps)", stage.name, stage.duration_s,
                                      std::round(stage.duration_s / dt)));
    impl.plan.stages.push_back(std::move(stage));
  }
  impl.plan.sample_interval_s = spec.output.interval_s;
  impl.plan.seed = spec.seed;
  return run;
}

RunOutcome PreparedRun::run(RunObserver& observer, const std::atomic<bool>& stop_requested) {
  return run_stages(*impl_->simulation, impl_->plan, observer, stop_requested);
}

std::vector<std::string> PreparedRun::describe() const { return impl_->description; }
const Simulation& PreparedRun::simulation() const { return *impl_->simulation; }
double PreparedRun::time_step_s() const { return impl_->simulation->time_step_s(); }
int PreparedRun::threads() const { return impl_->simulation->threads(); }

}  // namespace regodem
