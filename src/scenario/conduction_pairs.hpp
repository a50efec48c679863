#pragma once
// What conduction will use at every kind of contact that passes heat, said before a run
// (`validate` prints it), and the check that keeps a scenario from mixing a real modulus
// with a reduced one at those contacts (the paper's Eq. 1 needs the real E*).
#include <optional>
#include <string>
#include <vector>

#include "core/material.hpp"
#include "scenario/scenario_spec.hpp"

namespace regodem {

/// A wall body that conducts (fixed or lumped), as conduction sees it.
struct ConductingWall {
  std::string name;
  MaterialIndex material = 0;
  std::optional<double> conductivity_W_per_mK;  // none: the particle's own (Eq. 1's k_s)
  bool harmonic_mean = false;                   // k_c = 2 k_w k / (k_w + k) (EDEM)
};

/// One line per conducting pair: particle materials with each other and with each
/// conducting wall: the law, the E* its contact radius uses against the mechanics', and
/// k_c. Throws InputError (file:line of the material) when some material of the
/// scenario gives a real modulus and a material of a force-law conducting pair does not
/// say what its modulus is (`real_shear_modulus: VALUE` or `same`).
std::vector<std::string> conduction_pair_lines(const ScenarioSpec& spec, const MaterialTable& materials,
                                               const std::vector<char>& particle_material,
                                               const std::vector<ConductingWall>& walls);

}  // namespace regodem
