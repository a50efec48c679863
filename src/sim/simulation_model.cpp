#include "sim/simulation_model.hpp"

#include <fmt/format.h>

#include "core/error.hpp"

namespace regodem {

SimulationModel::SimulationModel(MaterialTable materials_in, const SimulationSettings& settings_in)
    : settings(settings_in), materials(std::move(materials_in)) {
  if (!(settings.neighbor_skin_m > 0.0))
    throw InputError(fmt::format("the neighbour skin must be positive, got {} m", settings.neighbor_skin_m));
  derive_tables();
}

void SimulationModel::derive_tables() {
  contact = ContactParameterTable(materials);
  conduction = ConductionParameterTable(materials, settings.heat.time_scale_factor);
  // Per material: 1/c when c is constant (the common, fast case), else 0 and the
  // enthalpy route, h += Q dt / m then T = h^-1, which conserves energy exactly.
  const std::size_t n_materials = materials.size();
  inv_specific_heat.assign(n_materials, 0.0);
  conductivity_varies.assign(n_materials, 0);
  for (std::size_t m = 0; m < n_materials; ++m) {
    const Material& mat = materials[static_cast<MaterialIndex>(m)];
    if (mat.specific_heat_J_per_kgK.is_constant() && mat.specific_heat_J_per_kgK.at(0.0) > 0.0)
      inv_specific_heat[m] = 1.0 / mat.specific_heat_J_per_kgK.at(0.0);
    conductivity_varies[m] = !mat.conductivity_W_per_mK.is_constant();
  }
}

}  // namespace regodem
