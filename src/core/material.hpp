#pragma once
// Materials and the properties of a pair of materials in contact. Walls name materials
// too (their elastic constants and, later, conductivity), so one table serves both.
#include <string>
#include <vector>

#include "core/particle_store.hpp"

namespace regodem {

struct Material {
  std::string name;
  double density_kg_per_m3 = 0.0;
  double shear_modulus_Pa = 0.0;
  double poisson_ratio = 0.0;

  /// E = 2G(1+nu).
  double youngs_modulus_Pa() const { return 2.0 * shear_modulus_Pa * (1.0 + poisson_ratio); }
};

/// What the scenario says about two materials in contact (DESIGN.md section 2).
struct PairProperties {
  double restitution = 0.5;
  double sliding_friction = 0.5;
  double rolling_friction = 0.0;
  bool clamp_attractive_normal_force = false;  // EDEM default: no clamping
};

/// Materials plus a symmetric table of pair properties, indexed by material index.
class MaterialTable {
 public:
  MaterialIndex add(const Material& m);
  std::size_t size() const { return materials_.size(); }
  const Material& operator[](MaterialIndex i) const { return materials_[i]; }
  /// Index of the named material, or -1.
  int find(const std::string& name) const;

  void set_pair(MaterialIndex a, MaterialIndex b, const PairProperties& p);
  const PairProperties& pair(MaterialIndex a, MaterialIndex b) const {
    return pairs_[a * materials_.size() + b];
  }

 private:
  std::vector<Material> materials_;
  std::vector<PairProperties> pairs_;  // size() x size(), symmetric
};

}  // namespace regodem
