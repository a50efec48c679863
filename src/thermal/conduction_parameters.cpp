#include "thermal/conduction_parameters.hpp"

#include <numbers>

namespace regodem {

ConductionParameterTable::ConductionParameterTable(const MaterialTable& materials, double time_scale_factor)
    : n_(materials.size()), table_(n_ * n_) {
  for (std::size_t a = 0; a < n_; ++a)
    for (std::size_t b = 0; b < n_; ++b) {
      const auto ia = static_cast<MaterialIndex>(a), ib = static_cast<MaterialIndex>(b);
      const Material& ma = materials[ia];
      const Material& mb = materials[ib];
      const PairProperties& pair = materials.pair(ia, ib);
      ConductionPairParameters& p = table_[a * n_ + b];
      if (ma.conductivity_W_per_mK.is_constant() && mb.conductivity_W_per_mK.is_constant()) {
        const double k_a = ma.conductivity_W_per_mK.at(0.0), k_b = mb.conductivity_W_per_mK.at(0.0);
        p.constant_pair_conductivity_W_per_mK = k_a + k_b > 0.0 ? harmonic_mean(k_a, k_b) : 0.0;
      }
      switch (pair.conduction) {
        case ConductionLaw::force: {
          p.radius_factor = 2.0 * time_scale_factor *
                            std::cbrt(effective_youngs_modulus_Pa(ma, mb) / effective_real_youngs_modulus_Pa(ma, mb));
          break;
        }
        case ConductionLaw::radius: p.radius_factor = 2.0 * time_scale_factor; break;
        case ConductionLaw::area:
          p.area_factor = time_scale_factor * pair.heat_transfer_coefficient_W_per_m2K * std::numbers::pi;
          break;
        case ConductionLaw::none: break;
      }
    }
}

}  // namespace regodem
