#pragma once
// Per material pair constants of the Hertz-Mindlin law, computed once from the
// material table (DESIGN.md section 2) so the force loop does no mixing.
#include <vector>

#include "core/material.hpp"

namespace regodem {

struct ContactPairParameters {
  double effective_youngs_modulus_Pa = 0.0;  // 1/E* = (1-nu_i^2)/E_i + (1-nu_j^2)/E_j
  double effective_shear_modulus_Pa = 0.0;   // 1/G* = (2-nu_i)/G_i + (2-nu_j)/G_j
  double damping_factor = 0.0;               // 2 sqrt(5/6) |beta|, beta = ln e / sqrt(ln^2 e + pi^2)
  double sliding_friction = 0.0;
  double rolling_friction = 0.0;
  RollingModel rolling_model = RollingModel::relative_spin;
  bool clamp_attractive_normal_force = false;
};

/// 2 sqrt(5/6) |beta| for a restitution coefficient e in (0, 1].
double restitution_damping_factor(double restitution);

/// Square table over material indices (particles and walls share the materials).
class ContactParameterTable {
 public:
  ContactParameterTable() = default;
  explicit ContactParameterTable(const MaterialTable& materials);
  const ContactPairParameters& operator()(MaterialIndex a, MaterialIndex b) const {
    return table_[a * n_ + b];
  }
  /// Whether any pair rolls by EDEM's own-spin model (its resistance is summed per particle).
  bool any_own_spin() const { return any_own_spin_; }

 private:
  std::size_t n_ = 0;
  bool any_own_spin_ = false;
  std::vector<ContactPairParameters> table_;
};

}  // namespace regodem
