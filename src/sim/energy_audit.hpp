#pragma once
// The mechanical energy books of a run (docs/physics.md, "Energy audit"). The particles'
// kinetic, potential and elastic energy may change only by the work of moving walls, the
// losses at contacts and bonds, and what added or removed particles bring or take:
//   E_kin + E_pot + E_el = wall work + exchanged + spring source - dissipated
// (+ the integrator's error), where the spring source is what the Mindlin tangential
// spring's energy gains without a force's work: as its stiffness follows the overlap,
// and at its reset while sliding (contact/contact_law.hpp). It is the contact model's
// own, and the audit reports it rather than hide it in the imbalance.
// With heat.dissipation_heating every joule of `dissipated` is heat, booked in the thermal
// ledger as generated heat, so the two books meet.
#include <vector>

namespace regodem {

struct EnergyAudit {
  double wall_work_J = 0.0;    // done on the particles by moving walls, F . v + tau . omega
  double dissipated_J = 0.0;   // lost at contacts (damping, sliding, rolling) and bonds (damping, breaking)
  double spring_source_J = 0.0;  // made by the tangential springs themselves (stiffening, reset)
  // Brought in by added particles (kinetic and potential energy, and the springs' energy
  // when forces are first found after an insertion or a change of contact properties),
  // less what removed particles take out.
  double exchanged_J = 0.0;
  std::vector<double> wall_work_by_body_J;

  /// What the particles' mechanical energy should be.
  double expected_energy_J() const { return wall_work_J + exchanged_J + spring_source_J - dissipated_J; }
  /// The energy that went through the books, |wall work| + dissipated, against which an
  /// imbalance is judged (the exchanged energy holds potential energy, whose zero is
  /// arbitrary, so it is left out).
  double turnover_J() const { return (wall_work_J < 0.0 ? -wall_work_J : wall_work_J) + dissipated_J; }
  /// An imbalance over the turnover; 0 while nothing has gone through the books.
  double relative(double imbalance_J) const { return turnover_J() > 0.0 ? imbalance_J / turnover_J() : 0.0; }
};

}  // namespace regodem
