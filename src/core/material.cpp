#include "core/material.hpp"

namespace regodem {
namespace {

double mixed_modulus_Pa(const Material& a, double youngs_a_Pa, const Material& b, double youngs_b_Pa) {
  return 1.0 / ((1.0 - a.poisson_ratio * a.poisson_ratio) / youngs_a_Pa +
                (1.0 - b.poisson_ratio * b.poisson_ratio) / youngs_b_Pa);
}

}  // namespace

double effective_youngs_modulus_Pa(const Material& a, const Material& b) {
  return mixed_modulus_Pa(a, a.youngs_modulus_Pa(), b, b.youngs_modulus_Pa());
}

double effective_real_youngs_modulus_Pa(const Material& a, const Material& b) {
  return mixed_modulus_Pa(a, a.real_youngs_modulus_Pa(), b, b.real_youngs_modulus_Pa());
}

MaterialIndex MaterialTable::add(const Material& m) {
  const std::size_t old_n = materials_.size();
  const std::size_t n = old_n + 1;
  std::vector<PairProperties> grown(n * n);
  for (std::size_t a = 0; a < old_n; ++a)
    for (std::size_t b = 0; b < old_n; ++b) grown[a * n + b] = pairs_[a * old_n + b];
  pairs_.swap(grown);
  materials_.push_back(m);
  return static_cast<MaterialIndex>(old_n);
}

int MaterialTable::find(const std::string& name) const {
  for (std::size_t i = 0; i < materials_.size(); ++i)
    if (materials_[i].name == name) return static_cast<int>(i);
  return -1;
}

void MaterialTable::set_pair(MaterialIndex a, MaterialIndex b, const PairProperties& p) {
  const std::size_t n = materials_.size();
  pairs_[a * n + b] = p;
  pairs_[b * n + a] = p;
}

}  // namespace regodem
