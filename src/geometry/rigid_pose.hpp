#pragma once
// The placement of a moving rigid wall: world = R x_ref + t, where x_ref is the wall's
// point at the start of the run. Mesh walls keep their triangles and grid in the
// reference frame and map each particle centre into it (R^T (x - t)) instead of
// moving thousands of vertices every step.
#include "core/matrix3.hpp"
#include "core/vec3.hpp"

namespace regodem {

struct RigidPose {
  Matrix3 rotation = identity_matrix3();
  Vec3 translation_m;

  Vec3 to_world(const Vec3& reference_m) const { return multiply(rotation, reference_m) + translation_m; }
  Vec3 to_reference(const Vec3& world_m) const { return multiply_transposed(rotation, world_m - translation_m); }

  /// Turns the body by the rotation vector (angle x unit axis, right-handed) about the
  /// world point pivot_m, then shifts it by shift_m: x -> Rot (x - pivot) + pivot + shift.
  void turn_and_shift(const Vec3& rotation_vector_rad, const Vec3& pivot_m, const Vec3& shift_m);
};

}  // namespace regodem
