#pragma once
// The elastic part of one parallel-bond step (update_bond, parallel_bond.hpp), written
// once over a lane type: `double` for one bond, or `BondLanes` (a vector of doubles,
// GCC's vector extension) for several bonds side by side in the bond pass. Each lane
// does the operations of one bond alone, in the same order, so the batched pass gives
// the bits the one-bond law gives (ParallelBondBatch.* tests) and the answer does not
// depend on which bonds share a vector.
//
// What the lanes cannot do alike is the spin's rotation when its angle is not small:
// the one-bond law then takes sin and cos (Rotation in parallel_bond.cpp), so a lane
// whose angle^2 reaches kSeriesLimit is flagged and the pass runs that bond alone.
#include <cmath>
#include <cstdint>

#if defined(__AVX__) || defined(__SSE2__)
#include <immintrin.h>
#endif

namespace regodem::bond_kernel {

/// Lanes of the batched bond pass: one vector register of doubles, four with AVX, else
/// two (SSE2, or any target's 128-bit vectors). A wider vector than the target has would
/// change the calling convention of the inline functions below (GCC's -Wpsabi).
#if defined(__AVX__)
inline constexpr int kLanes = 4;
#else
inline constexpr int kLanes = 2;
#endif
using BondLanes = double __attribute__((vector_size(kLanes * sizeof(double))));
using LaneMask = decltype(BondLanes{} < BondLanes{});

/// Below this angle^2 the spin's rotation is the series (error a^8/9! < 1e-21), else sin/cos.
inline constexpr double kSeriesLimit = 1e-4;

inline double lane_sqrt(double a) { return std::sqrt(a); }
inline BondLanes lane_sqrt(BondLanes a) {
#if defined(__AVX__)
  return _mm256_sqrt_pd(a);
#elif defined(__SSE2__)
  return _mm_sqrt_pd(a);
#else
  BondLanes r;
  for (int l = 0; l < kLanes; ++l) r[l] = std::sqrt(a[l]);
  return r;
#endif
}
inline double lane_select(bool m, double a, double b) { return m ? a : b; }
inline BondLanes lane_select(LaneMask m, BondLanes a, BondLanes b) { return m ? a : b; }

/// A 3-vector of lanes, with Vec3's arithmetic in Vec3's order (core/vec3.hpp).
template <class T>
struct V3 {
  T x, y, z;
};
template <class T>
inline V3<T> operator+(const V3<T>& a, const V3<T>& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
template <class T>
inline V3<T> operator-(const V3<T>& a, const V3<T>& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
template <class T>
inline V3<T> operator-(const V3<T>& a) { return {-a.x, -a.y, -a.z}; }
template <class T>
inline V3<T> operator*(const V3<T>& a, T s) { return {a.x * s, a.y * s, a.z * s}; }
template <class T>
inline T dot(const V3<T>& a, const V3<T>& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
template <class T>
inline V3<T> cross(const V3<T>& a, const V3<T>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class T>
inline V3<T> select(decltype(T{} < T{}) m, const V3<T>& a, const V3<T>& b) {
  return {lane_select(m, a.x, b.x), lane_select(m, a.y, b.y), lane_select(m, a.z, b.z)};
}

/// One bond's inputs: the pair's state over the step and the bond's stored state.
template <class T>
struct BondStepInput {
  // x_j - x_i and v_j - v_i (the law needs only these of the positions and velocities;
  // the pass takes the differences as it reads the particles: two vectors, not four)
  V3<T> separation, centre_velocity;
  V3<T> spin_i, spin_j;
  T radius_i, radius_j, rest_length;
  V3<T> normal;  // of the last step
  T normal_force, twist_moment;
  V3<T> shear_force, bend_moment;
  // k_n A, k_s A, k_s J, k_n I (the bond's stiffnesses)
  T normal_stiffness, shear_stiffness, twist_stiffness, bend_stiffness;
};

/// Its new state and the rates of the step (the damping needs them).
template <class T>
struct BondStepOutput {
  V3<T> normal;
  T normal_force, twist_moment;
  V3<T> shear_force, bend_moment;
  T arm_i, arm_j;
  T normal_speed, twist_rate;
  V3<T> shear_velocity, bend_rate;
};

/// The spin's rotation by phi in Rodrigues form (see Rotation in parallel_bond.cpp):
/// v' = v c + (phi x v) s1 + phi (phi.v) c1, here with the series coefficients.
template <class T>
struct SeriesRotation {
  V3<T> phi;
  T c, s1, c1;
  V3<T> operator()(const V3<T>& v) const { return v * c + cross(phi, v) * s1 + phi * (dot(phi, v) * c1); }
};
template <class T>
[[gnu::always_inline]] inline SeriesRotation<T> series_rotation(const V3<T>& phi) {
  const T a2 = dot(phi, phi);
  SeriesRotation<T> r{phi, T{}, T{}, T{}};
  r.s1 = 1.0 - a2 / 6.0 * (1.0 - a2 / 20.0 * (1.0 - a2 / 42.0));
  r.c1 = 0.5 * (1.0 - a2 / 12.0 * (1.0 - a2 / 30.0 * (1.0 - a2 / 56.0)));
  r.c = 1.0 - a2 * r.c1;
  return r;
}

/// The smallest rotation taking unit a onto unit b (MinimalRotation in parallel_bond.cpp):
/// v' = v c + (k x v) + k (k.v)/(1 + c), k = a x b, c = a.b; a half turn gives -v.
template <class T>
struct SmallestRotation {
  V3<T> k;
  T c, c1;
  decltype(T{} < T{}) flip;
  V3<T> operator()(const V3<T>& v) const { return select(flip, -v, v * c + cross(k, v) + k * (dot(k, v) * c1)); }
};
template <class T>
inline SmallestRotation<T> smallest_rotation(const V3<T>& a, const V3<T>& b) {
  SmallestRotation<T> r{cross(a, b), dot(a, b), T{}, {}};
  r.flip = r.c <= T{} + (-1.0 + 1e-12);
  // A flipped lane's 1/(1 + c) may be huge or infinite: it is not used.
  r.c1 = lane_select(r.flip, T{} + 0.5, 1.0 / (1.0 + r.c));
  return r;
}

/// The step of a bond (update_bond's steps 1-3; see parallel_bond.hpp for the law),
/// with `spin` the rotation of the pair's mean spin over the step. Always inlined, as are
/// series_rotation and bond_forces: called out of line, the lanes passed through the stack,
/// where a wide load of two narrower stores stalled the batch (docs/benchmarks.md).
template <class T, class Spin>
[[gnu::always_inline]] inline BondStepOutput<T> bond_step(const BondStepInput<T>& in, const Spin& spin, double dt_s) {
  BondStepOutput<T> out;
  const V3<T> d = in.separation;
  const T length = lane_sqrt(dot(d, d)), inv_length = 1.0 / length;
  const V3<T> n = d * inv_length;

  // 1. Turn the stored loads with the pair: the mean spin, then the smallest rotation of
  // the spun old normal onto the new one.
  const SmallestRotation<T> align = smallest_rotation(spin(in.normal), n);
  V3<T> shear = align(spin(in.shear_force));
  V3<T> bend = align(spin(in.bend_moment));
  shear = shear - n * dot(shear, n);
  bend = bend - n * dot(bend, n);
  out.normal = n;

  // 2. The relative motion at the bond, with mid-step lever arms.
  out.arm_i = 0.5 * (length + in.radius_i - in.radius_j);
  out.arm_j = length - out.arm_i;
  const V3<T> wi = in.spin_i, wj = in.spin_j;
  const V3<T> centre_velocity = in.centre_velocity;
  const V3<T> d_mid = d - centre_velocity * (T{} + 0.5 * dt_s);
  const T mid_length = lane_sqrt(dot(d_mid, d_mid));
  const V3<T> n_mid = select(mid_length > T{}, V3<T>{d_mid.x / mid_length, d_mid.y / mid_length, d_mid.z / mid_length},
                             V3<T>{T{}, T{}, T{}});
  const V3<T> relative_velocity =
      centre_velocity - cross(wj, d_mid * (out.arm_j * inv_length)) - cross(wi, d_mid * (out.arm_i * inv_length));
  out.normal_speed = dot(relative_velocity, n_mid);
  out.shear_velocity = relative_velocity - n_mid * out.normal_speed;
  out.shear_velocity = out.shear_velocity - n * dot(out.shear_velocity, n);
  const V3<T> relative_spin = wj - wi;
  out.twist_rate = dot(relative_spin, n_mid);
  out.bend_rate = relative_spin - n_mid * out.twist_rate;
  out.bend_rate = out.bend_rate - n * dot(out.bend_rate, n);

  // 3. Increments (Potyondy & Cundall 2004 Eq. 10, 11), the normal force from the stretch.
  out.normal_force = in.normal_stiffness * (length - in.rest_length);
  out.shear_force = shear + out.shear_velocity * (in.shear_stiffness * dt_s);
  out.twist_moment = in.twist_moment + in.twist_stiffness * out.twist_rate * dt_s;
  out.bend_moment = bend + out.bend_rate * (in.bend_stiffness * dt_s);
  return out;
}

/// Forces and torques of the loads (update_bond's step 4): on i, F_n n + F_s and
/// M_t n + M_b + arm_i n x F_s; on j the opposite force and -M_t n - M_b + arm_j n x F_s.
template <class T>
struct BondForces {
  V3<T> force_on_i, torque_on_i, torque_on_j;
};
template <class T>
[[gnu::always_inline]] inline BondForces<T> bond_forces(const V3<T>& n, T normal_force, const V3<T>& shear_force,
                                                        T twist, const V3<T>& bend_moment, T arm_i, T arm_j) {
  BondForces<T> f;
  f.force_on_i = n * normal_force + shear_force;
  const V3<T> lever = cross(n, shear_force);
  f.torque_on_i = n * twist + bend_moment + lever * arm_i;
  f.torque_on_j = -(n * twist + bend_moment) + lever * arm_j;
  return f;
}

}  // namespace regodem::bond_kernel
