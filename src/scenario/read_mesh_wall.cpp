// `type: mesh` walls, triangles from an STL (binary or ASCII) or OBJ file, scaled and
// placed, and `type: auger` walls, generated from a drill's dimensions. The mesh is
// made here, so that a bad file or a bad dimension is reported at its key with the
// line, and the placed mesh's extent is checked against the domain.
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "core/error.hpp"
#include "io/obj_reader.hpp"
#include "io/stl_reader.hpp"
#include "scenario/scenario_fields.hpp"
#include "scenario/scenario_sections.hpp"

namespace regodem {
namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

void read_placement(const YamlValue& value, MeshPlacementSpec& placement) {
  const auto section = value.section();
  if (!section) return;
  section->allow_only({"translation", "rotation"});
  placement.translation_m = section->vector("translation", Dimension::length).value_or(Vec3{});
  if (const auto rotation = section->get("rotation")) {
    if (const auto turn = rotation->section()) {
      turn->allow_only({"axis", "angle"});
      if (const auto axis = read_direction(*turn, "axis", Presence::required)) placement.rotation_axis = *axis;
      placement.rotation_angle_rad = turn->required_quantity("angle", Dimension::angle).value_or(0.0);
    }
  }
}

/// The auger's dimensions (geometry/auger_generator.hpp); its own checks (blades that
/// would touch, a tip longer than the drill) are reported at the wall.
std::optional<AugerSpec> read_auger(const YamlSection& section) {
  AugerSpec auger;
  const auto length = [&](const char* key, double& out) {
    const auto v = read_checked_quantity(section, key, Dimension::length, Presence::required, is_positive,
                                         "be greater than 0");
    if (v) out = *v;
    return v.has_value();
  };
  bool complete = length("outer_diameter", auger.outer_diameter_m);
  complete = length("core_diameter", auger.core_diameter_m) && complete;
  complete = length("pitch", auger.pitch_m) && complete;
  complete = length("flute_thickness", auger.flute_thickness_m) && complete;
  complete = length("length", auger.length_m) && complete;
  if (const auto flutes = section.get("flutes")) {
    const auto n = flutes->whole_number();
    if (n && (*n < 1 || *n > 16)) flutes->error(fmt::format("must be 1 to 16, got {}", *n));
    if (n && *n >= 1 && *n <= 16) auger.flutes = static_cast<int>(*n);
    complete = complete && n && *n >= 1 && *n <= 16;
  }
  if (const auto segments = section.get("segments_per_turn")) {
    const auto n = segments->whole_number();
    if (n && (*n < 16 || *n > 4096)) segments->error(fmt::format("must be 16 to 4096, got {}", *n));
    if (n && *n >= 16 && *n <= 4096) auger.segments_per_turn = static_cast<int>(*n);
    complete = complete && n && *n >= 16 && *n <= 4096;
  }
  if (const auto hand = section.get("hand")) {
    const auto choice = hand->choice({"right", "left"});
    if (choice) auger.hand = *choice == "right" ? FluteHand::right : FluteHand::left;
    complete = complete && choice;
  }
  if (const auto tip_value = section.get("tip")) {
    if (const auto tip = tip_value->section()) {
      tip->allow_only({"shape", "angle"});
      const auto shape = tip->require("shape");
      const auto choice = shape ? shape->choice({"flat", "cone"}) : std::nullopt;
      if (choice) auger.tip = *choice == "cone" ? AugerTip::cone : AugerTip::flat;
      if (tip->has("angle")) {
        if (auger.tip != AugerTip::cone) tip->get("angle")->error("only a cone tip has an angle");
        const auto angle = tip->quantity("angle", Dimension::angle);
        if (angle) auger.tip_angle_rad = *angle;
      }
      complete = complete && choice;
    }
  }
  if (!complete) return std::nullopt;
  try {
    auger.validate();
  } catch (const InputError& e) {
    section.error(e.what());
    return std::nullopt;
  }
  return auger;
}

}  // namespace

MeshTransform mesh_transform(const MeshPlacementSpec& placement) {
  return MeshTransform::from_axis_angle(placement.scale, placement.rotation_axis, placement.rotation_angle_rad,
                                        placement.translation_m);
}

TriangleMesh read_mesh_file(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".stl") return read_stl(path);
  if (ext == ".obj") return read_obj(path);
  throw InputError(fmt::format("'{}': a mesh file must end in .stl (binary or ASCII) or .obj", path));
}

void read_mesh_shape(const YamlSection& section, const ScenarioReferences& references, WallSpec& wall) {
  const bool generated = wall.shape == WallShape::auger;
  std::optional<YamlValue> file_value;
  std::optional<std::string> path;
  if (!generated) {
    file_value = section.require("file");
    if (file_value) path = read_input_file(*file_value, references);
    wall.placement.scale = read_checked_quantity(section, "scale", Dimension::dimensionless, Presence::optional,
                                                 is_positive, "be greater than 0 (0.001 for a file in mm)")
                               .value_or(1.0);
  } else {
    wall.auger = read_auger(section);
  }
  if (const auto placement = section.get("placement")) read_placement(*placement, wall.placement);
  wall.point_m = wall.placement.translation_m;
  wall.mesh_grid_cell_m = read_checked_quantity(section, "grid_cell", Dimension::length, Presence::optional,
                                                is_positive, "be greater than 0")
                              .value_or(0.0);
  const YamlValue& at = file_value ? *file_value : section.value();
  if (generated ? !wall.auger : !path) return;
  if (path) wall.mesh_file = *path;
  try {
    const MeshTransform placed = mesh_transform(wall.placement);
    wall.normal = placed.rotate({0.0, 0.0, 1.0});  // an auger's axis; a mesh's default spin axis
    TriangleMesh mesh = generated ? make_auger(*wall.auger) : read_mesh_file(*path);
    if (mesh.triangle_count() == 0) {
      at.error(fmt::format("'{}' has no triangles (after dropping {} degenerate ones)", *path,
                                    mesh.dropped_degenerate_triangles));
      return;
    }
    mesh.apply(placed);
    const Aabb box = mesh.bounding_box();
    check_inside_domain(section.value(), Bounds{box.lo_m, box.hi_m}, references, "the mesh, as placed,");
    wall.mesh = std::make_shared<const TriangleMesh>(std::move(mesh));
  } catch (const InputError& e) {
    at.error(e.what());
  }
}

}  // namespace regodem
