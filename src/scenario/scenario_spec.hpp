#pragma once
// The scenario as plain data, in SI units and kelvin: what the YAML reader produces
// (scenario_reader) and what the builder turns into a Simulation (scenario_builder).
// Nothing here knows YAML. `where` fields keep the file:line of the key that set a
// value so that checks made after parsing (a missing material, a region outside the
// domain) can still name the line.
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/vec3.hpp"
#include "geometry/auger_generator.hpp"
#include "geometry/triangle_mesh.hpp"
#include "sim/measurement_plan.hpp"

namespace regodem {

/// File, line and key path of a value in the scenario file, for error messages.
struct SourceLocation {
  std::string file;
  int line = 0;       // 1-based; 0 = unknown
  int column = 0;     // 1-based
  std::string key;    // dotted key path, e.g. "walls[2].radius"
  std::string describe() const;  // "file:line:column: key"
};

/// A property that is a constant or a table over temperature (rows T, value).
struct TemperatureCurveSpec {
  double constant = 0.0;                  // used when the table is empty
  std::vector<double> temperature_K;      // table rows (strictly increasing)
  std::vector<double> value;
  SourceLocation where;
};

struct MaterialSpec {
  std::string name;
  double density_kg_per_m3 = 0.0;
  double shear_modulus_Pa = 0.0;
  double poisson_ratio = 0.0;
  // Thermal properties; both must be given when heat is on. W/(m K) and J/(kg K).
  std::optional<TemperatureCurveSpec> conductivity_W_per_mK;
  std::optional<TemperatureCurveSpec> specific_heat_J_per_kgK;
  double real_shear_modulus_Pa = 0.0;  // 0: none (conduction uses shear_modulus_Pa)
  // The file says what conduction's modulus is: a real_shear_modulus (or
  // real_youngs_modulus) value, or `same` (shear_modulus is the real one). A scenario
  // that gives any material a real modulus must say it of every conducting one.
  bool real_modulus_stated = false;
  SourceLocation where;
};

/// A material with elastic constants only (no thermal properties): what programs that
/// build a ScenarioSpec in code (tests, benchmarks) most often need.
inline MaterialSpec elastic_material(std::string name, double density_kg_per_m3, double shear_modulus_Pa,
                                     double poisson_ratio) {
  MaterialSpec m;
  m.name = std::move(name);
  m.density_kg_per_m3 = density_kg_per_m3;
  m.shear_modulus_Pa = shear_modulus_Pa;
  m.poisson_ratio = poisson_ratio;
  return m;
}

enum class ConductionLawSpec { force, radius, area, none };

/// Contact properties of a pair of materials ("interactions" section).
struct InteractionSpec {
  std::string material_a, material_b;
  double restitution = 0.5;
  double sliding_friction = 0.5;
  double rolling_friction = 0.0;
  bool rolling_own_spin = false;  // rolling_model: own_spin (EDEM's standard) or relative_spin (default)
  bool clamp_attractive_normal_force = false;
  ConductionLawSpec conduction = ConductionLawSpec::force;
  double heat_transfer_coefficient_W_per_m2K = 0.0;  // area law only (required there)
  SourceLocation where;
};

/// Prescribed wall motion: translation at a velocity plus rotation at an angular
/// velocity about an axis through axis_point (rotation only about the shape's own
/// symmetry axis for analytic walls), active for start_s <= t < stop_s.
struct MotionSpec {
  Vec3 velocity_m_per_s;
  Vec3 angular_velocity_rad_per_s;
  Vec3 axis_point_m;
  double start_s = 0.0;
  double stop_s = std::numeric_limits<double>::infinity();
  // A drill's depth: depth_at_start_m plus the distance fed along `velocity`; the feed
  // stops when the depth reaches stop_at_depth_m (rotation goes on until stop_s).
  double depth_at_start_m = 0.0;
  double stop_at_depth_m = std::numeric_limits<double>::infinity();
  double stop_at_thrust_N = std::numeric_limits<double>::infinity();  // the feed stops at this thrust
};

/// Where a mesh goes: x -> R(axis, angle) (scale x) + translation.
struct MeshPlacementSpec {
  double scale = 1.0;  // e.g. 0.001 for a file in millimetres
  Vec3 rotation_axis{0.0, 0.0, 1.0};
  double rotation_angle_rad = 0.0;
  Vec3 translation_m;
};

enum class WallShape { plane, disk, cylinder, sieve, mesh, auger };
enum class CylinderSide { inside, outside, both };

enum class WallThermalModeSpec { adiabatic, fixed, lumped };

/// The `thermal` block of a wall (DESIGN.md section 2, "Thermal walls").
struct WallThermalSpec {
  WallThermalModeSpec mode = WallThermalModeSpec::adiabatic;
  // fixed: the temperature, constant (one row at t = 0) or a table over time;
  // lumped: the initial temperature (one row).
  std::vector<double> time_s;
  std::vector<double> temperature_K;
  std::optional<double> conductivity_W_per_mK;  // none: the material's, else the particles' own
  // `conductivity: particles`: the contacts conduct with the particles' own k (Eq. 1's k_s)
  // even when the wall's material gives a k (which the heat partition and the rod then use).
  bool conductivity_of_particles = false;
  bool harmonic_mean = false;                   // k_c = harmonic mean of wall and particle
  double specific_heat_J_per_kgK = 0.0;         // lumped
  double mass_kg = 0.0;                         // lumped: mass, or
  double areal_density_kg_per_m2 = 0.0;         //   areal density x the wall's area (per segment)
  // lumped mesh and auger walls: a rod of `segments` axial pieces (1 at the tip), the
  // rod's axial conduction, and a held far end (docs/drilling-heat.md).
  int segments = 1;
  std::optional<double> rod_conductivity_W_per_mK;  // none: the wall material's conductivity
  double rod_cross_section_m2 = 0.0;                // 0: no rod given
  std::optional<double> held_end_K;
  // lumped: radiation to the surroundings (emissivity 0: none).
  double emissivity = 0.0;
  double surroundings_K = 0.0;
  SourceLocation where;
};

struct WallSpec {
  std::string name;
  WallShape shape = WallShape::plane;
  std::string material;  // empty: the material of the first particle material
  // plane: point + normal (normal points towards the particles)
  // disk: point = centre, normal = axis, radius
  // cylinder: point = centre of the bottom end, normal = axis (bottom -> top), radius, length
  // sieve: as a cylinder, from the bottom of its lowest segment; length of one segment
  Vec3 point_m;
  Vec3 normal{0.0, 0.0, 1.0};
  double radius_m = 0.0;
  double length_m = 0.0;
  CylinderSide side = CylinderSide::inside;  // cylinder (a sieve: always both)
  bool cap_bottom = false;                   // cylinder and sieve
  bool cap_top = false;                      // cylinder only
  // sieve: a segmented cylinder, contact from both sides, `segments` pieces of length
  // length_m each stacked along the axis from point_m, numbered from the top (1) down;
  // cap_bottom closes the lowest one (the paper's segment 10). Each segment is its own
  // wall body "name[k]" with its own temperature.
  int segments = 1;
  // mesh: triangles from an STL (binary or ASCII) or OBJ file, placed; auger: a drill
  // generated from its dimensions (geometry/auger_generator), tip apex at the
  // placement's translation, axis along the placement's rotation of +z. point_m is the
  // translation and normal the turned +z (the default axis point and spin axis).
  std::string mesh_file;  // absolute; empty for a generated mesh
  MeshPlacementSpec placement;
  double mesh_grid_cell_m = 0.0;  // 0: the mesh's mean edge length
  std::shared_ptr<const TriangleMesh> mesh;  // read or generated, and placed (world frame at the start)
  std::optional<AugerSpec> auger;
  WallThermalSpec thermal;
  MotionSpec motion;
  SourceLocation where;
};

enum class RegionShape { box, cylinder, annulus };

/// An insertion region. box: min/max corners. cylinder and annulus: base centre,
/// axis (unit), length, outer radius and (annulus) inner radius.
struct RegionSpec {
  RegionShape shape = RegionShape::box;
  Vec3 min_m, max_m;
  Vec3 base_m;
  Vec3 axis{0.0, 0.0, 1.0};
  double length_m = 0.0;
  double radius_m = 0.0;
  double inner_radius_m = 0.0;
  SourceLocation where;
};

/// Initial particle temperature: value + gradient . (x - reference_point).
struct InitialTemperatureSpec {
  double value_K = 0.0;
  Vec3 gradient_K_per_m;
  Vec3 reference_point_m;
};

struct SizeClassSpec {
  double radius_m = 0.0;
  double fraction = 1.0;  // share of the class, by number or by mass (InsertionSpec)
};

enum class InsertAmount { count, solid_fraction, mass };

/// A random, non-overlapping, dynamic insertion (or a CSV file of particles).
struct InsertionSpec {
  std::string name;
  std::string region_tag;  // particles carry this tag; insertions may share one
  std::string material;
  RegionSpec region;
  std::vector<SizeClassSpec> sizes;  // discrete size distribution (one entry: single size)
  bool fractions_by_mass = false;
  InsertAmount amount_kind = InsertAmount::count;
  double amount = 0.0;   // count, solid fraction (0..1) or mass in kg
  double rate_per_s = 0.0;          // particles per second; 0 = everything at the first attempt
  bool allow_partial = false;       // a region that fills up before the count is reached: go on (else the stage fails)
  // A file's packing: the deepest overlap accepted, between two of its particles or
  // with an analytic wall, as a fraction of the smaller diameter (of the particle's).
  double max_overlap_fraction = 0.05;
  double interval_s = 0.0;          // time between insertion attempts; 0 = builder's default
  Vec3 initial_velocity_m_per_s;
  std::string stage;                // stage during which it inserts; empty = the first stage
  std::string from_file;            // CSV of x,y,z,radius[,vx,vy,vz][,temperature]; region unused
  // Initial temperature; a CSV temperature column, where present, wins. Required when
  // heat is on (unless the CSV gives every temperature).
  std::optional<InitialTemperatureSpec> temperature;
  SourceLocation where;
};

/// A kind of parallel bond between two materials (the `bonds` section; DESIGN.md
/// section 2). A preset gives every value; the keys given override it.
struct BondSpec {
  std::string material_a, material_b;
  std::string preset = "icy_regolith";  // or "zhao2023" (the paper's Table 2)
  double normal_stiffness_Pa_per_m = 0.0;  // N/m^3
  double shear_stiffness_Pa_per_m = 0.0;
  double tensile_strength_Pa = 0.0;
  double shear_strength_Pa = 0.0;
  double radius_multiplier = 1.0;
  double damping_ratio = 0.0;
  bool conduction = false;
  SourceLocation where;
};

/// A stage's `form_bonds`: bonds form at the stage start between particles in contact
/// or within gap_fraction x the smaller radius, both of the listed materials and
/// region tags (empty: all), whose material pair has a `bonds` entry.
struct BondFormationSpec {
  double gap_fraction = 0.0;
  std::vector<std::string> materials;
  std::vector<std::string> region_tags;
  SourceLocation where;
};

/// Temporary change of contact properties during a stage (e.g. friction 0 while filling).
struct OverrideSpec {
  std::string material_a, material_b;  // both empty: every pair
  std::optional<double> restitution, sliding_friction, rolling_friction;
  SourceLocation where;
};

enum class StageEnd { time, settled, depth, measurement };

/// How a stage moves heat. coupled: with the mechanics, every step. The others freeze the
/// mechanics (particles do not move) and advance temperatures alone on the contact
/// network taken at the stage start: explicit at a fraction of the stability limit, or
/// implicit (backward Euler, Crank-Nicolson).
enum class ThermalStepping { coupled, static_explicit, static_backward_euler, static_crank_nicolson };

struct StageSpec {
  std::string name;
  StageEnd end = StageEnd::time;
  double duration_s = 0.0;  // end == time
  // end == settled: mean kinetic energy per particle (translational + rotational)
  // below the threshold, checked after min_duration_s and after this stage's insertions
  // have finished; failing to settle within max_duration_s fails the run.
  double settled_kinetic_energy_J = 0.0;
  double min_duration_s = 0.0;
  double max_duration_s = std::numeric_limits<double>::infinity();
  // end == depth: until wall `depth_wall` has reached `depth_m` (its motion's depth).
  std::string depth_wall;
  double depth_m = 0.0;
  // end == measurement: until measurement `until_measurement`'s `until_quantity` (mean,
  // min, max of a region; T_in, T_out, T_d of a band) rises (or falls) to the value,
  // within max_duration_s.
  std::string until_measurement, until_quantity;
  bool until_rising = true;
  double until_value_K = 0.0;
  std::vector<OverrideSpec> overrides;
  ThermalStepping heat_stepping = ThermalStepping::coupled;
  double thermal_time_step_s = 0.0;   // static modes; 0 = stability_fraction x the explicit limit
  double stability_fraction = 0.5;    // static explicit (and the default implicit step)
  std::optional<BondFormationSpec> form_bonds;
  SourceLocation where;
};

/// The top-level `heat` section (DESIGN.md section 2, "Conduction", "Thermal stepping").
struct HeatSpec {
  bool enabled = false;               // true when the section is present, unless `enabled: false`
  double time_scale_factor = 1.0;     // S: every conductance is multiplied by it
  bool friction_heating = false;      // the sliding power heats the two bodies
  bool dissipation_heating = false;   // every loss of contacts and bonds does
  std::string heat_partition = "fixed";  // equal | fixed | conductivity | effusivity
  double friction_partition = 0.5;    // `fixed`: the particle's share at a wall
  SourceLocation where;
};

/// ParaView snapshots (`output.snapshots`): by simulated time or by steps.
struct SnapshotSpec {
  bool enabled = false;           // the block is present and valid
  double interval_s = 0.0;        // > 0: every interval of simulated time
  std::uint64_t every_steps = 0;  // > 0: every so many steps
  std::string depth_wall;         // non-empty: every depth_interval_m of that wall's depth
  double depth_interval_m = 0.0;
  bool at_stage_end = true;       // one more at the end of each stage
  bool walls = true;              // the walls series too
  bool compress = true;           // zlib inside the .vtp
  SourceLocation where;
};

struct OutputSpec {
  double interval_s = 0.0;        // time-series sampling interval; 0 = 100 samples per stage
  double progress_interval_s = 2.0;  // wall-clock seconds between progress lines
  bool energy_audit = false;         // the mechanical energy books in the time series and summary
  SnapshotSpec snapshots;
};

/// One entry of the `measurements` section: a region, band or profile with its schedule,
/// in SI units; the walls it names are resolved to bodies by the builder.
struct MeasurementSpec {
  Measurement measurement;  // follow_body, depth_body and the schedule's depth_body unset
  std::string moves_with;   // wall name; empty: fixed
  std::string depth_wall;   // the schedule's wall (every_depth, at_depths); empty: none
  SourceLocation where;
};

/// The `measurements` section.
struct MeasurementsSpec {
  bool thermal_history = false;  // per-particle peak temperature and time above the threshold
  double thermal_history_threshold_K = 203.15;  // -70 degC
  std::vector<MeasurementSpec> items;
  SourceLocation where;
};

struct DomainSpec {
  Vec3 min_m, max_m;
  bool remove_lost_particles = false;  // `lost_particles: remove`; else a loss stops the run
  SourceLocation where;
};

struct ScenarioSpec {
  std::string name;
  std::string file;          // path of the scenario file
  std::string description;
  std::string content_hash;  // FNV-1a 64 (hex) of the file bytes and the --set overrides
  std::uint64_t seed = 1;
  Vec3 gravity_m_per_s2{0.0, 0.0, -9.81};
  DomainSpec domain;
  double time_step_s = 0.0;         // 0 = rayleigh_fraction x Rayleigh time
  double rayleigh_fraction = 0.2;
  double max_rayleigh_fraction = 0.5;  // a larger requested step is refused
  double neighbor_skin_m = 0.0;        // 0 = builder's default (0.1 x smallest diameter)
  std::vector<MaterialSpec> materials;
  std::vector<InteractionSpec> interactions;
  std::vector<WallSpec> walls;
  std::vector<InsertionSpec> insertions;
  std::vector<StageSpec> stages;
  std::vector<BondSpec> bonds;
  HeatSpec heat;
  OutputSpec output;
  MeasurementsSpec measurements;
  // initial_state.checkpoint: a checkpoint file, or a run's output directory (its newest
  // checkpoint), whose particles, contacts, bonds and temperatures the run starts with.
  std::string initial_state_checkpoint;  // absolute; empty: none
  std::optional<double> initial_state_temperature_K;  // every adopted particle starts at it
  SourceLocation initial_state_where;
};

}  // namespace regodem
