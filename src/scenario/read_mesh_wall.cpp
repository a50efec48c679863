// A `type: mesh` wall: triangles from an STL (binary or ASCII) or OBJ file, scaled and
// placed. The file is read here, so that a bad file is reported at its key with the
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
  const auto file_value = section.require("file");
  std::optional<std::string> path;
  if (file_value) path = read_input_file(*file_value, references);
  wall.placement.scale = read_checked_quantity(section, "scale", Dimension::dimensionless, Presence::optional,
                                               is_positive, "be greater than 0 (0.001 for a file in mm)")
                             .value_or(1.0);
  if (const auto placement = section.get("placement")) read_placement(*placement, wall.placement);
  wall.point_m = wall.placement.translation_m;
  wall.mesh_grid_cell_m = read_checked_quantity(section, "grid_cell", Dimension::length, Presence::optional,
                                                is_positive, "be greater than 0")
                              .value_or(0.0);
  if (!path) return;
  wall.mesh_file = *path;
  try {
    TriangleMesh mesh = read_mesh_file(*path);
    if (mesh.triangle_count() == 0) {
      file_value->error(fmt::format("'{}' has no triangles (after dropping {} degenerate ones)", *path,
                                    mesh.dropped_degenerate_triangles));
      return;
    }
    mesh.apply(mesh_transform(wall.placement));
    const Aabb box = mesh.bounding_box();
    check_inside_domain(section.value(), Bounds{box.lo_m, box.hi_m}, references, "the mesh, as placed,");
    wall.mesh = std::make_shared<const TriangleMesh>(std::move(mesh));
  } catch (const InputError& e) {
    file_value->error(e.what());
  }
}

}  // namespace regodem
