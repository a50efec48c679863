// The `insertions` list: random insertion into a box, cylinder or annulus region with
// one size or a discrete size distribution, or particles loaded from a CSV file.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "scenario/scenario_fields.hpp"
#include "scenario/scenario_sections.hpp"

namespace regodem {
namespace {

const std::vector<std::string> kRegionInsertionKeys{
    "region", "radius", "diameter", "sizes", "fractions_by", "count", "solid_fraction",
    "mass",   "rate",   "interval", "velocity", "allow_partial"};

// The densest packing of equal spheres (Kepler): no region can hold more.
bool is_possible_solid_fraction(double value) { return value > 0.0 && value <= 0.74; }
bool is_fraction_weight(double value) { return value > 0.0; }

std::optional<RegionSpec> read_region(const YamlValue& value, const ScenarioReferences& references) {
  const auto section = value.section();
  if (!section) return std::nullopt;
  RegionSpec region;
  region.where = value.where();
  const auto type_value = section->require("type");
  const auto type = type_value ? type_value->choice({"box", "cylinder", "annulus"}) : std::nullopt;
  if (!type) return std::nullopt;

  if (*type == "box") {
    section->allow_only({"type", "min", "max"},
                        {{"base", "a box takes 'min' and 'max' corners"},
                         {"radius", "a box takes 'min' and 'max' corners"}});
    region.shape = RegionShape::box;
    const auto low = section->required_vector("min", Dimension::length);
    const auto high = section->required_vector("max", Dimension::length);
    if (!low || !high) return std::nullopt;
    region.min_m = *low;
    region.max_m = *high;
    for (int axis = 0; axis < 3; ++axis) {
      if (!(region.min_m[axis] < region.max_m[axis])) {
        section->get("max")->error(fmt::format("must be above 'min' along every axis ({} is not)",
                                               "xyz"[axis]));
        return std::nullopt;
      }
    }
    check_inside_domain(value, Bounds{region.min_m, region.max_m}, references, "the region");
    return region;
  }

  const bool annulus = *type == "annulus";
  std::vector<std::string> allowed{"type", "base", "axis", "radius", "diameter", "length"};
  if (annulus) allowed.insert(allowed.end(), {"inner_radius", "inner_diameter"});
  section->allow_only(allowed, {{"min", "a cylinder or annulus takes 'base', 'axis' and 'length'"},
                                {"max", "a cylinder or annulus takes 'base', 'axis' and 'length'"},
                                {"inner_radius", "only an annulus has an inner radius"},
                                {"inner_diameter", "only an annulus has an inner diameter"}});
  region.shape = annulus ? RegionShape::annulus : RegionShape::cylinder;
  const auto base = section->required_vector("base", Dimension::length);
  const auto axis = read_direction(*section, "axis", Presence::optional);
  const auto radius = read_radius(*section, "radius", "diameter", Presence::required);
  const auto length = read_checked_quantity(*section, "length", Dimension::length,
                                            Presence::required, is_positive, "be greater than 0");
  std::optional<double> inner_radius = 0.0;
  if (annulus) {
    inner_radius = read_radius(*section, "inner_radius", "inner_diameter", Presence::required);
    if (inner_radius && radius && *inner_radius >= *radius) {
      const std::string inner_key = section->has("inner_radius") ? "inner_radius" : "inner_diameter";
      section->get(inner_key)->error(fmt::format(
          "the inner radius ({:g} m) must be smaller than the outer radius ({:g} m)",
          *inner_radius, *radius));
      return std::nullopt;
    }
  }
  if (section->has("axis") && !axis) return std::nullopt;
  if (!base || !radius || !length || !inner_radius) return std::nullopt;
  region.base_m = *base;
  region.axis = axis.value_or(Vec3{0.0, 0.0, 1.0});
  region.radius_m = *radius;
  region.length_m = *length;
  region.inner_radius_m = *inner_radius;
  check_inside_domain(value, cylinder_bounds(region.base_m, region.axis, region.radius_m,
                                             region.length_m),
                      references, "the region");
  return region;
}

/// `sizes: [{radius: 0.3 mm, fraction: 0.7}, {diameter: 0.8 mm, fraction: 0.3}]`.
std::optional<std::vector<SizeClassSpec>> read_size_distribution(const YamlValue& value) {
  const auto items = value.items();
  if (!items) return std::nullopt;
  if (items->empty()) {
    value.error("give at least one size, e.g. [{diameter: 0.6 mm, fraction: 1}]");
    return std::nullopt;
  }
  std::vector<SizeClassSpec> sizes;
  bool complete = true;
  for (const YamlValue& item : *items) {
    const auto section = item.section();
    if (!section) {
      complete = false;
      continue;
    }
    section->allow_only({"radius", "diameter", "fraction"});
    const auto radius = read_radius(*section, "radius", "diameter", Presence::required);
    // One class needs no fraction; several must say how they share.
    const auto fraction = read_checked_quantity(
        *section, "fraction", Dimension::dimensionless,
        items->size() > 1 ? Presence::required : Presence::optional, is_fraction_weight,
        "be greater than 0");
    if (!radius || (section->has("fraction") && !fraction) || (items->size() > 1 && !fraction)) {
      complete = false;
      continue;
    }
    sizes.push_back({*radius, fraction.value_or(1.0)});
  }
  if (!complete) return std::nullopt;
  double total = 0.0;
  for (const SizeClassSpec& size : sizes) total += size.fraction;
  // A little slack for thirds written as 0.333; then the shares are made exact.
  if (std::abs(total - 1.0) > 1e-3) {
    value.error(fmt::format("the fractions add up to {:g}; they must add up to 1", total));
    return std::nullopt;
  }
  for (SizeClassSpec& size : sizes) size.fraction /= total;
  return sizes;
}

void read_amount(const YamlSection& section, InsertionSpec& insertion) {
  const auto key = section.exactly_one_of({"count", "solid_fraction", "mass"});
  if (!key) return;
  if (*key == "count") {
    insertion.amount_kind = InsertAmount::count;
    const auto count = section.get("count")->whole_number();
    if (count && *count == 0) section.get("count")->error("must be at least 1");
    insertion.amount = static_cast<double>(count.value_or(0));
  } else if (*key == "solid_fraction") {
    insertion.amount_kind = InsertAmount::solid_fraction;
    insertion.amount = read_checked_quantity(section, "solid_fraction", Dimension::dimensionless,
                                             Presence::required, is_possible_solid_fraction,
                                             "be greater than 0 and at most 0.74 (the densest "
                                             "packing of spheres)")
                           .value_or(0.0);
  } else {
    insertion.amount_kind = InsertAmount::mass;
    insertion.amount = read_checked_quantity(section, "mass", Dimension::mass, Presence::required,
                                             is_positive, "be greater than 0")
                           .value_or(0.0);
  }
}

/// The narrowest width of a region: whole particles are placed inside it.
double narrowest_width_m(const RegionSpec& region) {
  switch (region.shape) {
    case RegionShape::box: {
      const Vec3 side = region.max_m - region.min_m;
      return std::min({side.x, side.y, side.z});
    }
    case RegionShape::cylinder:
      return std::min(2.0 * region.radius_m, region.length_m);
    case RegionShape::annulus:
      return std::min(region.radius_m - region.inner_radius_m, region.length_m);
  }
  return 0.0;
}

void read_random_insertion(const YamlSection& section, const ScenarioReferences& references,
                           InsertionSpec& insertion) {
  const YamlValue region_value = *section.get("region");
  const auto region = read_region(region_value, references);
  if (region) insertion.region = *region;
  const auto size_key = section.exactly_one_of({"radius", "diameter", "sizes"});
  if (size_key && *size_key == "sizes") {
    if (auto sizes = read_size_distribution(*section.get("sizes"))) insertion.sizes = *sizes;
  } else if (size_key) {
    if (const auto radius = read_radius(section, "radius", "diameter", Presence::required)) {
      insertion.sizes = {SizeClassSpec{*radius, 1.0}};
    }
  }
  if (region && !insertion.sizes.empty()) {
    double largest_radius_m = 0.0;
    for (const SizeClassSpec& size : insertion.sizes) {
      largest_radius_m = std::max(largest_radius_m, size.radius_m);
    }
    const double width_m = narrowest_width_m(*region);
    if (2.0 * largest_radius_m > width_m) {
      region_value.error(fmt::format(
          "particles of diameter {:g} m do not fit: the region is {:g} m across at its "
          "narrowest, and particles are placed wholly inside it",
          2.0 * largest_radius_m, width_m));
    }
  }
  if (const auto by = section.get("fractions_by")) {
    insertion.fractions_by_mass = by->choice({"number", "mass"}).value_or("number") == "mass";
  }
  read_amount(section, insertion);
  insertion.rate_per_s = read_checked_quantity(section, "rate", Dimension::rate,
                                               Presence::optional, is_positive,
                                               "be greater than 0")
                             .value_or(0.0);
  insertion.interval_s = read_checked_quantity(section, "interval", Dimension::time,
                                               Presence::optional, is_positive,
                                               "be greater than 0")
                             .value_or(0.0);
  insertion.initial_velocity_m_per_s =
      section.vector("velocity", Dimension::velocity).value_or(Vec3{});
  insertion.allow_partial = section.boolean("allow_partial").value_or(false);
}

void read_file_insertion(const YamlSection& section, const ScenarioReferences& references,
                         InsertionSpec& insertion) {
  if (const auto path = read_input_file(*section.get("file"), references)) insertion.from_file = *path;
  insertion.max_overlap_fraction =
      read_checked_quantity(section, "max_overlap", Dimension::dimensionless, Presence::optional,
                            [](double v) { return v >= 0.0 && v < 1.0; }, "lie in [0, 1)")
          .value_or(insertion.max_overlap_fraction);
}

/// A static-bed stage freezes the particles: nothing can be inserted during it.
void check_stage_is_coupled(const YamlSection& section, const ScenarioReferences& references,
                            const InsertionSpec& insertion) {
  if (references.static_stage_names.empty() || references.stage_names.empty()) return;
  const std::string& stage = insertion.stage.empty() ? references.stage_names.front() : insertion.stage;
  for (const std::string& frozen : references.static_stage_names) {
    if (frozen != stage) continue;
    const std::string message = fmt::format(
        "stage '{}' is a static-bed stage (particles do not move in it), so nothing can be inserted "
        "during it: insert in an earlier stage with `heat_stepping: coupled` (a short one is enough "
        "for particles from a file)",
        stage);
    if (const auto stage_value = section.get("stage")) {
      stage_value->error(message);
    } else {
      section.error(message + "; without 'stage' an insertion belongs to the first stage");
    }
  }
}

/// The lowest value of the linear field over the region (where the region is known):
/// min of g.(x - p) is reached at a corner of a box, and for a cylinder at an end, on
/// the rim, opposite the gradient's radial part.
double coldest_in_region_K(const InitialTemperatureSpec& field, const RegionSpec& region) {
  const Vec3& g = field.gradient_K_per_m;
  double lowest = field.value_K - dot(g, field.reference_point_m);
  if (region.shape == RegionShape::box) {
    for (int axis = 0; axis < 3; ++axis) {
      lowest += std::min(g[axis] * region.min_m[axis], g[axis] * region.max_m[axis]);
    }
    return lowest;
  }
  const Vec3 axis = normalized(region.axis);
  const double along = dot(g, axis);
  lowest += dot(g, region.base_m) + std::min(0.0, along * region.length_m);
  return lowest - region.radius_m * norm(g - axis * along);
}

/// `temperature: -196 degC`, or a linear field
/// `{value: -196 degC, gradient: [0, 0, 100 K/m], reference_point: [0, 0, 0]}`.
std::optional<InitialTemperatureSpec> read_initial_temperature(const YamlValue& value) {
  InitialTemperatureSpec field;
  if (!value.node().IsMap()) {
    const auto temperature = value.quantity(Dimension::temperature);
    if (!temperature) return std::nullopt;
    field.value_K = *temperature;
    return field;
  }
  const auto section = value.section();
  section->allow_only({"value", "gradient", "reference_point"});
  const auto temperature = section->required_quantity("value", Dimension::temperature);
  const auto gradient = section->vector("gradient", Dimension::temperature_gradient);
  const auto reference = section->vector("reference_point", Dimension::length);
  if (!temperature || (section->has("gradient") && !gradient) ||
      (section->has("reference_point") && !reference)) {
    return std::nullopt;
  }
  field.value_K = *temperature;
  field.gradient_K_per_m = gradient.value_or(Vec3{});
  field.reference_point_m = reference.value_or(Vec3{});
  return field;
}

void read_insertion_temperature(const YamlSection& section, const ScenarioReferences& references,
                                InsertionSpec& insertion) {
  const auto value = section.get("temperature");
  if (!value) {
    // A file may give every particle its temperature; the builder checks that.
    if (references.heat_enabled && section.has("region")) {
      section.error("heat is on: give the particles' initial 'temperature' (e.g. -196 degC)");
    }
    return;
  }
  insertion.temperature = read_initial_temperature(*value);
  // The region's `where` is set only once it has been read without problems.
  if (!insertion.temperature || !section.has("region") || insertion.region.where.key.empty()) return;
  if (norm2(insertion.temperature->gradient_K_per_m) == 0.0) return;
  const double coldest = coldest_in_region_K(*insertion.temperature, insertion.region);
  if (coldest < 0.0) {
    value->error(fmt::format("the temperature field falls below absolute zero in the region (to {:.4g} K)",
                             coldest));
  }
}

std::optional<InsertionSpec> read_insertion(const YamlValue& item,
                                            const ScenarioReferences& references) {
  const auto section = item.section();
  if (!section) return std::nullopt;
  InsertionSpec insertion;
  insertion.where = item.where();
  const auto source = section->exactly_one_of({"region", "file"});
  std::vector<std::string> allowed{"name", "region_tag", "material", "stage",
                                   "region", "file", "temperature"};
  if (source == "file") allowed.push_back("max_overlap");
  std::vector<std::pair<std::string, std::string>> misplaced;
  for (const std::string& key : kRegionInsertionKeys) {
    if (source == "file") {
      misplaced.emplace_back(key, "not used with 'file': the file gives the particles");
    } else {
      allowed.push_back(key);
    }
  }
  section->allow_only(allowed, misplaced);
  const auto name = read_item_name(*section);
  if (name) insertion.name = *name;

  if (const auto material = section->require("material")) {
    insertion.material =
        read_reference(*material, references.material_names, "material").value_or("");
  }
  insertion.region_tag = insertion.name;
  if (const auto tag = section->get("region_tag")) insertion.region_tag = tag->name().value_or("");
  if (const auto stage = section->get("stage")) {
    insertion.stage = read_reference(*stage, references.stage_names, "stage").value_or("");
  }
  check_stage_is_coupled(*section, references, insertion);
  if (source == "region") read_random_insertion(*section, references, insertion);
  if (source == "file") read_file_insertion(*section, references, insertion);
  read_insertion_temperature(*section, references, insertion);
  if (!name) return std::nullopt;
  return insertion;
}

}  // namespace

void read_insertions(const YamlSection& root, const ScenarioReferences& references,
                     ScenarioSpec& spec) {
  const auto value = root.get("insertions");
  if (!value) return;
  const auto items = value->items();
  if (!items) return;
  std::vector<NamedPlace> names;
  for (const YamlValue& item : *items) {
    if (auto insertion = read_insertion(item, references)) {
      names.push_back({insertion->name, insertion->where});
      spec.insertions.push_back(std::move(*insertion));
    }
  }
  report_duplicate_names(names, "insertion", value->context().diagnostics);
}

}  // namespace regodem
