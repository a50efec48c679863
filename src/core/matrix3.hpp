#pragma once
// A row-major 3x3 matrix (m[row][column]) and the products rotations need.
#include <array>

#include "core/vec3.hpp"

namespace regodem {

using Matrix3 = std::array<std::array<double, 3>, 3>;

constexpr Matrix3 identity_matrix3() { return {{{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}}}; }

/// m v
constexpr Vec3 multiply(const Matrix3& m, const Vec3& v) {
  return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
          m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
}

/// m^T v (the inverse of a rotation)
constexpr Vec3 multiply_transposed(const Matrix3& m, const Vec3& v) {
  return {m[0][0] * v.x + m[1][0] * v.y + m[2][0] * v.z, m[0][1] * v.x + m[1][1] * v.y + m[2][1] * v.z,
          m[0][2] * v.x + m[1][2] * v.y + m[2][2] * v.z};
}

/// a b
constexpr Matrix3 multiply(const Matrix3& a, const Matrix3& b) {
  Matrix3 c{};
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j) c[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
  return c;
}

}  // namespace regodem
