// The `walls` list: analytic planes, disks, cylinder shells and segmented sieves, and
// triangle meshes (read_mesh_wall.cpp), with prescribed motion and a thermal mode.
#include <cmath>

#include <fmt/format.h>

#include "scenario/scenario_fields.hpp"
#include "scenario/scenario_sections.hpp"

namespace regodem {
namespace {

bool is_mesh(WallShape shape) { return shape == WallShape::mesh || shape == WallShape::auger; }

const std::vector<std::string> kCommonKeys{"name", "type", "material", "motion", "thermal"};

std::vector<std::string> keys_for(WallShape shape) {
  std::vector<std::string> keys = kCommonKeys;
  switch (shape) {
    case WallShape::plane:
      keys.insert(keys.end(), {"point", "normal"});
      break;
    case WallShape::disk:
      keys.insert(keys.end(), {"center", "normal", "radius", "diameter"});
      break;
    case WallShape::cylinder:
      keys.insert(keys.end(), {"base", "axis", "radius", "diameter", "length", "contact", "ends"});
      break;
    case WallShape::sieve:
      keys.insert(keys.end(), {"base", "axis", "radius", "diameter", "length", "segments", "ends"});
      break;
    case WallShape::mesh:
      keys.insert(keys.end(), {"file", "scale", "placement", "grid_cell"});
      break;
    case WallShape::auger:
      keys.insert(keys.end(), {"outer_diameter", "core_diameter", "pitch", "flutes", "flute_thickness", "length",
                               "tip", "segments_per_turn", "hand", "placement", "grid_cell"});
      break;
  }
  return keys;
}

// The three shapes name their anchor point and direction differently (as their meaning
// differs); say so when a key of another shape is used.
std::vector<std::pair<std::string, std::string>> misplaced_keys(WallShape shape) {
  switch (shape) {
    case WallShape::plane:
      return {{"center", "a plane takes 'point', any point on it"},
              {"base", "a plane takes 'point', any point on it"},
              {"axis", "a plane takes 'normal', pointing towards the particles"},
              {"radius", "a plane is unbounded; a disk has a radius"},
              {"diameter", "a plane is unbounded; a disk has a diameter"}};
    case WallShape::disk:
      return {{"point", "a disk takes 'center'"},
              {"base", "a disk takes 'center'"},
              {"axis", "a disk takes 'normal'"}};
    case WallShape::cylinder:
      return {{"point", "a cylinder takes 'base', the centre of its bottom end"},
              {"center", "a cylinder takes 'base', the centre of its bottom end"},
              {"normal", "a cylinder takes 'axis', from its bottom end to its top"},
              {"segments", "only a sieve has segments"}};
    case WallShape::auger:
      return {{"point", "an auger's tip apex is placed by 'placement: {translation: ...}'"},
              {"base", "an auger's tip apex is placed by 'placement: {translation: ...}'"},
              {"axis", "an auger points along +z turned by 'placement: {rotation: ...}'"},
              {"file", "an auger is generated; a drill from a file is 'type: mesh'"},
              {"diameter", "an auger has 'outer_diameter' and 'core_diameter'"},
              {"radius", "an auger has 'outer_diameter' and 'core_diameter'"}};
    case WallShape::mesh:
      return {{"point", "a mesh is placed by 'placement: {translation: ..., rotation: ...}'"},
              {"center", "a mesh is placed by 'placement: {translation: ..., rotation: ...}'"},
              {"base", "a mesh is placed by 'placement: {translation: ..., rotation: ...}'"},
              {"translation", "goes inside 'placement'"},
              {"rotation", "goes inside 'placement'"}};
    case WallShape::sieve:
      return {{"point", "a sieve takes 'base', the centre of the bottom end of its lowest segment"},
              {"center", "a sieve takes 'base', the centre of the bottom end of its lowest segment"},
              {"normal", "a sieve takes 'axis', from its bottom end to its top"},
              {"contact", "particles meet a sieve from both sides"},
              {"cap_bottom", "a sieve takes 'ends: {bottom: capped}' to close its lowest segment"}};
  }
  return {};
}

void read_motion(const YamlValue& value, WallSpec& wall) {
  const auto section = value.section();
  if (!section) return;
  section->allow_only({"velocity", "angular_velocity", "axis", "axis_point", "start", "stop", "stop_at_depth",
                       "stop_at_thrust", "depth_at_start"});
  MotionSpec& motion = wall.motion;
  motion.velocity_m_per_s = section->vector("velocity", Dimension::velocity).value_or(Vec3{});
  motion.axis_point_m = section->vector("axis_point", Dimension::length).value_or(wall.point_m);

  if (const auto spin = section->get("angular_velocity")) {
    if (spin->node().IsScalar()) {
      // "200 rpm" turns about `axis`, by default the wall's own axis (right-handed).
      const auto speed = spin->quantity(Dimension::angular_velocity);
      const auto axis = read_direction(*section, "axis", Presence::optional);
      if (speed) motion.angular_velocity_rad_per_s = axis.value_or(wall.normal) * *speed;
    } else {
      if (section->has("axis")) {
        section->get("axis")->error(
            "'axis' goes with a single angular speed (e.g. 200 rpm); the vector "
            "angular_velocity already gives the axis");
      }
      motion.angular_velocity_rad_per_s =
          spin->vector(Dimension::angular_velocity).value_or(Vec3{});
    }
    const Vec3& omega = motion.angular_velocity_rad_per_s;
    // Analytic walls may only spin about their own symmetry axis (or plane normal);
    // a mesh turns as a rigid body about any axis.
    if (!is_mesh(wall.shape) && norm(cross(omega, wall.normal)) > 1e-9 * norm(omega)) {
      spin->error("an analytic wall can turn only about its own axis (its 'axis' or 'normal')");
    }
    // A plane turned about any line along its normal stays in place; a disk or cylinder
    // only about its own axis.
    const Vec3 offset = motion.axis_point_m - wall.point_m;
    if (wall.shape != WallShape::plane && !is_mesh(wall.shape) &&
        norm(cross(offset, wall.normal)) > 1e-9 * (norm(offset) + 1e-3)) {
      (section->has("axis_point") ? *section->get("axis_point") : *spin)
          .error("the rotation axis must pass through the wall's own axis");
    }
  } else if (section->has("axis")) {
    section->get("axis")->error("'axis' is only used with 'angular_velocity'");
  }

  motion.start_s = read_checked_quantity(*section, "start", Dimension::time, Presence::optional,
                                         is_non_negative, "be 0 or more")
                       .value_or(0.0);
  if (const auto stop = read_checked_quantity(*section, "stop", Dimension::time,
                                              Presence::optional, is_positive,
                                              "be greater than 0")) {
    if (*stop <= motion.start_s) section->get("stop")->error("must be later than 'start'");
    motion.stop_s = *stop;
  }
  // Depth: how far the wall has been fed along its velocity, plus where it started.
  motion.depth_at_start_m =
      read_checked_quantity(*section, "depth_at_start", Dimension::length, Presence::optional, is_any, "")
          .value_or(0.0);
  if (const auto stop_depth = section->get("stop_at_depth")) {
    if (norm(motion.velocity_m_per_s) == 0.0) {
      stop_depth->error("the depth is measured along 'velocity' (the feed); give the wall a velocity");
    } else if (const auto depth = stop_depth->quantity(Dimension::length)) {
      if (*depth <= motion.depth_at_start_m)
        stop_depth->error(fmt::format("must be deeper than 'depth_at_start' ({} m)", motion.depth_at_start_m));
      else
        motion.stop_at_depth_m = *depth;
    }
  }
  if (const auto stop_thrust = section->get("stop_at_thrust")) {
    if (norm(motion.velocity_m_per_s) == 0.0) {
      stop_thrust->error("the thrust is the particles' force against 'velocity' (the feed); give the wall a velocity");
    } else if (const auto thrust = read_checked_quantity(*section, "stop_at_thrust", Dimension::force,
                                                         Presence::required, is_positive, "be greater than 0")) {
      motion.stop_at_thrust_N = *thrust;
    }
  }
}

void read_cylinder_ends(const YamlValue& value, WallSpec& wall) {
  const auto section = value.section();
  if (!section) return;
  if (wall.shape == WallShape::sieve) {
    section->allow_only({"bottom"}, {{"top", "the top of a sieve is open"}});
  } else {
    section->allow_only({"bottom", "top"});
  }
  const std::vector<std::string> options{"open", "capped"};
  if (const auto bottom = section->get("bottom")) {
    wall.cap_bottom = bottom->choice(options).value_or("open") == "capped";
  }
  if (const auto top = section->get("top")) {
    wall.cap_top = top->choice(options).value_or("open") == "capped";
  }
}

void read_shape(const YamlSection& section, const ScenarioReferences& references, WallSpec& wall) {
  const char* point_key = "point";
  const char* direction_key = "normal";
  if (wall.shape == WallShape::disk) point_key = "center";
  const bool cylindrical = wall.shape == WallShape::cylinder || wall.shape == WallShape::sieve;
  if (cylindrical) {
    point_key = "base";
    direction_key = "axis";
  }
  const auto point = section.required_vector(point_key, Dimension::length);
  // A cylinder is usually upright, so its axis defaults to +z; a plane or disk must say
  // which side the particles are on.
  const auto direction = read_direction(section, direction_key,
                                        cylindrical ? Presence::optional : Presence::required);
  if (point) wall.point_m = *point;
  if (direction) wall.normal = *direction;

  std::optional<Bounds> extent;
  switch (wall.shape) {
    case WallShape::plane:
      if (point) extent = Bounds{*point, *point};
      break;
    case WallShape::disk: {
      const auto radius = read_radius(section, "radius", "diameter", Presence::required);
      if (radius) wall.radius_m = *radius;
      if (point && direction && radius) extent = cylinder_bounds(*point, *direction, *radius, 0.0);
      break;
    }
    case WallShape::cylinder: {
      const auto radius = read_radius(section, "radius", "diameter", Presence::required);
      const auto length = read_checked_quantity(section, "length", Dimension::length,
                                                Presence::required, is_positive,
                                                "be greater than 0");
      if (radius) wall.radius_m = *radius;
      if (length) wall.length_m = *length;
      if (const auto contact = section.get("contact")) {
        const auto side = contact->choice({"inside", "outside", "both"});
        if (side == "outside") wall.side = CylinderSide::outside;
        if (side == "both") wall.side = CylinderSide::both;
      }
      if (const auto ends = section.get("ends")) read_cylinder_ends(*ends, wall);
      if (point && (direction || !section.has(direction_key)) && radius && length) {
        extent = cylinder_bounds(*point, wall.normal, *radius, *length);
      }
      break;
    }
    case WallShape::sieve: {
      const auto radius = read_radius(section, "radius", "diameter", Presence::required);
      const auto length = read_checked_quantity(section, "length", Dimension::length,
                                                Presence::required, is_positive,
                                                "be greater than 0");
      std::optional<std::uint64_t> segments;
      if (const auto segments_value = section.require("segments")) {
        segments = segments_value->whole_number();
        // Each segment is a wall body with its own temperature; the bound only keeps
        // the count an int.
        constexpr std::uint64_t kMostSegments = 65536;
        if (segments && (*segments == 0 || *segments > kMostSegments)) {
          segments_value->error(fmt::format("must be at least 1 and at most {}, got '{}'", kMostSegments,
                                            segments_value->node().Scalar()));
          segments.reset();
        }
      }
      if (radius) wall.radius_m = *radius;
      if (length) wall.length_m = *length;
      if (segments) wall.segments = static_cast<int>(*segments);
      wall.side = CylinderSide::both;
      if (const auto ends = section.get("ends")) read_cylinder_ends(*ends, wall);
      if (point && (direction || !section.has(direction_key)) && radius && length && segments) {
        extent = cylinder_bounds(*point, wall.normal, *radius,
                                 *length * static_cast<double>(wall.segments));
      }
      break;
    }
    case WallShape::mesh:
    case WallShape::auger: break;  // read_mesh_shape
  }
  if (extent) check_inside_domain(section.value(), *extent, references, "the wall");
}

const std::vector<std::string> kThermalKeys{"mode",          "temperature", "conductivity", "conductivity_mix",
                                           "specific_heat", "mass",        "areal_density", "segments",
                                           "rod",           "held_end",    "radiation"};

/// The keys a thermal mode takes, and why the others do not belong.
std::vector<std::string> thermal_keys_for(WallThermalModeSpec mode) {
  switch (mode) {
    case WallThermalModeSpec::adiabatic: return {"mode"};
    case WallThermalModeSpec::fixed: return {"mode", "temperature", "conductivity", "conductivity_mix"};
    case WallThermalModeSpec::lumped: return kThermalKeys;
  }
  return kThermalKeys;
}

std::vector<std::pair<std::string, std::string>> misplaced_thermal_keys(WallThermalModeSpec mode) {
  if (mode == WallThermalModeSpec::adiabatic) {
    const std::string why = "an adiabatic wall passes no heat; use mode: fixed or lumped";
    std::vector<std::pair<std::string, std::string>> hints;
    for (const std::string& key : kThermalKeys) hints.emplace_back(key, why);
    return hints;
  }
  const std::string why = "only a lumped wall has a heat capacity";
  const std::string rod_why = "only a lumped wall has its own heat paths (a fixed wall holds its temperature)";
  return {{"specific_heat", why}, {"mass", why},          {"areal_density", why}, {"segments", rod_why},
          {"rod", rod_why},       {"held_end", rod_why}, {"radiation", rod_why}};
}

/// A lumped wall's own heat paths (docs/drilling-heat.md, "The drill as a thermal body"):
/// `segments` and `rod` and `held_end` for a mesh or auger (the rod runs along its axis),
/// `radiation` for any wall with an area.
void read_lumped_heat_paths(const YamlSection& section, const WallSpec& wall, WallThermalSpec& thermal) {
  const bool mesh = is_mesh(wall.shape);
  for (const char* key : {"segments", "rod", "held_end"})
    if (!mesh && section.has(key))
      section.get(key)->error(fmt::format("'{}' belongs to a mesh or auger wall, whose rod runs along its axis; "
                                          "a {} wall is one lumped body",
                                          key, wall.shape == WallShape::sieve ? "sieve segment" : "primitive"));
  if (mesh) {
    if (const auto segments = section.get("segments")) {
      const auto n = segments->whole_number();
      if (n && (*n < 1 || *n > 1000)) segments->error(fmt::format("must be 1 to 1000, got {}", *n));
      if (n && *n >= 1 && *n <= 1000) thermal.segments = static_cast<int>(*n);
    }
    if (const auto rod_value = section.get("rod")) {
      if (const auto rod = rod_value->section()) {
        rod->allow_only({"conductivity", "cross_section"});
        thermal.rod_conductivity_W_per_mK = read_checked_quantity(
            *rod, "conductivity", Dimension::thermal_conductivity, Presence::optional, is_positive, "be greater than 0");
        thermal.rod_cross_section_m2 = read_checked_quantity(*rod, "cross_section", Dimension::area,
                                                             Presence::required, is_positive, "be greater than 0")
                                           .value_or(0.0);
      }
    }
    thermal.held_end_K = read_checked_quantity(section, "held_end", Dimension::temperature, Presence::optional,
                                               is_positive, "be greater than 0 K");
    const bool needs_rod = thermal.segments > 1 || thermal.held_end_K;
    if (needs_rod && !section.has("rod"))
      section.get(thermal.segments > 1 ? "segments" : "held_end")
          ->error("heat runs along the rod: give `rod: {cross_section: ..., conductivity: ...}` (the conductivity "
                  "defaults to the wall material's)");
    if (!needs_rod && section.has("rod"))
      section.get("rod")->error("a rod conducts between segments or to a held end: give `segments` (2 or more) or "
                                "`held_end`");
  }
  if (const auto radiation_value = section.get("radiation")) {
    if (wall.shape == WallShape::plane) {
      radiation_value->error("a plane is unbounded and has no area to radiate from");
      return;
    }
    if (const auto radiation = radiation_value->section()) {
      radiation->allow_only({"emissivity", "surroundings"});
      const auto emissivity = read_checked_quantity(*radiation, "emissivity", Dimension::dimensionless,
                                                    Presence::required, is_positive, "be greater than 0");
      if (emissivity && *emissivity > 1.0)
        radiation->get("emissivity")->error(fmt::format("must be at most 1, got {}", *emissivity));
      else if (emissivity)
        thermal.emissivity = *emissivity;
      thermal.surroundings_K = read_checked_quantity(*radiation, "surroundings", Dimension::temperature,
                                                     Presence::required, is_non_negative, "be 0 K or more")
                                   .value_or(0.0);
    }
  }
}

/// A fixed wall's temperature: one value, or {time: [...], value: [...]} (linear
/// between rows, held outside them).
void read_fixed_temperature(const YamlValue& value, WallThermalSpec& thermal) {
  if (value.node().IsMap()) {
    const auto rows = read_table(value, {"time", Dimension::time, is_non_negative, "be 0 or more"},
                                 {"value", Dimension::temperature, is_any, ""});
    if (!rows) return;
    thermal.time_s = rows->x;
    thermal.temperature_K = rows->y;
    return;
  }
  if (const auto temperature = value.quantity(Dimension::temperature)) {
    thermal.time_s = {0.0};
    thermal.temperature_K = {*temperature};
  }
}

void read_lumped_capacity(const YamlSection& section, const WallSpec& wall, WallThermalSpec& thermal) {
  thermal.specific_heat_J_per_kgK =
      read_checked_quantity(section, "specific_heat", Dimension::specific_heat, Presence::required,
                            is_positive, "be greater than 0")
          .value_or(0.0);
  const auto key = section.exactly_one_of({"mass", "areal_density"});
  if (!key) return;
  if (*key == "mass") {
    thermal.mass_kg = read_checked_quantity(section, "mass", Dimension::mass, Presence::required,
                                            is_positive, "be greater than 0")
                          .value_or(0.0);
    return;
  }
  if (wall.shape == WallShape::plane) {
    section.get("areal_density")->error("a plane is unbounded and has no area: give the wall's 'mass'");
    return;
  }
  thermal.areal_density_kg_per_m2 =
      read_checked_quantity(section, "areal_density", Dimension::areal_density, Presence::required,
                            is_positive, "be greater than 0")
          .value_or(0.0);
}

/// The `thermal` block (DESIGN.md section 2, "Thermal walls"). Whether heat is on at
/// all is checked here too, at the mode, so that the message points at the wall.
void read_wall_thermal(const YamlValue& value, const ScenarioReferences& references, WallSpec& wall) {
  const auto section = value.section();
  if (!section) return;
  WallThermalSpec& thermal = wall.thermal;
  thermal.where = value.where();
  const auto mode_value = section->require("mode");
  const auto mode = mode_value ? mode_value->choice({"adiabatic", "fixed", "lumped"}) : std::nullopt;
  if (!mode) {
    section->allow_only(kThermalKeys);
    return;
  }
  thermal.mode = *mode == "adiabatic" ? WallThermalModeSpec::adiabatic
                 : *mode == "fixed"   ? WallThermalModeSpec::fixed
                                      : WallThermalModeSpec::lumped;
  section->allow_only(thermal_keys_for(thermal.mode), misplaced_thermal_keys(thermal.mode));
  if (thermal.mode == WallThermalModeSpec::adiabatic) return;
  // `heat: {enabled: false}` switches heat off for a whole run (thermal walls are then
  // ignored); without any `heat` section a thermal wall is surely a forgotten section.
  if (!references.heat_section) {
    mode_value->error(fmt::format("a {} wall exchanges heat, but heat transfer is off: add a "
                                  "top-level `heat:` section (e.g. `heat: {{}}`)",
                                  *mode));
  }

  if (const auto temperature = section->require("temperature")) {
    if (thermal.mode == WallThermalModeSpec::fixed) {
      read_fixed_temperature(*temperature, thermal);
    } else if (temperature->node().IsMap()) {
      temperature->error("a lumped wall's temperature is its initial value: give one temperature "
                         "(a table over time is for mode: fixed)");
    } else if (const auto initial = temperature->quantity(Dimension::temperature)) {
      thermal.time_s = {0.0};
      thermal.temperature_K = {*initial};
    }
  }
  const auto conductivity = section->get("conductivity");
  if (conductivity && conductivity->node().IsScalar() && conductivity->node().Scalar() == "particles") {
    thermal.conductivity_of_particles = true;
  } else {
    thermal.conductivity_W_per_mK =
        read_checked_quantity(*section, "conductivity", Dimension::thermal_conductivity, Presence::optional,
                              is_positive, "be greater than 0 (or `particles`: the particles' own)");
  }
  if (const auto mix = section->get("conductivity_mix")) {
    thermal.harmonic_mean = mix->choice({"wall", "harmonic_mean"}).value_or("wall") == "harmonic_mean";
  }
  if (thermal.mode == WallThermalModeSpec::lumped) {
    read_lumped_capacity(*section, wall, thermal);
    read_lumped_heat_paths(*section, wall, thermal);
  }
}

std::optional<WallSpec> read_wall(const YamlValue& item, const ScenarioReferences& references) {
  const auto section = item.section();
  if (!section) return std::nullopt;
  WallSpec wall;
  wall.where = item.where();
  const auto type_value = section->require("type");
  const auto type =
      type_value ? type_value->choice({"plane", "disk", "cylinder", "sieve", "mesh", "auger"}) : std::nullopt;
  if (!type) {
    // Without a shape, still catch keys that no wall takes.
    std::vector<std::string> any_wall_key = keys_for(WallShape::cylinder);
    any_wall_key.insert(any_wall_key.end(), {"point", "center", "normal", "segments"});
    section->allow_only(any_wall_key);
    read_item_name(*section);
    return std::nullopt;
  }
  wall.shape = *type == "plane"      ? WallShape::plane
               : *type == "disk"     ? WallShape::disk
               : *type == "cylinder" ? WallShape::cylinder
               : *type == "sieve"    ? WallShape::sieve
               : *type == "mesh"     ? WallShape::mesh
                                     : WallShape::auger;
  section->allow_only(keys_for(wall.shape), misplaced_keys(wall.shape));
  const auto name = read_item_name(*section);
  if (name) wall.name = *name;

  if (const auto material = section->get("material")) {
    wall.material = read_reference(*material, references.material_names, "material").value_or("");
  }
  if (is_mesh(wall.shape))
    read_mesh_shape(*section, references, wall);
  else
    read_shape(*section, references, wall);
  if (const auto motion = section->get("motion")) read_motion(*motion, wall);
  if (const auto thermal = section->get("thermal")) read_wall_thermal(*thermal, references, wall);
  if (!name) return std::nullopt;
  return wall;
}

}  // namespace

void read_walls(const YamlSection& root, const ScenarioReferences& references,
                ScenarioSpec& spec) {
  const auto value = root.get("walls");
  if (!value) return;
  const auto items = value->items();
  if (!items) return;
  std::vector<NamedPlace> names;
  for (const YamlValue& item : *items) {
    if (auto wall = read_wall(item, references)) {
      names.push_back({wall->name, wall->where});
      spec.walls.push_back(std::move(*wall));
    }
  }
  report_duplicate_names(names, "wall", value->context().diagnostics);
}

}  // namespace regodem
