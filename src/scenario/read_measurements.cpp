// The `measurements` section: the per-particle thermal history, and regions, bands
// beside a wall (the paper's T_in, T_out, T_d, Eq. 3-5) and temperature profiles
// (Figs. 3 and 13a), each with its schedule.
#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "scenario/scenario_fields.hpp"
#include "scenario/scenario_sections.hpp"

namespace regodem {
namespace {

const std::vector<std::string> kScheduleKeys{"interval", "every_steps", "every_depth", "at_times", "at_depths",
                                             "at_stage_end"};

std::string heat_off(const ScenarioReferences& references) {
  return references.heat_section ? "but heat is off (`heat: {enabled: false}`)"
                                 : "but heat transfer is off: add a top-level `heat:` section (e.g. `heat: {}`)";
}

std::vector<std::string> wall_names(const ScenarioSpec& spec) {
  std::vector<std::string> names;
  for (const WallSpec& w : spec.walls) names.push_back(w.name);
  return names;
}

/// `[low, high]`: two quantities with low < high (low >= 0 when `non_negative`).
std::optional<std::pair<double, double>> read_range(const YamlSection& section, std::string_view key,
                                                    Dimension dimension, bool non_negative) {
  const auto value = section.require(key);
  if (!value) return std::nullopt;
  if (!value->node().IsSequence() || value->node().size() != 2) {
    value->error(fmt::format("expected a list of two values [low, high], each {} (e.g. [0, {}])",
                             dimension_description(dimension), dimension_example(dimension)));
    return std::nullopt;
  }
  const auto items = value->items();
  if (!items) return std::nullopt;
  const auto low = (*items)[0].quantity(dimension);
  const auto high = (*items)[1].quantity(dimension);
  if (!low || !high) return std::nullopt;
  if (non_negative && *low < 0.0) {
    (*items)[0].error(fmt::format("must be 0 or more, got '{}'", (*items)[0].node().Scalar()));
    return std::nullopt;
  }
  if (!(*low < *high)) {
    value->error(fmt::format("the range is inverted or empty: low ({:g}) must be below high ({:g})", *low, *high));
    return std::nullopt;
  }
  return std::pair{*low, *high};
}

/// Values of a list that must increase (times or depths of samples).
std::optional<std::vector<double>> read_increasing(const YamlValue& value, Dimension dimension,
                                                   bool (*valid)(double), std::string_view rule) {
  auto values = read_quantity_list(value, dimension, valid, rule);
  if (!values) return std::nullopt;
  for (std::size_t k = 1; k < values->size(); ++k)
    if (!((*values)[k] > (*values)[k - 1])) {
      value.error(fmt::format("the values must increase: {:g} follows {:g}", (*values)[k], (*values)[k - 1]));
      return std::nullopt;
    }
  return values;
}

/// The schedule keys of an entry: at most one trigger; none samples with the time series.
void read_schedule(const YamlSection& section, const std::vector<std::string>& walls, MeasurementSpec& out) {
  MeasurementSchedule& schedule = out.measurement.schedule;
  SnapshotSchedule& periodic = schedule.periodic;
  const auto trigger = section.at_most_one_of({"interval", "every_steps", "every_depth", "at_times", "at_depths"});
  if (trigger == "interval") {
    if (const auto interval = read_checked_quantity(section, "interval", Dimension::time, Presence::required,
                                                    is_positive, "be greater than 0")) {
      periodic.trigger = SnapshotSchedule::Trigger::time;
      periodic.interval_s = *interval;
    }
  } else if (trigger == "every_steps") {
    const YamlValue steps = *section.get("every_steps");
    if (const auto count = steps.whole_number()) {
      if (*count == 0) {
        steps.error("must be 1 or more (steps between samples)");
      } else {
        periodic.trigger = SnapshotSchedule::Trigger::steps;
        periodic.every_steps = *count;
      }
    }
  } else if (trigger == "every_depth") {
    if (const auto depth = section.get("every_depth")->section()) {
      depth->allow_only({"wall", "depth"});
      const auto wall = depth->require("wall");
      const auto name = wall ? read_reference(*wall, walls, "wall") : std::nullopt;
      const auto step = read_checked_quantity(*depth, "depth", Dimension::length, Presence::required, is_positive,
                                              "be greater than 0");
      if (name && step) {
        periodic.trigger = SnapshotSchedule::Trigger::depth;
        periodic.depth_interval_m = *step;
        out.depth_wall = *name;
      }
    }
  } else if (trigger == "at_times") {
    if (auto times = read_increasing(*section.get("at_times"), Dimension::time, is_non_negative, "be 0 or more"))
      schedule.at_times_s = std::move(*times);
  } else if (trigger == "at_depths") {
    if (const auto depths = section.get("at_depths")->section()) {
      depths->allow_only({"wall", "depths"}, {{"depth", "'depths' is a list, e.g. [75 mm, 100 mm]"}});
      const auto wall = depths->require("wall");
      const auto name = wall ? read_reference(*wall, walls, "wall") : std::nullopt;
      const auto list = depths->require("depths");
      auto values = list ? read_increasing(*list, Dimension::length, is_any, "be a depth") : std::nullopt;
      if (name && values) {
        schedule.at_depths_m = std::move(*values);
        out.depth_wall = *name;
      }
    }
  }
  periodic.at_stage_end = section.boolean("at_stage_end").value_or(true);
  if (section.has("at_stage_end") && !periodic.enabled())
    section.get("at_stage_end")
        ->error("only with 'interval', 'every_steps' or 'every_depth' (listed instants take no extra sample; "
                "a measurement without a schedule samples with the time series, which ends every stage)");
}

void read_moves_with(const YamlSection& section, const std::vector<std::string>& walls, MeasurementSpec& out) {
  if (const auto wall = section.get("moves_with"))
    out.moves_with = read_reference(*wall, walls, "wall").value_or("");
}

/// A surface beside which a band lies: `wall: NAME` (plane, disk, cylinder or sieve),
/// `plane: {point, normal}` or `cylinder: {base, axis, radius, length}`.
struct Surface {
  bool cylinder = false;
  Vec3 point_m, direction{0.0, 0.0, 1.0};
  double radius_m = 0.0;  // cylinder
  double length_m = std::numeric_limits<double>::infinity();
  double lateral_radius_m = std::numeric_limits<double>::infinity();  // a disk
};

std::optional<Surface> read_surface(const YamlSection& section, const ScenarioSpec& spec) {
  const auto key = section.exactly_one_of({"wall", "plane", "cylinder"});
  if (!key) return std::nullopt;
  Surface surface;
  if (*key == "wall") {
    const YamlValue value = *section.get("wall");
    const auto name = read_reference(value, wall_names(spec), "wall");
    if (!name) return std::nullopt;
    const WallSpec& w = *std::find_if(spec.walls.begin(), spec.walls.end(), [&](const WallSpec& s) { return s.name == *name; });
    surface.point_m = w.point_m;
    surface.direction = normalized(w.normal);
    switch (w.shape) {
      case WallShape::plane: break;
      case WallShape::disk: surface.lateral_radius_m = w.radius_m; break;
      case WallShape::cylinder:
      case WallShape::sieve:
        surface.cylinder = true;
        surface.radius_m = w.radius_m;
        surface.length_m = w.length_m * (w.shape == WallShape::sieve ? w.segments : 1);
        break;
      case WallShape::mesh:
      case WallShape::auger:
        value.error(fmt::format("wall '{}' is a mesh: a band lies beside a plane, disk, cylinder or sieve wall "
                                "(or give 'plane' or 'cylinder')",
                                *name));
        return std::nullopt;
    }
    return surface;
  }
  const auto shape = section.get(*key)->section();
  if (!shape) return std::nullopt;
  if (*key == "plane") {
    shape->allow_only({"point", "normal"});
    const auto point = shape->required_vector("point", Dimension::length);
    const auto normal = read_direction(*shape, "normal", Presence::required);
    if (!point || !normal) return std::nullopt;
    surface.point_m = *point;
    surface.direction = *normal;
    return surface;
  }
  shape->allow_only({"base", "axis", "radius", "diameter", "length"});
  surface.cylinder = true;
  const auto base = shape->required_vector("base", Dimension::length);
  const auto axis = read_direction(*shape, "axis", Presence::optional);
  const auto radius = read_radius(*shape, "radius", "diameter", Presence::required);
  const auto length = read_checked_quantity(*shape, "length", Dimension::length, Presence::optional, is_positive,
                                            "be greater than 0");
  if (!base || !radius || (shape->has("axis") && !axis) || (shape->has("length") && !length)) return std::nullopt;
  surface.point_m = *base;
  surface.direction = axis.value_or(Vec3{0.0, 0.0, 1.0});
  surface.radius_m = *radius;
  surface.length_m = length.value_or(surface.length_m);
  return surface;
}

/// `front`/`back` beside a plane, `inside`/`outside` beside a cylinder; true for the
/// front or the outside (the side of positive distance).
std::optional<bool> read_side(const YamlSection& section, std::string_view key, const Surface& surface) {
  const auto value = section.require(key);
  if (!value) return std::nullopt;
  const auto side = surface.cylinder ? value->choice({"inside", "outside"}) : value->choice({"front", "back"});
  if (!side) return std::nullopt;
  return *side == "front" || *side == "outside";
}

MeasureRegion band_region(const Surface& s, double width_m, bool positive_side) {
  return s.cylinder ? cylinder_band(s.point_m, s.direction, s.radius_m, s.length_m, width_m, positive_side)
                    : plane_band(s.point_m, s.direction, width_m, positive_side, s.lateral_radius_m);
}

std::optional<double> read_width(const YamlSection& section) {
  return read_checked_quantity(section, "width", Dimension::length, Presence::required, is_positive,
                               "be greater than 0");
}

std::optional<MeasureRegion> read_measure_region(const YamlValue& value, const ScenarioSpec& spec) {
  const auto section = value.section();
  if (!section) return std::nullopt;
  const auto type_value = section->require("type");
  const auto type =
      type_value ? type_value->choice({"box", "cylinder", "annulus", "chip_zone", "band"}) : std::nullopt;
  if (!type) return std::nullopt;
  MeasureRegion region;
  if (*type == "box") {
    section->allow_only({"type", "min", "max"});
    region.shape = MeasureShape::box;
    const auto low = section->required_vector("min", Dimension::length);
    const auto high = section->required_vector("max", Dimension::length);
    if (!low || !high) return std::nullopt;
    for (int axis = 0; axis < 3; ++axis)
      if (!((*low)[axis] < (*high)[axis])) {
        section->get("max")->error(fmt::format("must be above 'min' along every axis ({} is not)", "xyz"[axis]));
        return std::nullopt;
      }
    region.min_m = *low;
    region.max_m = *high;
    return region;
  }
  if (*type == "band") {
    section->allow_only({"type", "wall", "plane", "cylinder", "width", "side"});
    const auto surface = read_surface(*section, spec);
    const auto width = read_width(*section);
    const auto side = surface ? read_side(*section, "side", *surface) : std::nullopt;
    if (!surface || !width || !side) return std::nullopt;
    return band_region(*surface, *width, *side);
  }
  // The chip-removal zone (paper Section 5.2, Fig. 11): an annulus standing on the
  // initial sample surface around the hole, where the cuttings pile up.
  const bool chip_zone = *type == "chip_zone";
  const bool annulus = *type == "annulus" || chip_zone;
  std::vector<std::string> allowed{"type", "axis", "radius", "diameter"};
  allowed.insert(allowed.end(), chip_zone ? std::initializer_list<std::string>{"center", "height"}
                                          : std::initializer_list<std::string>{"base", "length"});
  if (annulus) allowed.insert(allowed.end(), {"inner_radius", "inner_diameter"});
  section->allow_only(allowed, {{"base", "a chip_zone stands on the sample surface: give its 'center' there"},
                                {"length", "a chip_zone takes its 'height' above the surface"},
                                {"inner_radius", "only an annulus or chip_zone has an inner radius"}});
  region.shape = annulus ? MeasureShape::annulus : MeasureShape::cylinder;
  const auto base = section->required_vector(chip_zone ? "center" : "base", Dimension::length);
  const auto axis = read_direction(*section, "axis", Presence::optional);
  const auto radius = read_radius(*section, "radius", "diameter", Presence::required);
  const auto length = read_checked_quantity(*section, chip_zone ? "height" : "length", Dimension::length,
                                            Presence::required, is_positive, "be greater than 0");
  std::optional<double> inner = 0.0;
  if (annulus) {
    inner = read_radius(*section, "inner_radius", "inner_diameter", Presence::required);
    if (inner && radius && *inner >= *radius) {
      section->get(section->has("inner_radius") ? "inner_radius" : "inner_diameter")
          ->error(fmt::format("the inner radius ({:g} m) must be smaller than the outer radius ({:g} m)", *inner,
                              *radius));
      return std::nullopt;
    }
  }
  if (!base || !radius || !length || !inner || (section->has("axis") && !axis)) return std::nullopt;
  region.base_m = *base;
  region.axis = axis.value_or(Vec3{0.0, 0.0, 1.0});
  region.radius_m = *radius;
  region.inner_radius_m = *inner;
  region.length_m = *length;
  return region;
}

std::optional<MeasurementSpec> read_region_entry(const YamlValue& item, const ScenarioSpec& spec) {
  const auto section = item.section();
  if (!section) return std::nullopt;
  std::vector<std::string> allowed{"name", "region", "moves_with"};
  allowed.insert(allowed.end(), kScheduleKeys.begin(), kScheduleKeys.end());
  section->allow_only(allowed);
  MeasurementSpec out;
  out.where = item.where();
  out.measurement.kind = MeasurementKind::region;
  const auto name = read_item_name(*section);
  const auto region_value = section->require("region");
  const auto region = region_value ? read_measure_region(*region_value, spec) : std::nullopt;
  const std::vector<std::string> walls = wall_names(spec);
  read_moves_with(*section, walls, out);
  read_schedule(*section, walls, out);
  if (!name || !region) return std::nullopt;
  out.measurement.name = *name;
  out.measurement.region = *region;
  return out;
}

std::optional<MeasurementSpec> read_band_entry(const YamlValue& item, const ScenarioSpec& spec,
                                               const ScenarioReferences& references) {
  const auto section = item.section();
  if (!section) return std::nullopt;
  std::vector<std::string> allowed{"name", "wall", "plane", "cylinder", "width", "in_side", "moves_with"};
  allowed.insert(allowed.end(), kScheduleKeys.begin(), kScheduleKeys.end());
  section->allow_only(allowed, {{"side", "a band measurement names the side of T_in: 'in_side'"}});
  MeasurementSpec out;
  out.where = item.where();
  out.measurement.kind = MeasurementKind::band;
  if (!references.heat_enabled) item.error(fmt::format("a band measures temperatures, {}", heat_off(references)));
  const auto name = read_item_name(*section);
  const auto surface = read_surface(*section, spec);
  const auto width = read_width(*section);
  const auto in_side = surface ? read_side(*section, "in_side", *surface) : std::nullopt;
  const std::vector<std::string> walls = wall_names(spec);
  // A band beside a moving wall moves with it unless it says otherwise.
  if (const auto wall = section->get("wall"); wall && !section->has("moves_with") && wall->node().IsScalar())
    for (const WallSpec& w : spec.walls)
      if (w.name == wall->node().Scalar() && (norm2(w.motion.velocity_m_per_s) > 0.0)) out.moves_with = w.name;
  read_moves_with(*section, walls, out);
  read_schedule(*section, walls, out);
  if (!name || !surface || !width || !in_side) return std::nullopt;
  out.measurement.name = *name;
  const bool in_front = in_side.value_or(false);  // (value_or: GCC 12 warns on *in_side here)
  out.measurement.band_in = band_region(*surface, *width, in_front);
  out.measurement.band_out = band_region(*surface, *width, !in_front);
  return out;
}

std::optional<MeasurementSpec> read_profile_entry(const YamlValue& item, const ScenarioSpec& spec) {
  const auto section = item.section();
  if (!section) return std::nullopt;
  const auto type_value = section->get("type");
  const bool radial = type_value && type_value->node().IsScalar() && type_value->node().Scalar() == "radial";
  std::vector<std::string> allowed{"name", "type", "range", "bin", "moves_with"};
  if (radial)
    allowed.insert(allowed.end(), {"axis_point", "axis", "slab"});
  else
    allowed.insert(allowed.end(), {"point", "normal"});
  allowed.insert(allowed.end(), kScheduleKeys.begin(), kScheduleKeys.end());
  section->allow_only(allowed, {{"axis_point", "only a radial profile has an axis ('type: radial')"},
                                {"slab", "only a radial profile has a slab ('type: radial')"},
                                {"point", "a radial profile takes 'axis_point' and 'axis'"},
                                {"normal", "a radial profile takes 'axis_point' and 'axis'"}});
  MeasurementSpec out;
  out.where = item.where();
  out.measurement.kind = MeasurementKind::profile;
  const auto name = read_item_name(*section);
  const auto type_required = section->require("type");
  const auto type = type_required ? type_required->choice({"plane", "radial"}) : std::nullopt;
  ProfileGeometry& p = out.measurement.profile;
  bool complete = type.has_value();
  if (radial) {
    p.coordinate = ProfileCoordinate::radius;
    const auto origin = section->required_vector("axis_point", Dimension::length);
    const auto axis = read_direction(*section, "axis", Presence::optional);
    const auto slab = read_range(*section, "slab", Dimension::length, false);
    complete = complete && origin && slab && !(section->has("axis") && !axis);
    if (complete) {
      p.origin_m = *origin;
      p.direction = axis.value_or(Vec3{0.0, 0.0, 1.0});
      p.slab_min_m = slab->first;
      p.slab_max_m = slab->second;
    }
  } else {
    p.coordinate = ProfileCoordinate::plane_distance;
    const auto point = section->required_vector("point", Dimension::length);
    const auto normal = read_direction(*section, "normal", Presence::required);
    complete = complete && point && normal;
    if (complete) {
      p.origin_m = *point;
      p.direction = *normal;
    }
  }
  const auto range = read_range(*section, "range", Dimension::length, radial);
  const auto bin = read_checked_quantity(*section, "bin", Dimension::length, Presence::required, is_positive,
                                         "be greater than 0");
  const std::vector<std::string> walls = wall_names(spec);
  read_moves_with(*section, walls, out);
  read_schedule(*section, walls, out);
  if (!name || !complete || !range || !bin) return std::nullopt;
  out.measurement.name = *name;
  p.min_m = range->first;
  p.max_m = range->second;
  p.bin_m = *bin;
  if (p.bin_count() > 100000) {
    section->get("bin")->error(fmt::format("makes {} bins over the range: use a wider bin", p.bin_count()));
    return std::nullopt;
  }
  return out;
}

template <class ReadEntry>
void read_list(const YamlSection& section, std::string_view key, std::vector<NamedPlace>& names,
               MeasurementsSpec& out, ReadEntry read_entry) {
  const auto value = section.get(key);
  if (!value) return;
  const auto items = value->items();
  if (!items) return;
  for (const YamlValue& item : *items) {
    if (auto entry = read_entry(item)) {
      names.push_back({entry->measurement.name, entry->where});
      out.items.push_back(std::move(*entry));
    }
  }
}

}  // namespace

void read_measurements(const YamlSection& root, const ScenarioReferences& references, ScenarioSpec& spec) {
  const auto value = root.get("measurements");
  if (!value) return;
  const auto section = value->section();
  if (!section) return;
  section->allow_only({"thermal_history", "regions", "bands", "profiles"});
  MeasurementsSpec& out = spec.measurements;
  out.where = value->where();
  if (const auto history = section->get("thermal_history")) {
    if (const auto block = history->section()) {
      block->allow_only({"threshold"});
      if (!references.heat_enabled) {
        history->error(fmt::format("the thermal history follows particle temperatures, {}", heat_off(references)));
      } else {
        out.thermal_history = true;
        out.thermal_history_threshold_K =
            block->quantity("threshold", Dimension::temperature).value_or(out.thermal_history_threshold_K);
      }
    }
  }
  // Regions and bands write regions/NAME.csv, profiles profiles/NAME.csv: one name each.
  std::vector<NamedPlace> region_names, profile_names;
  read_list(*section, "regions", region_names, out, [&](const YamlValue& item) { return read_region_entry(item, spec); });
  read_list(*section, "bands", region_names, out,
            [&](const YamlValue& item) { return read_band_entry(item, spec, references); });
  read_list(*section, "profiles", profile_names, out,
            [&](const YamlValue& item) { return read_profile_entry(item, spec); });
  report_duplicate_names(region_names, "region or band", value->context().diagnostics);
  report_duplicate_names(profile_names, "profile", value->context().diagnostics);
}

}  // namespace regodem
