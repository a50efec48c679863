#include "scenario/scenario_builder.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>
#include <optional>

#include "core/error.hpp"
#include "geometry/mesh_axial_segments.hpp"
#include "io/checkpoint_file.hpp"
#include "io/particle_csv_reader.hpp"
#include "scenario/conduction_pairs.hpp"
#include "scenario/wall_speed_check.hpp"
#include "sim/simulation.hpp"
#include "sim/stage_plan.hpp"
#include "sim/stage_runner.hpp"
#include "scenario/plan_limits.hpp"
#include "sim/overlap_scan.hpp"
#include "sim/time_step.hpp"
#include "thermal/lumped_wall_step.hpp"
#include "thermal/thermal_wall.hpp"
#include "thermal/time_table.hpp"

namespace regodem {

struct PreparedRun::Impl {
  std::unique_ptr<Simulation> simulation;
  StagePlan plan;
  double rayleigh_time_s = 0.0;
  std::vector<std::string> description;
  std::vector<std::string> warnings;
};

namespace {

/// The reader has checked the name.
HeatPartitionModel heat_partition_model(const std::string& name) {
  if (name == "equal") return HeatPartitionModel::equal;
  if (name == "conductivity") return HeatPartitionModel::conductivity;
  if (name == "effusivity") return HeatPartitionModel::effusivity;
  return HeatPartitionModel::fixed;
}

[[noreturn]] void fail(const SourceLocation& where, const std::string& message) {
  throw InputError(fmt::format("{}: {}", where.describe(), message));
}

MaterialIndex material_index(const MaterialTable& table, const std::string& name, const SourceLocation& where) {
  const int index = table.find(name);
  if (index < 0) fail(where, fmt::format("material '{}' is not defined in `materials`", name));
  return static_cast<MaterialIndex>(index);
}

ConductionLaw conduction_law(ConductionLawSpec law) {
  switch (law) {
    case ConductionLawSpec::force: return ConductionLaw::force;
    case ConductionLawSpec::radius: return ConductionLaw::radius;
    case ConductionLawSpec::area: return ConductionLaw::area;
    case ConductionLawSpec::none: return ConductionLaw::none;
  }
  return ConductionLaw::force;
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
    p.rolling_model = in.rolling_own_spin ? RollingModel::own_spin : RollingModel::relative_spin;
    p.clamp_attractive_normal_force = in.clamp_attractive_normal_force;
    p.conduction = conduction_law(in.conduction);
    p.heat_transfer_coefficient_W_per_m2K = in.heat_transfer_coefficient_W_per_m2K;
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

/// A property curve; a bad table (which the reader refuses already) names its key.
TemperatureCurve curve_of(const TemperatureCurveSpec& spec) {
  try {
    if (spec.temperature_K.empty()) return TemperatureCurve(spec.constant);
    return TemperatureCurve(spec.temperature_K, spec.value);
  } catch (const InputError& problem) {
    fail(spec.where, problem.what());
  }
}

Material material_of(const MaterialSpec& m) {
  Material material;
  material.name = m.name;
  material.density_kg_per_m3 = m.density_kg_per_m3;
  material.shear_modulus_Pa = m.shear_modulus_Pa;
  material.poisson_ratio = m.poisson_ratio;
  if (m.conductivity_W_per_mK) material.conductivity_W_per_mK = curve_of(*m.conductivity_W_per_mK);
  if (m.specific_heat_J_per_kgK) material.specific_heat_J_per_kgK = curve_of(*m.specific_heat_J_per_kgK);
  material.real_shear_modulus_Pa = m.real_shear_modulus_Pa;
  return material;
}

std::string curve_text(const TemperatureCurve& curve, const char* unit) {
  if (curve.is_constant()) return fmt::format("{:.4g} {}", curve.at(0.0), unit);
  return fmt::format("{:.4g} to {:.4g} {} over {:.4g} to {:.4g} K ({} rows)", curve.table_values().front(),
                     curve.table_values().back(), unit, curve.table_temperatures_K().front(),
                     curve.table_temperatures_K().back(), curve.table_values().size());
}

const char* shape_name(WallShape shape) {
  switch (shape) {
    case WallShape::plane: return "plane";
    case WallShape::disk: return "disk";
    case WallShape::cylinder: return "cylinder";
    case WallShape::sieve: return "sieve";
    case WallShape::mesh: return "mesh";
    case WallShape::auger: return "auger";
  }
  return "wall";
}

/// The body whose depth a stage end or a snapshot schedule follows: it must exist and feed.
int fed_wall_index(const WallSet& walls, const std::string& name, const SourceLocation& where,
                   const std::string& who) {
  const auto named = std::find_if(walls.bodies.begin(), walls.bodies.end(),
                                  [&](const WallBody& b) { return b.name == name; });
  if (named == walls.bodies.end()) fail(where, fmt::format("{}: no wall named '{}' to measure the depth of", who, name));
  if (norm(named->motion.velocity_m_per_s) == 0.0)
    fail(where, fmt::format("{}: wall '{}' has no feed (motion velocity), so its depth never changes", who, name));
  return static_cast<int>(named - walls.bodies.begin());
}

/// A stage's `until: {measurement, quantity, ...}`: the measurement must exist, be a
/// region or a band, and have the quantity asked for; a band needs heat on to mean anything.
MeasurementTarget measurement_target(const StageSpec& st, const MeasurementPlan& plan) {
  const auto named = std::find_if(plan.items.begin(), plan.items.end(),
                                  [&](const Measurement& m) { return m.name == st.until_measurement; });
  const std::string who = fmt::format("stage '{}'", st.name);
  if (named == plan.items.end())
    fail(st.where, fmt::format("{} waits for measurement '{}', but no region or band has that name", who,
                               st.until_measurement));
  const bool band_quantity = st.until_quantity.starts_with("T_");
  if (named->kind == MeasurementKind::profile)
    fail(st.where, fmt::format("{} waits for '{}', a profile: wait for a region or a band", who, named->name));
  if (band_quantity != (named->kind == MeasurementKind::band))
    fail(st.where, fmt::format("{} waits for {} of '{}', a {}: a band gives T_in, T_out or T_d, a region mean, min or max",
                               who, st.until_quantity, named->name,
                               named->kind == MeasurementKind::band ? "band" : "region"));
  MeasurementTarget target;
  target.measurement = static_cast<std::size_t>(named - plan.items.begin());
  target.quantity = st.until_quantity == "mean"    ? MeasuredQuantity::mean
                    : st.until_quantity == "min"   ? MeasuredQuantity::min
                    : st.until_quantity == "max"   ? MeasuredQuantity::max
                    : st.until_quantity == "T_in"  ? MeasuredQuantity::T_in
                    : st.until_quantity == "T_out" ? MeasuredQuantity::T_out
                                                   : MeasuredQuantity::T_d;
  target.rising = st.until_rising;
  target.value_K = st.until_value_K;
  return target;
}

/// The body of a wall named in the scenario (a sieve's: its first segment; they move as one).
int wall_body_index(const WallSet& walls, const std::string& name, const SourceLocation& where) {
  for (std::size_t b = 0; b < walls.bodies.size(); ++b)
    if (walls.bodies[b].name == name || walls.bodies[b].name == name + "[1]") return static_cast<int>(b);
  fail(where, fmt::format("no wall named '{}'", name));
}

/// The plan's measurements with their walls resolved to bodies.
MeasurementPlan measurement_plan(const MeasurementsSpec& spec, const WallSet& walls, std::vector<std::string>& lines) {
  MeasurementPlan plan;
  for (const MeasurementSpec& in : spec.items) {
    Measurement m = in.measurement;
    if (!in.moves_with.empty()) m.follow_body = wall_body_index(walls, in.moves_with, in.where);
    const std::string who = fmt::format("measurement '{}'", m.name);
    if (!in.depth_wall.empty()) {
      m.depth_body = fed_wall_index(walls, in.depth_wall, in.where, who);
      m.schedule.periodic.depth_body = m.depth_body;
    } else if (m.follow_body >= 0 && norm2(walls.bodies[static_cast<std::size_t>(m.follow_body)].motion.velocity_m_per_s) > 0.0) {
      m.depth_body = m.follow_body;  // a region riding on a drill: its depth is worth a column
    }
    const char* kind = m.kind == MeasurementKind::region ? "region" : m.kind == MeasurementKind::band ? "band" : "profile";
    const MeasurementSchedule& s = m.schedule;
    const SnapshotSchedule& p = s.periodic;
    const std::string when =
        p.trigger == SnapshotSchedule::Trigger::time    ? fmt::format("every {:.4g} s", p.interval_s)
        : p.trigger == SnapshotSchedule::Trigger::steps ? fmt::format("every {} steps", p.every_steps)
        : p.trigger == SnapshotSchedule::Trigger::depth ? fmt::format("every {:.4g} m of wall '{}''s depth", p.depth_interval_m, in.depth_wall)
        : !s.at_times_s.empty()                         ? fmt::format("at {} times", s.at_times_s.size())
        : !s.at_depths_m.empty()                        ? fmt::format("at {} depths of wall '{}'", s.at_depths_m.size(), in.depth_wall)
                                                        : std::string("with the time series");
    lines.push_back(fmt::format("measurement '{}': {}, {}{}", m.name, kind, when,
                                in.moves_with.empty() ? "" : fmt::format(", moving with wall '{}'", in.moves_with)));
    plan.items.push_back(std::move(m));
  }
  return plan;
}

bool parallel(const Vec3& a, const Vec3& b) { return norm(cross(normalized(a), normalized(b))) < 1e-9; }

WallMotion wall_motion(const WallSpec& w) {
  WallMotion m;
  m.velocity_m_per_s = w.motion.velocity_m_per_s;
  m.angular_velocity_rad_per_s = w.motion.angular_velocity_rad_per_s;
  m.axis_point_m = w.motion.axis_point_m;
  m.start_s = w.motion.start_s;
  m.stop_s = w.motion.stop_s;
  m.max_travel_m = w.motion.stop_at_depth_m - w.motion.depth_at_start_m;  // infinite without a stop depth
  m.max_thrust_N = w.motion.stop_at_thrust_N;
  // A mesh turns as a rigid body about any axis.
  if (norm2(m.angular_velocity_rad_per_s) == 0.0 || w.mesh) return m;
  // Analytic shapes may only spin about their own symmetry axis (their shape then
  // stays put); turning them any other way needs a mesh wall.
  const Vec3 axis = normalized(w.normal);
  if (!parallel(m.angular_velocity_rad_per_s, axis))
    fail(w.where,
         fmt::format("wall '{}': an analytic {} may only rotate about its own axis/normal", w.name, shape_name(w.shape)));
  if (w.shape != WallShape::plane) {
    const Vec3 offset = m.axis_point_m - w.point_m;
    if (norm(offset - axis * dot(offset, axis)) > 1e-9 * std::max(1.0, w.radius_m))
      fail(w.where, fmt::format("wall '{}': the rotation axis must pass through the wall's own axis", w.name));
  } else {
    m.axis_point_m = w.point_m + axis * dot(m.axis_point_m - w.point_m, axis);
  }
  return m;
}

/// The wall's own conductivity: its thermal block's, else that of the material it
/// names (a table at the wall's initial temperature), else none (the particles' own);
/// none too when the block says `conductivity: particles`.
std::optional<double> wall_conductivity(const ScenarioSpec& spec, const WallSpec& w, double initial_K) {
  if (w.thermal.conductivity_of_particles) return std::nullopt;
  if (w.thermal.conductivity_W_per_mK) return w.thermal.conductivity_W_per_mK;
  if (w.material.empty()) return std::nullopt;
  for (const MaterialSpec& m : spec.materials) {
    if (m.name != w.material || !m.conductivity_W_per_mK) continue;
    return curve_of(*m.conductivity_W_per_mK).at(initial_K);
  }
  return std::nullopt;
}

/// The thermal body of one wall body (one sieve segment); area_m2 serves areal density.
ThermalWall thermal_wall(const ScenarioSpec& spec, const WallSpec& w, double area_m2) {
  const WallThermalSpec& t = w.thermal;
  ThermalWall out;
  switch (t.mode) {
    case WallThermalModeSpec::adiabatic: out.mode = WallThermalMode::adiabatic; return out;
    case WallThermalModeSpec::fixed: out.mode = WallThermalMode::fixed; break;
    case WallThermalModeSpec::lumped: out.mode = WallThermalMode::lumped; break;
  }
  try {
    out.prescribed_temperature_K = TimeTable(t.time_s, t.temperature_K);
  } catch (const InputError& problem) {
    fail(t.where, problem.what());
  }
  out.initial_temperature_K = out.prescribed_temperature_K.at(0.0);
  if (out.mode == WallThermalMode::lumped) {
    out.prescribed_temperature_K = TimeTable();  // only the initial value was a table row
    const double mass_kg = t.mass_kg > 0.0 ? t.mass_kg : t.areal_density_kg_per_m2 * area_m2;
    if (!(mass_kg > 0.0))
      fail(t.where, fmt::format("wall '{}': a lumped wall needs a mass ('mass', or 'areal_density' of a wall with an "
                                "area)",
                                w.name));
    out.heat_capacity_J_per_K = mass_kg * t.specific_heat_J_per_kgK;
  }
  out.conductivity_W_per_mK = wall_conductivity(spec, w, out.initial_temperature_K);
  out.mix = t.harmonic_mean ? WallConductivityMix::harmonic_mean : WallConductivityMix::wall;
  out.rod.area_m2 = area_m2;
  out.rod.emissivity = t.emissivity;
  out.rod.surroundings_K = t.surroundings_K;
  return out;
}

/// A lumped mesh wall as a rod along its axis (docs/drilling-heat.md): its triangles
/// cut into `segments` slices, each slice's m C by its share of the area, neighbours
/// linked by k A / dz and the last (far from the tip) to a held end by k A / (dz / 2).
void make_rod(const ScenarioSpec& spec, const WallSpec& w, MeshWall& mesh, ThermalWall& out) {
  const WallThermalSpec& t = w.thermal;
  if (out.mode != WallThermalMode::lumped || (t.segments <= 1 && !t.held_end_K)) return;
  MeshAxialSegments cut;
  try {
    cut = split_mesh_along_axis(mesh.mesh, w.normal, t.segments);
  } catch (const InputError& problem) {
    fail(t.where, fmt::format("wall '{}': {}", w.name, problem.what()));
  }
  std::optional<double> k = t.rod_conductivity_W_per_mK;
  if (!k) {
    for (const MaterialSpec& m : spec.materials)
      if (m.name == w.material && m.conductivity_W_per_mK) k = curve_of(*m.conductivity_W_per_mK).at(out.initial_temperature_K);
  }
  if (!k || !(*k > 0.0))
    fail(t.where, fmt::format("wall '{}': its rod conducts along its axis: give `rod: {{conductivity: ...}}` or a "
                              "conductivity for its material",
                              w.name));
  const double dz_m = cut.length_m / static_cast<double>(t.segments);
  const double conductance = *k * t.rod_cross_section_m2 / dz_m;
  if (t.held_end_K) {
    out.rod.held_end_K = t.held_end_K;
    out.rod.held_end_conductance_W_per_K = 2.0 * conductance;
  }
  if (t.segments <= 1) return;
  out.rod.link_conductance_W_per_K = conductance;
  const double total_area = mesh.mesh.area();
  for (double a : cut.area_m2) {
    out.rod.segment_heat_capacity_J_per_K.push_back(out.heat_capacity_J_per_K * a / total_area);
    out.rod.segment_area_m2.push_back(a);
  }
  mesh.triangle_segment = std::move(cut.triangle_segment);
}

/// The rod's part of a lumped wall's line in the plan (nothing for a plain lumped wall).
std::string describe_heat_paths(const ThermalWall& t) {
  std::string out;
  const WallRod& rod = t.rod;
  if (rod.segmented())
    out += fmt::format("; {} axial segments (1 at the tip), m C {:.4g} to {:.4g} J/K, linked by {:.4g} W/K",
                       rod.segment_heat_capacity_J_per_K.size(),
                       *std::min_element(rod.segment_heat_capacity_J_per_K.begin(), rod.segment_heat_capacity_J_per_K.end()),
                       *std::max_element(rod.segment_heat_capacity_J_per_K.begin(), rod.segment_heat_capacity_J_per_K.end()),
                       rod.link_conductance_W_per_K);
  if (rod.held_end_K)
    out += fmt::format("; far end held at {:.5g} K through {:.4g} W/K", *rod.held_end_K, rod.held_end_conductance_W_per_K);
  if (rod.emissivity > 0.0)
    out += fmt::format("; radiates with emissivity {:.3g} to {:.5g} K", rod.emissivity, rod.surroundings_K);
  return out;
}

/// One line per wall on its thermal side (heat on only); a sieve's segments differ at
/// most in heat capacity (the capped one has its bottom too), from t to largest_capacity.
std::string describe_thermal_wall(const WallSpec& w, const ThermalWall& t, int segments,
                                  double largest_capacity_J_per_K) {
  const std::string who = segments > 1 ? fmt::format("sieve '{}' ({} segments '{}[1]' at the top to '{}[{}]' at the "
                                                     "bottom, each)",
                                                     w.name, segments, w.name, w.name, segments)
                                       : fmt::format("wall '{}'", w.name);
  const std::string k = t.conductivity_W_per_mK ? fmt::format("{:.4g} W/(m K)", *t.conductivity_W_per_mK)
                                                : std::string("the particles' own");
  const std::string mix = t.mix == WallConductivityMix::harmonic_mean ? ", harmonic mean with the particle's" : "";
  switch (t.mode) {
    case WallThermalMode::adiabatic: return fmt::format("{}: adiabatic", who);
    case WallThermalMode::fixed: {
      const TimeTable& table = t.prescribed_temperature_K;
      const std::string temperature =
          table.values().size() == 1
              ? fmt::format("{:.5g} K", table.values().front())
              : fmt::format("{:.5g} K to {:.5g} K over {:.4g} to {:.4g} s ({} rows)", table.values().front(),
                            table.values().back(), table.times_s().front(), table.times_s().back(),
                            table.values().size());
      return fmt::format("{}: fixed at {}; conductivity {}{}", who, temperature, k, mix);
    }
    case WallThermalMode::lumped: {
      const std::string capacity =
          largest_capacity_J_per_K > t.heat_capacity_J_per_K
              ? fmt::format("{:.4g} J/K ({:.4g} J/K with the bottom)", t.heat_capacity_J_per_K, largest_capacity_J_per_K)
              : fmt::format("{:.4g} J/K", t.heat_capacity_J_per_K);
      return fmt::format("{}: lumped, heat capacity m C = {}, initially {:.5g} K; conductivity {}{}{}", who, capacity,
                         t.initial_temperature_K, k, mix, describe_heat_paths(t));
    }
  }
  return who;
}

double disk_area(double r) { return std::numbers::pi * r * r; }

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

HeatStepping heat_stepping(ThermalStepping method) {
  switch (method) {
    case ThermalStepping::coupled: return HeatStepping::coupled;
    case ThermalStepping::static_explicit: return HeatStepping::static_explicit;
    case ThermalStepping::static_backward_euler: return HeatStepping::static_backward_euler;
    case ThermalStepping::static_crank_nicolson: return HeatStepping::static_crank_nicolson;
  }
  return HeatStepping::coupled;
}

const char* heat_method_name(HeatStepping method) {
  switch (method) {
    case HeatStepping::coupled: return "coupled stepping";
    case HeatStepping::static_explicit: return "explicit Euler";
    case HeatStepping::static_backward_euler: return "backward Euler";
    case HeatStepping::static_crank_nicolson: return "Crank-Nicolson";
  }
  return "coupled stepping";
}

double sphere_volume(double r) { return 4.0 / 3.0 * std::numbers::pi * r * r * r; }

/// A packing from a file must lie in the domain and not overlap itself more than the
/// insertion allows: the contact law would blast a 90 % overlap apart on the first step.
void check_file_packing(const ScenarioSpec& spec, const InsertionSpec& in, const std::vector<ParticleRecord>& records) {
  const Vec3 lo = spec.domain.min_m, hi = spec.domain.max_m;
  for (const ParticleRecord& r : records) {
    const Vec3& x = r.position_m;
    if (x.x - r.radius_m < lo.x || x.y - r.radius_m < lo.y || x.z - r.radius_m < lo.z || x.x + r.radius_m > hi.x ||
        x.y + r.radius_m > hi.y || x.z + r.radius_m > hi.z)
      fail(in.where, fmt::format("{}:{}: the particle at ({:.6g}, {:.6g}, {:.6g}) m, radius {:.4g} m, is not wholly "
                                 "inside the domain [{:.6g}, {:.6g}, {:.6g}] to [{:.6g}, {:.6g}, {:.6g}] m",
                                 in.from_file, r.line, x.x, x.y, x.z, r.radius_m, lo.x, lo.y, lo.z, hi.x, hi.y, hi.z));
  }
  std::vector<Vec3> positions;
  std::vector<double> radii;
  for (const ParticleRecord& r : records) {
    positions.push_back(r.position_m);
    radii.push_back(r.radius_m);
  }
  const DeepestOverlap deepest = deepest_overlap(positions, radii);
  if (deepest.fraction > in.max_overlap_fraction)
    fail(in.where, fmt::format("{}: the particles of lines {} and {} overlap by {:.3g} of the smaller diameter, more "
                               "than the {:.3g} accepted (`max_overlap`); the contact law would fling them apart. Is "
                               "the file in metres, and a settled packing?",
                               in.from_file, records[deepest.i].line, records[deepest.j].line, deepest.fraction,
                               in.max_overlap_fraction));
}

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
  if (in.temperature) {
    ins.temperature.value_K = in.temperature->value_K;
    ins.temperature.gradient_K_per_m = in.temperature->gradient_K_per_m;
    ins.temperature.reference_point_m = in.temperature->reference_point_m;
  }

  if (!in.from_file.empty()) {
    std::filesystem::path path(in.from_file);
    if (path.is_relative()) path = std::filesystem::path(spec.file).parent_path() / path;
    const std::vector<ParticleRecord> records = read_particle_csv(path.string());
    std::size_t without_temperature = 0;
    std::size_t first_without = 0;
    for (const ParticleRecord& r : records) {
      NewParticle p;
      p.position_m = r.position_m;
      p.velocity_m_per_s = r.velocity_m_per_s;
      p.radius_m = r.radius_m;
      p.density_kg_per_m3 = ins.density_kg_per_m3;
      p.material = ins.material;
      p.region = ins.tag;
      // The file's temperature column wins; else the insertion's field at the particle.
      if (r.has_temperature) {
        p.temperature_K = r.temperature_K;
      } else {
        if (!in.temperature && without_temperature++ == 0) first_without = ins.from_file.size();
        p.temperature_K = ins.temperature.at(p.position_m);
      }
      if (p.temperature_K < 0.0)
        fail(in.where, fmt::format("particle {} of {} would start at {:.4g} K, below absolute zero",
                                   ins.from_file.size() + 1, in.from_file, p.temperature_K));
      ins.from_file.push_back(p);
      ins.from_file_lines.push_back(r.line);
    }
    if (spec.heat.enabled && without_temperature > 0)
      fail(in.where, fmt::format("heat is on, but {} gives no temperature for {} of its {} particles (the first is "
                                 "particle {}): add a `temperature` column or the insertion's `temperature`",
                                 in.from_file, without_temperature, records.size(), first_without + 1));
    check_file_packing(spec, in, records);
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
  double count = 0.0;
  switch (in.amount_kind) {
    case InsertAmount::count: count = in.amount; break;
    case InsertAmount::solid_fraction: count = in.amount * ins.region.volume_m3() / mean_volume; break;
    case InsertAmount::mass: count = in.amount / (ins.density_kg_per_m3 * mean_volume); break;
  }
  // Checked before the conversion, which would overflow; the memory check then says
  // whether this machine can hold them.
  if (!(std::round(count) <= max_particles_per_insertion))
    fail(in.where, fmt::format("insertion '{}' asks for {:.4g} particles; at most {:.0e} can be inserted at once",
                               in.name, count, max_particles_per_insertion));
  ins.target_count = static_cast<std::size_t>(std::llround(count));
  ins.rate_per_s = in.rate_per_s;
  ins.allow_partial = in.allow_partial;
  ins.interval_s = in.interval_s > 0.0 ? in.interval_s : 0.01;
  return ins;
}

/// The `bonds` section as bond kinds of the simulation (DESIGN.md section 2).
void configure_bonds(const ScenarioSpec& spec, Simulation& sim, std::vector<std::string>& lines) {
  if (spec.bonds.empty()) {
    for (const StageSpec& st : spec.stages)
      if (st.form_bonds)
        fail(st.form_bonds->where, "this stage forms bonds, but there is no `bonds` section to say what bonds "
                                   "which materials (e.g. `bonds: [{materials: [regolith, regolith]}]`)");
    return;
  }
  const std::size_t n = sim.model().materials.size();
  std::vector<BondParameters> kinds;
  std::vector<int> kind_of_pair(n * n, -1);
  for (const BondSpec& b : spec.bonds) {
    const MaterialIndex a = material_index(sim.model().materials, b.material_a, b.where);
    const MaterialIndex c = material_index(sim.model().materials, b.material_b, b.where);
    BondParameters p;
    p.normal_stiffness_Pa_per_m = b.normal_stiffness_Pa_per_m;
    p.shear_stiffness_Pa_per_m = b.shear_stiffness_Pa_per_m;
    p.tensile_strength_Pa = b.tensile_strength_Pa;
    p.shear_strength_Pa = b.shear_strength_Pa;
    p.radius_multiplier = b.radius_multiplier;
    p.damping_ratio = b.damping_ratio;
    p.conducts_heat = b.conduction;
    if (!(p.normal_stiffness_Pa_per_m > 0.0 && p.shear_stiffness_Pa_per_m > 0.0 && p.tensile_strength_Pa > 0.0 &&
          p.shear_strength_Pa > 0.0 && p.radius_multiplier > 0.0 && p.damping_ratio >= 0.0))
      fail(b.where, "bond stiffnesses, strengths and the radius multiplier must be greater than 0, the damping "
                    "ratio 0 or more");
    kind_of_pair[a * n + c] = kind_of_pair[c * n + a] = static_cast<int>(kinds.size());
    kinds.push_back(p);
    lines.push_back(fmt::format(
        "bonds [{}, {}] ({}): k_n {:.4g} N/m^3, k_s {:.4g} N/m^3, sigma_c {:.4g} Pa, tau_c {:.4g} Pa, lambda_b "
        "{:.3g}{}{}",
        b.material_a, b.material_b, b.preset, p.normal_stiffness_Pa_per_m, p.shear_stiffness_Pa_per_m,
        p.tensile_strength_Pa, p.shear_strength_Pa, p.radius_multiplier,
        p.damping_ratio > 0.0 ? fmt::format(", damping ratio {:.3g}", p.damping_ratio) : std::string(),
        p.conducts_heat ? ", conducting" : ""));
  }
  sim.configure_bonds(std::move(kinds), std::move(kind_of_pair));
}

/// A stage's `form_bonds` with names turned into flags.
BondFormation bond_formation(const ScenarioSpec& spec, const BondFormationSpec& in, const Simulation& sim,
                             const std::vector<std::string>& tags, const std::string& stage_name,
                             std::vector<std::string>& lines) {
  BondFormation out;
  out.gap_fraction = in.gap_fraction;
  if (!in.materials.empty()) {
    out.materials.assign(sim.model().materials.size(), 0);
    for (const std::string& name : in.materials) {
      const MaterialIndex m = material_index(sim.model().materials, name, in.where);
      const bool bonded = std::any_of(spec.bonds.begin(), spec.bonds.end(), [&](const BondSpec& b) {
        return b.material_a == name || b.material_b == name;
      });
      if (!bonded)
        fail(in.where, fmt::format("material '{}' has no bond kind in `bonds`: add one for it, e.g. "
                                   "`{{materials: [{}, {}]}}`",
                                   name, name, name));
      out.materials[m] = 1;
    }
  }
  if (!in.region_tags.empty()) {
    out.regions.assign(tags.size(), 0);
    for (const std::string& tag : in.region_tags) {
      const auto found = std::find(tags.begin(), tags.end(), tag);
      if (found == tags.end())
        fail(in.where, fmt::format("region tag '{}' is not used by any insertion", tag));
      out.regions[static_cast<std::size_t>(found - tags.begin())] = 1;
    }
  }
  lines.push_back(fmt::format("stage '{}': forms bonds at its start between particles in contact or within a gap of {:.3g} x the "
                              "smaller radius{}{}",
                              stage_name, in.gap_fraction,
                              in.materials.empty() ? "" : fmt::format(", materials {}", fmt::join(in.materials, ", ")),
                              in.region_tags.empty() ? "" : fmt::format(", regions {}", fmt::join(in.region_tags, ", "))));
  return out;
}

/// A file's particles must not reach into an analytic wall deeper than the insertion
/// allows (fraction of the particle's diameter).
void check_file_packing_against_walls(const Insertion& ins, const InsertionSpec& in, const WallSet& walls) {
  for (std::size_t k = 0; k < ins.from_file.size(); ++k) {
    const NewParticle& p = ins.from_file[k];
    for (const WallPrimitive& w : walls.primitives) {
      const WallProximity near = closest_wall_point(w, p.position_m);
      if (!near.candidate) continue;
      const double fraction = (p.radius_m - near.distance_m) / (2.0 * p.radius_m);
      if (fraction > in.max_overlap_fraction)
        fail(in.where,
             fmt::format("{}:{}: the particle at ({:.6g}, {:.6g}, {:.6g}) m, radius {:.4g} m, reaches into wall '{}' by "
                         "{:.3g} of its diameter, more than the {:.3g} accepted (`max_overlap`)",
                         in.from_file, ins.from_file_lines[k], p.position_m.x, p.position_m.y, p.position_m.z, p.radius_m,
                         walls.bodies[w.body].name, fraction, in.max_overlap_fraction));
    }
  }
}

/// Each stage's span in simulated time and its step, where the plan fixes them (a
/// static-bed stage's default step depends on the bed, and is not counted).
std::vector<PlannedStage> planned_stages(const ScenarioSpec& spec, const StagePlan& plan, const WallSet& walls,
                                         double dt) {
  std::vector<PlannedStage> stages;
  for (std::size_t s = 0; s < plan.stages.size(); ++s) {
    const Stage& stage = plan.stages[s];
    PlannedStage planned{stage.name, "its duration", stage.duration_s, dt, "", spec.stages[s].where};
    if (stage.freezes_mechanics()) {
      if (stage.thermal_time_step_s <= 0.0) continue;  // the stage runner checks the default step
      planned.step_s = stage.thermal_time_step_s;
      planned.span = "its duration in thermal steps";
      planned.step_origin = "the stage's thermal_time_step";
      if (stage.ends_on_measurement()) planned.simulated_s = stage.max_duration_s;
    } else if (stage.until_settled || stage.ends_on_measurement()) {
      planned.simulated_s = stage.max_duration_s;
      planned.span = "its max_duration";
    } else if (stage.ends_at_depth()) {
      const WallBody& wall = walls.bodies[static_cast<std::size_t>(stage.depth_body)];
      const double speed = norm(wall.motion.velocity_m_per_s);
      planned.simulated_s = speed > 0.0 ? stage.depth_m / speed : 0.0;
      planned.span = fmt::format("the time wall '{}' takes to feed {:.4g} m", wall.name, stage.depth_m);
    }
    stages.push_back(std::move(planned));
  }
  return stages;
}

}  // namespace

PreparedRun::PreparedRun() : impl_(std::make_unique<Impl>()) {}
PreparedRun::PreparedRun(PreparedRun&&) noexcept = default;
PreparedRun& PreparedRun::operator=(PreparedRun&&) noexcept = default;
PreparedRun::~PreparedRun() = default;

/// initial_state.checkpoint: the file, or the newest checkpoint of a run's directory.
std::filesystem::path initial_checkpoint_file(const ScenarioSpec& spec) {
  namespace fs = std::filesystem;
  const fs::path given(spec.initial_state_checkpoint);
  if (!fs::is_directory(given)) return given;
  fs::path newest;  // checkpoint_NNNNNN.rgck: zero-padded, so the name orders them
  std::error_code ignored;
  for (const fs::directory_entry& e : fs::directory_iterator(given / "checkpoints", ignored))
    if (e.path().extension() == ".rgck" && (newest.empty() || e.path().filename() > newest.filename())) newest = e.path();
  if (newest.empty())
    fail(spec.initial_state_where, fmt::format("'{}' holds no checkpoints/checkpoint_NNNNNN.rgck", given.string()));
  return newest;
}

PreparedRun PreparedRun::build(const ScenarioSpec& spec, int threads) {
  if (threads < 1) throw InputError(fmt::format("--threads must be at least 1, got {}", threads));
  PreparedRun run;
  Impl& impl = *run.impl_;
  std::vector<std::string>& lines = impl.description;

  MaterialTable materials;
  for (const MaterialSpec& m : spec.materials) materials.add(material_of(m));

  // Insertions first: they say which materials are particles and which sizes occur.
  std::vector<std::string> tags;
  std::vector<char> particle_material(materials.size(), 0);
  double min_radius = std::numeric_limits<double>::infinity();
  double max_radius = 0.0;
  double min_rayleigh = std::numeric_limits<double>::infinity();
  std::string min_rayleigh_particle;  // which particle sets the step, for a plan that cannot be run
  std::vector<double> smallest_radius_of_material(materials.size(), std::numeric_limits<double>::infinity());
  const auto consider_particle = [&](double r, MaterialIndex material) {
    const Material& m = materials[material];
    min_radius = std::min(min_radius, r);
    max_radius = std::max(max_radius, r);
    smallest_radius_of_material[material] = std::min(smallest_radius_of_material[material], r);
    const double rayleigh = rayleigh_time_s(r, m.density_kg_per_m3, m.shear_modulus_Pa, m.poisson_ratio);
    if (!(rayleigh >= min_rayleigh))
      min_rayleigh_particle = fmt::format("radius {:.4g} m, material '{}': shear modulus {:.4g} Pa, density {:.4g} "
                                          "kg/m^3",
                                          r, m.name, m.shear_modulus_Pa, m.density_kg_per_m3);
    min_rayleigh = std::min(min_rayleigh, rayleigh);
  };
  double planned_particles = 0.0;
  for (const InsertionSpec& in : spec.insertions) {
    Insertion ins = build_insertion(spec, in, materials, tags);
    particle_material[ins.material] = 1;
    planned_particles += static_cast<double>(ins.target_count);
    const Material& m = materials[ins.material];
    auto consider = [&](double r) { consider_particle(r, ins.material); };
    for (const SizeClass& c : ins.sizes) consider(c.radius_m);
    for (const NewParticle& p : ins.from_file) consider(p.radius_m);
    std::string temperature;
    if (in.temperature) {
      const InitialTemperature& field = ins.temperature;
      temperature = norm2(field.gradient_K_per_m) == 0.0
                        ? fmt::format(", at {:.5g} K", field.value_K)
                        : fmt::format(", at {:.5g} K + [{:.4g}, {:.4g}, {:.4g}] K/m . (x - [{:.4g}, {:.4g}, {:.4g}] m)",
                                      field.value_K, field.gradient_K_per_m.x, field.gradient_K_per_m.y,
                                      field.gradient_K_per_m.z, field.reference_point_m.x,
                                      field.reference_point_m.y, field.reference_point_m.z);
    }
    if (!in.from_file.empty() && in.temperature) temperature += " where the file gives none";
    if (ins.from_file.empty())
      lines.push_back(fmt::format("insertion '{}': {} particles of '{}' ({} size class{}){}, during stage '{}'{}",
                                  ins.name, ins.target_count, m.name, ins.sizes.size(), ins.sizes.size() == 1 ? "" : "es",
                                  ins.rate_per_s > 0 ? fmt::format(" at {:.4g} /s", ins.rate_per_s) : " all at once",
                                  spec.stages[ins.stage].name, temperature));
    else
      lines.push_back(fmt::format("insertion '{}': {} particles of '{}' from {}{}", ins.name, ins.target_count, m.name,
                                  in.from_file, temperature));
    impl.plan.insertions.push_back(std::move(ins));
  }
  // A start from another run's checkpoint: its particles count like an insertion's.
  std::optional<Checkpoint> initial;
  std::vector<MaterialIndex> initial_materials;
  if (!spec.initial_state_checkpoint.empty()) {
    const std::filesystem::path file = initial_checkpoint_file(spec);
    CheckpointParticles saved;
    try {
      initial = read_checkpoint_file(file);
      saved = read_checkpoint_particles(*initial);
    } catch (const CheckpointError& e) {
      fail(spec.initial_state_where, e.what());
    }
    // Materials by name: the other scenario may list them in another order.
    std::vector<char> used(saved.material_names.size(), 0);
    for (const MaterialIndex m : saved.particles.material) used[m] = 1;
    for (std::size_t k = 0; k < saved.material_names.size(); ++k) {
      const int index = materials.find(saved.material_names[k]);
      if (index < 0 && used[k])
        fail(spec.initial_state_where,
             fmt::format("the particles of checkpoint '{}' are of material '{}', which this scenario does not define",
                         file.string(), saved.material_names[k]));
      initial_materials.push_back(index < 0 ? MaterialIndex{0} : static_cast<MaterialIndex>(index));
    }
    for (std::size_t i = 0; i < saved.particles.size(); ++i) {
      const MaterialIndex mi = initial_materials[saved.particles.material[i]];
      particle_material[mi] = 1;
      consider_particle(saved.particles.radius_m[i], mi);
    }
    planned_particles += static_cast<double>(saved.particles.size());
    lines.push_back(fmt::format("initial state: {} particles from checkpoint '{}' (taken at t = {:.6g} s), with "
                                "their velocities, temperatures, contact history and bonds; this run starts at t = 0",
                                saved.particles.size(), file.string(), saved.time_s));
  }
  if (impl.plan.insertions.empty() && !initial) fail(SourceLocation{spec.file, 0, 0, "insertions"}, "no insertions: there would be no particles");
  check_particle_memory(planned_particles, SourceLocation{spec.file, 0, 0, "insertions"});
  fill_pair_table(materials, spec, particle_material);

  if (spec.heat.enabled) {
    const std::string partition =
        spec.heat.heat_partition == "fixed"
            ? fmt::format("{:.3g} of it to the particle at a wall, half each between particles", spec.heat.friction_partition)
            : spec.heat.heat_partition == "equal" ? std::string("half to each body")
                                                  : fmt::format("shared by {}", spec.heat.heat_partition);
    lines.push_back(fmt::format("heat: on, time-scale factor S = {:.4g}, heat generated at contacts: {}",
                                spec.heat.time_scale_factor,
                                spec.heat.dissipation_heating
                                    ? fmt::format("every loss of contacts and bonds ({}; the energy audit is kept)",
                                                  partition)
                                : spec.heat.friction_heating ? fmt::format("the sliding power ({})", partition)
                                                             : std::string("none")));
    for (std::size_t i = 0; i < materials.size(); ++i) {
      if (!particle_material[i]) continue;
      const Material& m = materials[static_cast<MaterialIndex>(i)];
      lines.push_back(fmt::format("material '{}': conductivity {}, specific heat {}{}", m.name,
                                  curve_text(m.conductivity_W_per_mK, "W/(m K)"),
                                  curve_text(m.specific_heat_J_per_kgK, "J/(kg K)"),
                                  m.real_shear_modulus_Pa > 0.0
                                      ? fmt::format(", contact radius from the real shear modulus {:.4g} Pa",
                                                    m.real_shear_modulus_Pa)
                                      : std::string()));
    }
  } else {
    lines.push_back("heat: off");
  }

  WallSet walls;
  std::vector<ThermalWall> wall_thermal;
  std::vector<const WallSpec*> spec_of_body;  // index for index with wall_thermal
  std::vector<ConductingWall> conducting_walls;
  const auto conducting = [&](const WallSpec& w, MaterialIndex material, const ThermalWall& t) {
    if (t.mode != WallThermalMode::adiabatic)
      conducting_walls.push_back({w.name, material, t.conductivity_W_per_mK, t.mix == WallConductivityMix::harmonic_mean});
  };
  for (const WallSpec& w : spec.walls) {
    const MaterialIndex material =
        w.material.empty() ? MaterialIndex{0} : material_index(materials, w.material, w.where);
    const WallMotion motion = wall_motion(w);
    if (w.shape == WallShape::sieve) {
      // Segment k (1 at the top, N at the bottom) spans [N - k, N - k + 1] segment
      // lengths from the base; edges only at the sieve's own ends.
      const int n = w.segments;
      const Vec3 axis = normalized(w.normal);
      ThermalWall first;
      for (int k = 1; k <= n; ++k) {
        const std::uint32_t body = walls.add_body(fmt::format("{}[{}]", w.name, k), motion);
        const Vec3 base = w.point_m + axis * (w.length_m * static_cast<double>(n - k));
        const bool bottom = k == n;
        walls.add_sieve_segment(body, base, axis, w.radius_m, w.length_m, bottom, k == 1, bottom && w.cap_bottom,
                                material);
        const double area = 2.0 * std::numbers::pi * w.radius_m * w.length_m +
                            (bottom && w.cap_bottom ? disk_area(w.radius_m) : 0.0);
        wall_thermal.push_back(thermal_wall(spec, w, area));
        spec_of_body.push_back(&w);
        if (k == 1) first = wall_thermal.back();
      }
      if (spec.heat.enabled)
        lines.push_back(describe_thermal_wall(w, first, n, wall_thermal.back().heat_capacity_J_per_K));
      conducting(w, material, first);
      continue;
    }
    const std::uint32_t body = walls.add_body(w.name, motion);
    walls.bodies[body].depth_at_start_m = w.motion.depth_at_start_m;
    double area = 0.0;
    switch (w.shape) {
      case WallShape::plane: walls.add_plane(body, w.point_m, w.normal, material); break;
      case WallShape::disk:
        walls.add_disk(body, w.point_m, w.normal, w.radius_m, material);
        area = disk_area(w.radius_m);
        break;
      case WallShape::cylinder:
        walls.add_cylinder(body, w.point_m, w.normal, w.radius_m, w.length_m, w.side != CylinderSide::outside,
                           w.side != CylinderSide::inside, w.cap_bottom, w.cap_top, material);
        area = 2.0 * std::numbers::pi * w.radius_m * w.length_m +
               disk_area(w.radius_m) * ((w.cap_bottom ? 1.0 : 0.0) + (w.cap_top ? 1.0 : 0.0));
        break;
      case WallShape::sieve: break;  // expanded above
      case WallShape::mesh:
      case WallShape::auger: {
        // The mesh's reference frame is its placement at the start (the body's pose is
        // the identity then).
        walls.add_mesh(body, *w.mesh, material, w.mesh_grid_cell_m);
        area = w.mesh->area();
        const Aabb box = w.mesh->bounding_box();
        lines.push_back(fmt::format("wall '{}': mesh of {} triangles {}, spanning ({:.4g}, {:.4g}, {:.4g}) to "
                                    "({:.4g}, {:.4g}, {:.4g}) m",
                                    w.name, w.mesh->triangle_count(),
                                    w.auger ? fmt::format("generated (auger, {} flutes, outer diameter {:.4g} m)",
                                                          w.auger->flutes, w.auger->outer_diameter_m)
                                            : fmt::format("from '{}'", w.mesh_file),
                                    box.lo_m.x, box.lo_m.y, box.lo_m.z, box.hi_m.x, box.hi_m.y, box.hi_m.z));
        break;
      }
    }
    wall_thermal.push_back(thermal_wall(spec, w, area));
    spec_of_body.push_back(&w);
    if (spec.heat.enabled && (w.shape == WallShape::mesh || w.shape == WallShape::auger)) make_rod(spec, w, walls.meshes.back(), wall_thermal.back());
    if (spec.heat.enabled) lines.push_back(describe_thermal_wall(w, wall_thermal.back(), 1, 0.0));
    conducting(w, material, wall_thermal.back());
  }
  if (spec.heat.enabled)
    for (std::string& line : conduction_pair_lines(spec, materials, particle_material, conducting_walls))
      lines.push_back(std::move(line));
  lines.push_back(fmt::format("walls: {} ({} analytic primitives)", walls.bodies.size(), walls.primitives.size()));
  for (std::size_t k = 0; k < impl.plan.insertions.size(); ++k)
    if (!impl.plan.insertions[k].from_file.empty())
      check_file_packing_against_walls(impl.plan.insertions[k], spec.insertions[k], walls);

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
  // A lumped rod stepped explicitly (thermal/lumped_wall_step.hpp) must be stable at dt.
  for (std::size_t b = 0; spec.heat.enabled && b < wall_thermal.size(); ++b) {
    const ThermalWall& t = wall_thermal[b];
    if (t.mode != WallThermalMode::lumped || !t.rod.exchanges()) continue;
    const double limit_s =
        lumped_wall_stability_limit_s(t.node_heat_capacities_J_per_K(), t.rod, spec.heat.time_scale_factor);
    if (dt >= limit_s)
      fail(spec_of_body[b]->thermal.where,
           fmt::format("wall '{}': its rod's segments exchange heat too fast for the time step ({:.4g} s against a "
                       "stable {:.4g} s, m C / G of its lightest segment with the time-scale factor): use fewer "
                       "segments, a thinner rod or a larger mass",
                       walls.bodies[b].name, dt, limit_s));
  }
  // Gravity that moves a free grain 1 % of the smallest radius in one step is no
  // gravity a contact can hold (1e30 m/s^2 was reported as a time step too large for the
  // contacts); the shipped scenarios stay below 3e-5 of it.
  if (const double per_step_m = norm(spec.gravity_m_per_s2) * dt * dt; per_step_m > 0.01 * min_radius)
    fail(SourceLocation{spec.file, 0, 0, "gravity"},
         fmt::format("gravity of {:.4g} m/s^2 moves a free particle {:.3g} m in one step of {:.4g} s (g dt^2), more than "
                     "1 % of the smallest radius {:.4g} m: no contact could hold it. Check gravity's value and unit",
                     norm(spec.gravity_m_per_s2), per_step_m, dt, min_radius));
  lines.insert(lines.begin(), fmt::format("time step {:.4g} s = {:.3g} x the Rayleigh time {:.4g} s of the smallest "
                                          "particle (radius {:.4g} m)",
                                          dt, dt / min_rayleigh, min_rayleigh, min_radius));
  {
    WallSpeedReport speeds = wall_speed_report(walls, materials, smallest_radius_of_material, dt,
                                               spec.time_step_s > 0.0 ? 0.0 : spec.rayleigh_fraction);
    lines.insert(lines.end(), speeds.lines.begin(), speeds.lines.end());
    for (const std::string& w : speeds.warnings) lines.push_back("warning: " + w);
    impl.warnings = std::move(speeds.warnings);
  }

  SimulationSettings settings;
  settings.domain = {spec.domain.min_m, spec.domain.max_m};
  settings.lost_particles = spec.domain.remove_lost_particles ? LostParticles::remove : LostParticles::stop;
  settings.gravity_m_per_s2 = spec.gravity_m_per_s2;
  settings.time_step_s = dt;
  settings.neighbor_skin_m = spec.neighbor_skin_m > 0.0 ? spec.neighbor_skin_m : 0.2 * min_radius;
  settings.min_particle_radius_m = min_radius;
  settings.max_particle_radius_m = max_radius;
  settings.threads = threads;
  settings.heat.enabled = spec.heat.enabled;
  settings.heat.time_scale_factor = spec.heat.time_scale_factor;
  settings.heat.friction_heating = spec.heat.friction_heating;
  settings.heat.friction_partition = spec.heat.friction_partition;
  settings.heat.dissipation_heating = spec.heat.enabled && spec.heat.dissipation_heating;
  settings.energy_audit = spec.output.energy_audit;
  settings.heat.partition = heat_partition_model(spec.heat.heat_partition);
  settings.heat.track_thermal_history = spec.heat.enabled && spec.measurements.thermal_history;
  settings.heat.thermal_history_threshold_K = spec.measurements.thermal_history_threshold_K;
  impl.simulation =
      std::make_unique<Simulation>(std::move(materials), std::move(walls), settings, std::move(wall_thermal));
  configure_bonds(spec, *impl.simulation, lines);
  if (initial) {
    try {
      impl.simulation->adopt_particles(*initial, initial_materials, spec.initial_state_temperature_K);
    } catch (const CheckpointError& e) {
      fail(spec.initial_state_where, e.what());
    }
  }

  // Built before the stages, which may end on a measurement; described after them.
  std::vector<std::string> measurement_lines;
  impl.plan.measurements = measurement_plan(spec.measurements, impl.simulation->walls, measurement_lines);
  for (const StageSpec& st : spec.stages) {
    Stage stage;
    stage.name = st.name;
    stage.until_settled = st.end == StageEnd::settled;
    stage.duration_s = st.duration_s;
    stage.settled_kinetic_energy_J = st.settled_kinetic_energy_J;
    stage.min_duration_s = st.min_duration_s;
    stage.max_duration_s = st.max_duration_s;
    if (st.end == StageEnd::depth) {
      stage.depth_body = fed_wall_index(impl.simulation->walls, st.depth_wall, st.where,
                                        fmt::format("stage '{}'", st.name));
      stage.depth_m = st.depth_m;
    }
    if (st.end == StageEnd::measurement) stage.until_measured = measurement_target(st, impl.plan.measurements);
    for (const OverrideSpec& o : st.overrides) {
      PairOverride po;
      if (!o.material_a.empty()) {
        po.material_a = material_index(impl.simulation->model().materials, o.material_a, o.where);
        po.material_b = material_index(impl.simulation->model().materials, o.material_b.empty() ? o.material_a : o.material_b, o.where);
      }
      po.restitution = o.restitution;
      po.sliding_friction = o.sliding_friction;
      po.rolling_friction = o.rolling_friction;
      stage.overrides.push_back(po);
    }
    if (st.form_bonds) stage.form_bonds = bond_formation(spec, *st.form_bonds, *impl.simulation, tags, stage.name, lines);
    stage.heat_stepping = heat_stepping(st.heat_stepping);
    stage.thermal_time_step_s = st.thermal_time_step_s;
    stage.stability_fraction = st.stability_fraction;
    const std::string measured_end =
        stage.ends_on_measurement()
            ? fmt::format("until '{}' {} {} {:.6g} K, at most {:.4g} s", st.until_measurement, st.until_quantity,
                          st.until_rising ? "rises to" : "falls to", st.until_value_K, stage.max_duration_s)
            : "";
    if (stage.freezes_mechanics()) {
      // The frozen network (thermal/thermal_network.hpp) holds one node per lumped wall and
      // no radiation: a drill's own heat paths are stepped with the contacts only.
      const auto& thermal = impl.simulation->model().wall_thermal;
      for (std::size_t b = 0; b < thermal.size(); ++b)
        if (thermal[b].mode == WallThermalMode::lumped && thermal[b].rod.exchanges())
          fail(st.where, fmt::format("stage '{}' freezes the bed, but wall '{}' has segments, radiation or a held "
                                     "end, which a static-bed stage does not step yet: use `heat_stepping: coupled` "
                                     "here, or a plain lumped wall",
                                     stage.name, impl.simulation->walls.bodies[b].name));
    }
    if (stage.freezes_mechanics())
      lines.push_back(fmt::format("stage '{}': {}, static bed (mechanics frozen), heat by {}, thermal step {}",
                                  stage.name,
                                  stage.ends_on_measurement() ? measured_end : fmt::format("{:.4g} s", stage.duration_s),
                                  heat_method_name(stage.heat_stepping),
                                  stage.thermal_time_step_s > 0.0
                                      ? fmt::format("{:.4g} s", stage.thermal_time_step_s)
                                      : fmt::format("{:.3g} x the explicit stability limit",
                                                    stage.default_step_in_stability_limits())));
    else
      lines.push_back(stage.ends_on_measurement() ? fmt::format("stage '{}': {}", stage.name, measured_end)
                      : stage.ends_at_depth()
                          ? fmt::format("stage '{}': until wall '{}' reaches a depth of {:.4g} m", stage.name,
                                        st.depth_wall, stage.depth_m)
                      : stage.until_settled
                          ? fmt::format("stage '{}': until settled (kinetic energy per particle < {:.3g} J), at most "
                                        "{:.4g} s",
                                        stage.name, stage.settled_kinetic_energy_J, stage.max_duration_s)
                          : fmt::format("stage '{}': {:.4g} s ({:.0f} steps)", stage.name, stage.duration_s,
                                        std::round(stage.duration_s / dt)));
    impl.plan.stages.push_back(std::move(stage));
  }
  check_stage_step_counts(planned_stages(spec, impl.plan, impl.simulation->walls, dt),
                          spec.time_step_s > 0.0
                              ? "the scenario's time_step"
                              : fmt::format("{:.3g} x the Rayleigh time {:.4g} s of the particle with {}", dt / min_rayleigh,
                                            min_rayleigh, min_rayleigh_particle));
  impl.plan.sample_interval_s = spec.output.interval_s;
  impl.plan.region_names = tags;
  if (const SnapshotSpec& snap = spec.output.snapshots; snap.enabled) {
    SnapshotSchedule& schedule = impl.plan.snapshots;
    schedule.trigger = !snap.depth_wall.empty() ? SnapshotSchedule::Trigger::depth
                       : snap.every_steps > 0    ? SnapshotSchedule::Trigger::steps
                                                 : SnapshotSchedule::Trigger::time;
    schedule.interval_s = snap.interval_s;
    schedule.every_steps = snap.every_steps;
    schedule.at_stage_end = snap.at_stage_end;
    if (!snap.depth_wall.empty()) {
      schedule.depth_body = fed_wall_index(impl.simulation->walls, snap.depth_wall, snap.where, "output.snapshots");
      schedule.depth_interval_m = snap.depth_interval_m;
    }
    lines.push_back(!snap.depth_wall.empty()
                        ? fmt::format("snapshots (ParaView) every {:.4g} m of wall '{}''s depth{}", snap.depth_interval_m,
                                      snap.depth_wall, snap.at_stage_end ? " and at the end of each stage" : "")
                    : snap.every_steps > 0
                        ? fmt::format("snapshots (ParaView) every {} steps{}", snap.every_steps,
                                      snap.at_stage_end ? " and at the end of each stage" : "")
                        : fmt::format("snapshots (ParaView) every {:.4g} s of simulated time{}", snap.interval_s,
                                      snap.at_stage_end ? " and at the end of each stage" : ""));
  }
  if (spec.measurements.thermal_history && spec.heat.enabled)
    lines.push_back(fmt::format("thermal history: peak temperature and time above {:.5g} K of every particle",
                                spec.measurements.thermal_history_threshold_K));
  lines.insert(lines.end(), measurement_lines.begin(), measurement_lines.end());
  impl.plan.seed = spec.seed;
  return run;
}

RunOutcome PreparedRun::run(RunObserver& observer, const std::atomic<bool>& stop_requested) {
  return run_stages(*impl_->simulation, impl_->plan, observer, stop_requested);
}

RunOutcome PreparedRun::resume(const Checkpoint& checkpoint, RunObserver& observer,
                               const std::atomic<bool>& stop_requested) {
  const RunResume from{checkpoint};
  return run_stages(*impl_->simulation, impl_->plan, observer, stop_requested, &from);
}

std::vector<std::string> PreparedRun::describe() const { return impl_->description; }
const std::vector<std::string>& PreparedRun::warnings() const { return impl_->warnings; }
const Simulation& PreparedRun::simulation() const { return *impl_->simulation; }
const StagePlan& PreparedRun::plan() const { return impl_->plan; }
Simulation& PreparedRun::simulation() { return *impl_->simulation; }
StagePlan& PreparedRun::plan() { return impl_->plan; }
double PreparedRun::time_step_s() const { return impl_->simulation->time_step_s(); }
int PreparedRun::threads() const { return impl_->simulation->threads(); }

}  // namespace regodem
