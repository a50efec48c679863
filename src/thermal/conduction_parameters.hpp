#pragma once
// Contact conduction (paper Eq. 1; DESIGN.md section 2, "Conduction"): the heat flow
// from j into i is Q_ij = G_ij (T_j - T_i). Every law in use reduces to
//   G = radius_factor * k_c * a + area_factor * a^2,   a = sqrt(R* delta_n),
// with per material pair factors (time-scale factor S folded in), so the contact pass
// evaluates any mixture of laws without branching:
//   force  (paper, EDEM): G = 2 k_c a_F, a_F = (3 F_n^e R* / (4 E*_real))^(1/3). For the
//          Hertz force F_n^e = 4/3 E* sqrt(R*) delta^(3/2) this is a (E*/E*_real)^(1/3):
//          radius_factor = 2 S (E*/E*_real)^(1/3).
//   radius (LAMMPS "heat radius"): G = 2 k_c a;      radius_factor = 2 S.
//   area   (LAMMPS "heat area"):   G = h pi a^2;     area_factor = S h pi.
#include <cmath>
#include <vector>

#include "core/material.hpp"

namespace regodem {

/// k_c of two particles: the harmonic mean (k itself for one material; 0 when both are 0).
inline double harmonic_mean(double k_i, double k_j) { return k_i + k_j > 0.0 ? 2.0 * k_i * k_j / (k_i + k_j) : 0.0; }

struct ConductionPairParameters {
  double radius_factor = 0.0;  // multiplies k_c a
  double area_factor = 0.0;    // W/(m^2 K): multiplies a^2
  // k_c of two particles of these materials when both conductivities are constant (the
  // common case: no per-contact division, no per-particle loads); < 0 when either is a
  // table, and k_c comes from the particles' current conductivities.
  double constant_pair_conductivity_W_per_mK = -1.0;

  [[gnu::always_inline]] double pair_conductivity(double k_i, double k_j) const {
    return constant_pair_conductivity_W_per_mK >= 0.0 ? constant_pair_conductivity_W_per_mK : harmonic_mean(k_i, k_j);
  }
};

/// Paper Eq. 1: the conductance of one contact (W/K), G = 2 k_c a with the pair's
/// factors (above); a the force law's contact radius. Every conducting contact, bond
/// and the frozen network of a static bed take their G from here.
[[gnu::always_inline]] inline double contact_conductance_W_per_K(const ConductionPairParameters& p,
                                                                 double conductivity_W_per_mK,
                                                                 double contact_radius_m) {
  return contact_radius_m * (p.radius_factor * conductivity_W_per_mK + p.area_factor * contact_radius_m);
}

/// The radius law's factors, G = 2 S k_c a, for a contact whose radius is geometric
/// (a bond's R_b), not the Hertz one the force law gives.
inline ConductionPairParameters geometric_radius_conduction(double time_scale_factor) {
  ConductionPairParameters p;
  p.radius_factor = 2.0 * time_scale_factor;
  return p;
}

/// Square table over material indices, built from the pair properties and the time-scale factor.
class ConductionParameterTable {
 public:
  ConductionParameterTable() = default;
  ConductionParameterTable(const MaterialTable& materials, double time_scale_factor);
  const ConductionPairParameters& operator()(MaterialIndex a, MaterialIndex b) const { return table_[a * n_ + b]; }

 private:
  std::size_t n_ = 0;
  std::vector<ConductionPairParameters> table_;
};

}  // namespace regodem
