#include "geometry/rigid_pose.hpp"

#include <cmath>

#include "geometry/triangle_mesh.hpp"

namespace regodem {

void RigidPose::turn_and_shift(const Vec3& rotation_vector_rad, const Vec3& pivot_m, const Vec3& shift_m) {
  const double angle = norm(rotation_vector_rad);
  if (angle > 0.0) {
    // Rodrigues' formula for the increment, applied to R and to t about the pivot.
    const Matrix3 turn = MeshTransform::from_axis_angle(1.0, rotation_vector_rad, angle, Vec3{}).rotation;
    const Matrix3 turned = multiply(turn, rotation);
    // Re-orthonormalise (Gram-Schmidt on the columns): a million small turns would
    // otherwise let rounding shear and scale the body.
    Vec3 c0{turned[0][0], turned[1][0], turned[2][0]}, c1{turned[0][1], turned[1][1], turned[2][1]};
    c0 = normalized(c0);
    c1 = normalized(c1 - dot(c1, c0) * c0);
    const Vec3 c2 = cross(c0, c1);
    rotation = {{{c0.x, c1.x, c2.x}, {c0.y, c1.y, c2.y}, {c0.z, c1.z, c2.z}}};
    translation_m = multiply(turn, translation_m - pivot_m) + pivot_m;
  }
  translation_m += shift_m;
}

}  // namespace regodem
