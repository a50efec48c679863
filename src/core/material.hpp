#pragma once
// Materials and the properties of a pair of materials in contact. Walls name materials
// too (their elastic constants and, later, conductivity), so one table serves both.
#include <string>
#include <vector>

#include "core/particle_store.hpp"
#include "core/temperature_curve.hpp"

namespace regodem {

struct Material {
  std::string name;
  double density_kg_per_m3 = 0.0;
  double shear_modulus_Pa = 0.0;
  double poisson_ratio = 0.0;
  // Thermal properties (DESIGN.md section 2, "Conduction"); constants or tables over T.
  TemperatureCurve conductivity_W_per_mK{0.0};
  TemperatureCurve specific_heat_J_per_kgK{0.0};
  // The modulus of the real material when shear_modulus_Pa is reduced to allow a larger
  // time step; 0 = the same. Conduction's contact radius then uses E*_real.
  double real_shear_modulus_Pa = 0.0;

  /// E = 2G(1+nu).
  double youngs_modulus_Pa() const { return 2.0 * shear_modulus_Pa * (1.0 + poisson_ratio); }
  double real_youngs_modulus_Pa() const {
    return 2.0 * (real_shear_modulus_Pa > 0.0 ? real_shear_modulus_Pa : shear_modulus_Pa) * (1.0 + poisson_ratio);
  }
};

/// 1/E* = (1 - nu_a^2)/E_a + (1 - nu_b^2)/E_b: the mechanics' E* (simulated moduli). A
/// wall has the same formula with its material's constants (DESIGN.md section 2).
double effective_youngs_modulus_Pa(const Material& a, const Material& b);
/// The same with each material's real modulus (its simulated one where it gives none):
/// what the force law's contact radius uses (paper Eq. 1).
double effective_real_youngs_modulus_Pa(const Material& a, const Material& b);

/// How a contact conducts heat (G = conductance, Q_ij = G (T_j - T_i)), per material pair:
///  force:  G = 2 k_c a, a = (3 F_n^e R* / (4 E*_real))^(1/3)  (the paper's Eq. 1, EDEM)
///  radius: G = 2 k_c a, a = sqrt(R* delta_n)                   (LAMMPS "heat radius")
///  area:   G = h pi a^2, a = sqrt(R* delta_n)                  (LAMMPS "heat area")
///  none:   no conduction.
enum class ConductionLaw : std::uint8_t { force, radius, area, none };

/// Which spin rolling friction resists, per material pair:
///  relative_spin: the relative spin less its normal part, with R* (Ai et al. 2011 type A;
///                 LIGGGHTS cdt); j feels the opposite torque.
///  own_spin:      each body its own spin, with its own distance to the contact point
///                 (EDEM's standard rolling friction; the paper does not name its
///                 software, and we assume EDEM's forms: docs/physics.md).
enum class RollingModel : std::uint8_t { relative_spin, own_spin };

/// What the scenario says about two materials in contact (DESIGN.md section 2).
struct PairProperties {
  double restitution = 0.5;
  double sliding_friction = 0.5;
  double rolling_friction = 0.0;
  RollingModel rolling_model = RollingModel::relative_spin;
  bool clamp_attractive_normal_force = false;  // EDEM default: no clamping
  ConductionLaw conduction = ConductionLaw::force;
  double heat_transfer_coefficient_W_per_m2K = 0.0;  // the area law's h
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
