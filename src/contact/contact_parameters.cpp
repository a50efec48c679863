#include "contact/contact_parameters.hpp"

#include <cmath>
#include <numbers>

namespace regodem {

double restitution_damping_factor(double restitution) {
  const double log_e = std::log(restitution);
  const double beta = log_e / std::sqrt(log_e * log_e + std::numbers::pi * std::numbers::pi);
  return 2.0 * std::sqrt(5.0 / 6.0) * std::abs(beta);
}

ContactParameterTable::ContactParameterTable(const MaterialTable& materials)
    : n_(materials.size()), table_(n_ * n_) {
  for (std::size_t a = 0; a < n_; ++a) {
    for (std::size_t b = 0; b < n_; ++b) {
      const Material& ma = materials[static_cast<MaterialIndex>(a)];
      const Material& mb = materials[static_cast<MaterialIndex>(b)];
      const PairProperties& pair =
          materials.pair(static_cast<MaterialIndex>(a), static_cast<MaterialIndex>(b));
      ContactPairParameters& p = table_[a * n_ + b];
      p.effective_youngs_modulus_Pa = effective_youngs_modulus_Pa(ma, mb);
      p.effective_shear_modulus_Pa = 1.0 / ((2.0 - ma.poisson_ratio) / ma.shear_modulus_Pa +
                                            (2.0 - mb.poisson_ratio) / mb.shear_modulus_Pa);
      p.damping_factor = restitution_damping_factor(pair.restitution);
      p.sliding_friction = pair.sliding_friction;
      p.rolling_friction = pair.rolling_friction;
      p.rolling_model = pair.rolling_model;
      p.clamp_attractive_normal_force = pair.clamp_attractive_normal_force;
      any_own_spin_ = any_own_spin_ || p.rolling_model == RollingModel::own_spin;
    }
  }
}

}  // namespace regodem
