#include "scenario/conduction_pairs.hpp"

#include <fmt/format.h>

#include "core/error.hpp"

namespace regodem {
namespace {

const char* law_name(ConductionLaw law) {
  switch (law) {
    case ConductionLaw::force: return "force";
    case ConductionLaw::radius: return "radius";
    case ConductionLaw::area: return "area";
    case ConductionLaw::none: return "none";
  }
  return "?";
}

std::string conductivity_text(const Material& m) {
  if (m.conductivity_W_per_mK.is_constant()) return fmt::format("{:.4g} W/(m K)", m.conductivity_W_per_mK.at(0.0));
  return "its table";
}

/// The contact radius part of a line: what E* the law's radius comes from.
std::string radius_text(const PairProperties& pair, const Material& a, const Material& b) {
  const double mechanics = effective_youngs_modulus_Pa(a, b);
  switch (pair.conduction) {
    case ConductionLaw::force: {
      const double real = effective_real_youngs_modulus_Pa(a, b);
      return real == mechanics ? fmt::format("force law, contact radius from E* {:.4g} Pa (the mechanics' too)", real)
                               : fmt::format("force law, contact radius from E* {:.4g} Pa (real; the mechanics' "
                                             "{:.4g} Pa)",
                                             real, mechanics);
    }
    case ConductionLaw::radius:
    case ConductionLaw::area:
      return fmt::format("{} law, contact radius sqrt(R* delta) from the mechanics' overlap (E* {:.4g} Pa)",
                         law_name(pair.conduction), mechanics);
    case ConductionLaw::none: break;
  }
  return "no conduction";
}

/// The guard: a force-law pair of a scenario with real moduli must state both of its own.
void check_real_modulus(const ScenarioSpec& spec, const MaterialTable& materials, MaterialIndex a, MaterialIndex b,
                        const std::string& where_they_meet) {
  if (materials.pair(a, b).conduction != ConductionLaw::force) return;
  const MaterialSpec* real = nullptr;
  for (const MaterialSpec& m : spec.materials)
    if (m.real_shear_modulus_Pa > 0.0) {
      real = &m;
      break;
    }
  if (real == nullptr) return;
  for (const MaterialIndex m : {a, b}) {
    const MaterialSpec& silent = spec.materials[m];
    if (silent.real_modulus_stated) continue;
    const MaterialSpec& other = spec.materials[m == a ? b : a];
    const MaterialSpec& named = other.real_modulus_stated && other.real_shear_modulus_Pa > 0.0 ? other : *real;
    throw InputError(fmt::format(
        "{}: material '{}' gives no real modulus, but '{}' does ({}:{}), and heat conducts {}: the force law's "
        "contact radius (paper Eq. 1) would mix {}'s simulated shear modulus {:.4g} Pa with real ones. Give its "
        "real value (e.g. `real_shear_modulus: 79 GPa` for steel), or `real_shear_modulus: same` if {:.4g} Pa is "
        "its real modulus",
        silent.where.describe(), silent.name, named.name, named.where.file, named.where.line, where_they_meet,
        silent.name, silent.shear_modulus_Pa, silent.shear_modulus_Pa));
  }
}

}  // namespace

std::vector<std::string> conduction_pair_lines(const ScenarioSpec& spec, const MaterialTable& materials,
                                               const std::vector<char>& particle_material,
                                               const std::vector<ConductingWall>& walls) {
  std::vector<std::string> lines;
  const std::size_t n = materials.size();
  for (std::size_t a = 0; a < n; ++a) {
    if (!particle_material[a]) continue;
    const auto ia = static_cast<MaterialIndex>(a);
    const Material& ma = materials[ia];
    for (std::size_t b = a; b < n; ++b) {
      if (!particle_material[b]) continue;
      const auto ib = static_cast<MaterialIndex>(b);
      const PairProperties& pair = materials.pair(ia, ib);
      if (pair.conduction == ConductionLaw::none) continue;
      const Material& mb = materials[ib];
      check_real_modulus(spec, materials, ia, ib, fmt::format("between particles of '{}' and '{}'", ma.name, mb.name));
      const std::string k = a == b ? conductivity_text(ma)
                                   : fmt::format("the harmonic mean of {} and {}", conductivity_text(ma),
                                                 conductivity_text(mb));
      lines.push_back(fmt::format("conduction '{}'-'{}': {}, k_c {}", ma.name, mb.name, radius_text(pair, ma, mb),
                                  pair.conduction == ConductionLaw::area ? "unused (h pi a^2)" : k));
    }
    for (const ConductingWall& w : walls) {
      const PairProperties& pair = materials.pair(ia, w.material);
      if (pair.conduction == ConductionLaw::none) continue;
      const Material& mw = materials[w.material];
      check_real_modulus(spec, materials, ia, w.material, fmt::format("between '{}' and wall '{}'", ma.name, w.name));
      std::string k;
      if (pair.conduction == ConductionLaw::area) {
        k = "unused (h pi a^2)";
      } else if (!w.conductivity_W_per_mK) {
        k = fmt::format("{} (the particle's own, Eq. 1's k_s)", conductivity_text(ma));
      } else if (w.harmonic_mean) {
        const double kw = *w.conductivity_W_per_mK;
        k = ma.conductivity_W_per_mK.is_constant()
                ? fmt::format("{:.4g} W/(m K) (harmonic mean of the wall's {:.4g} and the particle's {}, EDEM)",
                              2.0 * kw * ma.conductivity_W_per_mK.at(0.0) / (kw + ma.conductivity_W_per_mK.at(0.0)),
                              kw, conductivity_text(ma))
                : fmt::format("the harmonic mean of the wall's {:.4g} W/(m K) and the particle's", kw);
      } else {
        k = fmt::format("{:.4g} W/(m K) (the wall's own)", *w.conductivity_W_per_mK);
      }
      lines.push_back(fmt::format("conduction '{}' at wall '{}' ('{}'): {}, k_c {}", ma.name, w.name, mw.name,
                                  radius_text(pair, ma, mw), k));
    }
  }
  return lines;
}

}  // namespace regodem
