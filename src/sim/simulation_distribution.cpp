// The step's side of a run split over MPI ranks (issue 19; sim/particle_halo.hpp): which
// particles are this rank's, the decision to rebuild taken by all ranks, and the hand-over
// of particles and ghosts at each build.
#include <fmt/format.h>

#include <algorithm>
#include <array>

#include "core/error.hpp"
#include "sim/simulation.hpp"

namespace regodem {

void Simulation::start_gathered(ParticleHalo* halo) {
  halo_ = nullptr;
  gathered_halo_ = halo;
}

void Simulation::distribute(ParticleHalo* halo) {
  halo_ = halo;
  // The store holds the run's whole bond list: each rank keeps its bonds in this order.
  bonds_.number_in_order();
  bond_breaks_at_split_ = bond_breaks_.size();
  halo_build_pending_ = halo != nullptr;
  // The next build makes the grid afresh for all ranks' particles (the lists' order, and
  // every sum over them, follow the grid): a grid kept from this rank's own count would not
  // be the one of one process.
  grid_ = CellGrid{};
  ghost_.assign(halo ? particles.size() : 0, 0);
  run_particles_ = particles.size();  // a replicated start's; a spread one's from its first build
  forces_current_ = false;
}

void Simulation::gather_everywhere() {
  if (!halo_) return;
  if (every_rank_holds_all_) {
    // Split since the last gather but not yet built (a step that failed before its build):
    // every rank still holds every particle, the same, with one process's lists.
    gathered_halo_ = halo_;
    halo_ = nullptr;
    ghost_.clear();
    every_rank_holds_all_ = false;
    return;
  }
  // The contact history own particles hold, as a build would hand it to the halo (a
  // build that failed part way already saved it: its lists no longer match the particles).
  if (!lists_outdated_) neighbors_.save_history(particles);
  ghost_.resize(particles.size(), 0);
  ContactHistoryByOwner history = neighbors_.saved_history_of_kept(ghost_);
  particles.remove_if(std::vector<char>(ghost_.begin(), ghost_.end()));
  halo_->gather_everywhere(particles, history, bonds_);
  gather_bond_breaks();
  merge_fastest_impact_over_ranks();
  gathered_halo_ = halo_;
  halo_ = nullptr;
  ghost_.clear();
  neighbors_.set_saved_history(std::move(history));
  if (const std::size_t b = bonds_.refresh_indices(particles); b < bonds_.size())
    throw SimulationError(fmt::format("bond {}-{} lost an end in the gather", bonds_.id_i[b], bonds_.id_j[b]));
  grid_ = CellGrid{};
  // One process's lists over all particles: a checkpoint saves them; the forces came with
  // the particles, so the next step goes on from them as it would have.
  rebuild_neighbors(true);
}

void Simulation::merge_fastest_impact_over_ranks() {
  if (!halo_) return;
  const ImpactRecord mine = fastest_impact_;
  const std::vector<double> impacts = halo_->values_of_every_rank(std::array<double, 4>{
      mine.key, mine.approach_speed_m_per_s, static_cast<double>(mine.wall_body), mine.time_s});
  fastest_impact_ = ImpactRecord{};
  for (std::size_t at = 0; at + 4 <= impacts.size(); at += 4)
    fastest_impact_.merge(ImpactRecord{impacts[at], impacts[at + 1], static_cast<std::int32_t>(impacts[at + 2]),
                                       impacts[at + 3]});
}

void Simulation::gather_bond_breaks() {
  // The breaks since the split, each recorded by the rank of its bond's first end: every
  // rank's, by time and then bond (the order one process records them in), and counted.
  std::vector<double> mine;
  for (std::size_t e = bond_breaks_at_split_; e < bond_breaks_.size(); ++e) {
    const BondBreakEvent& b = bond_breaks_[e];
    mine.insert(mine.end(), {b.time_s, b.position_m.x, b.position_m.y, b.position_m.z, static_cast<double>(b.mode),
                             static_cast<double>(b.particle_i), static_cast<double>(b.particle_j), b.tensile_stress_Pa,
                             b.shear_stress_Pa, static_cast<double>(b.sequence)});
  }
  bond_breaks_.resize(bond_breaks_at_split_);
  const std::vector<double> all = halo_->values_of_every_rank(mine);
  std::vector<BondBreakEvent> merged;
  for (std::size_t at = 0; at + 10 <= all.size(); at += 10) {
    BondBreakEvent e;
    e.time_s = all[at];
    e.position_m = {all[at + 1], all[at + 2], all[at + 3]};
    e.mode = static_cast<BondBreak>(static_cast<int>(all[at + 4]));
    e.particle_i = static_cast<ParticleId>(all[at + 5]);
    e.particle_j = static_cast<ParticleId>(all[at + 6]);
    e.tensile_stress_Pa = all[at + 7];
    e.shear_stress_Pa = all[at + 8];
    e.sequence = static_cast<std::uint32_t>(all[at + 9]);
    merged.push_back(e);
  }
  std::stable_sort(merged.begin(), merged.end(), [](const BondBreakEvent& a, const BondBreakEvent& b) {
    return a.time_s != b.time_s ? a.time_s < b.time_s : a.sequence < b.sequence;
  });
  for (const BondBreakEvent& e : merged) {
    (e.mode == BondBreak::tension ? bond_counts_.broken_in_tension : bond_counts_.broken_in_shear)++;
    bond_breaks_.push_back(e);
  }
}

void Simulation::distribute_again() {
  if (!gathered_halo_) return;
  ParticleHalo* halo = gathered_halo_;
  gathered_halo_ = nullptr;
  const bool forces_were_current = forces_current_;
  distribute(halo);
  forces_current_ = forces_were_current;
  every_rank_holds_all_ = true;  // until the next build
}

std::size_t Simulation::run_particle_count() const { return halo_ ? run_particles_ : particles.size(); }

std::uint32_t Simulation::bits_over_ranks(std::uint32_t mine) const {
  ParticleHalo* halo = halo_ ? halo_ : gathered_halo_;
  return halo ? halo->bits_over_ranks(mine) : mine;
}

void Simulation::refuse_under_ranks(const char* what) const {
  if (halo_) throw InputError(fmt::format("{} is not yet supported in a run over MPI ranks", what));
}

std::vector<double> Simulation::particle_work() const {
  const NeighborList& nl = neighbors_;
  const bool listed = nl.offset.size() == particles.size() + 1 && nl.owner_offset.size() == particles.size() + 1;
  std::vector<double> work(particles.size(), 1.0);
  if (listed)
    for (std::size_t i = 0; i < particles.size(); ++i)
      work[i] += (nl.offset[i + 1] - nl.offset[i]) + (nl.owner_offset[i + 1] - nl.owner_offset[i]);
  return work;
}

std::size_t Simulation::own_particle_count() const {
  return particles.size() - static_cast<std::size_t>(std::count(ghost_.begin(), ghost_.end(), std::uint8_t{1}));
}

double Simulation::ghost_skin_m() const {
  // A pair is listed within R_i + R_j + h_i + h_j, each half h at most
  // max_half_skin_factor x skin/2 (NeighborSkin); a particle of the brick is inside it at
  // the build, and until the next build no pair closes that was not listed.
  const NeighborSkin skin(model_.settings.neighbor_skin_m);
  return skin.skin_m * std::max(1.0, skin.max_half_skin_factor);
}

bool Simulation::rebuild_everywhere(bool here, const std::exception_ptr& failed) {
  if (!halo_) {
    if (failed) std::rethrow_exception(failed);
    return here;
  }
  // The lists' validity is each rank's, the rebuild every rank's: one rank's grains moving
  // rebuilds all, as in one process.
  return halo_->any_rank(here || halo_build_pending_, failed);
}

void Simulation::redistribute_particles() {
  neighbors_.save_history(particles);
  lists_outdated_ = true;  // from here until the lists are built again
  ghost_.resize(particles.size(), 0);
  // Own particles that left the domain go with the ghosts (domain.lost_particles: remove),
  // their heat and motion out of every rank's books (as remove_lost_particles does in one
  // process; the books are the run's on every rank), summed in rank order.
  if (model_.settings.lost_particles == LostParticles::remove) drop_lost_over_ranks();
  every_rank_holds_all_ = false;  // the halo cuts the particles now
  ContactHistoryByOwner history = neighbors_.saved_history_of_kept(ghost_);
  const std::vector<double> every_work = particle_work();
  std::vector<double> work;  // the own particles'
  work.reserve(particles.size());
  for (std::size_t i = 0; i < particles.size(); ++i)
    if (!ghost_[i]) work.push_back(every_work[i]);
  particles.remove_if(std::vector<char>(ghost_.begin(), ghost_.end()));
  try {
    halo_->redistribute(particles, history, work, ghost_, bonds_);
  } catch (...) {
    // Every rank stopped at the same point (the halo agrees its errors), holding its own
    // particles, no ghosts, and their history: kept so that the failed run can still be
    // gathered and written (gather_everywhere).
    ghost_.assign(particles.size(), 0);
    if (history.owners() == particles.size()) neighbors_.set_saved_history(std::move(history));
    throw;
  }
  if (ghost_.size() != particles.size() || history.owners() != particles.size())
    throw SimulationError(fmt::format("the halo returned {} particles with {} ghost flags and {} histories",
                                      particles.size(), ghost_.size(), history.owners()));
  neighbors_.set_saved_history(std::move(history));
  if (bonds_configured()) {
    // Each bond of this rank's particles needs its other end here, own or ghost.
    std::exception_ptr stretched;
    if (const std::size_t b = bonds_.refresh_indices(particles); b < bonds_.size())
      stretched = std::make_exception_ptr(SimulationError(fmt::format(
          "the bond between particles {} and {} reaches farther than the ghosts (their radii and {:.4g} m from the "
          "other rank's grains): its ends are more than their radii and the skin apart, which an intact bond should not be",
          bonds_.id_i[b], bonds_.id_j[b], ghost_skin_m())));
    halo_->agree(stretched);
  }
}

void Simulation::drop_lost_over_ranks() {
  // Own particles that left the domain go with the ghosts, their heat and motion out of
  // every rank's books (as remove_lost_particles does in one process; the books are the
  // run's on every rank): each rank's sums and lost ids on every rank, added in rank order.
  const std::vector<std::uint8_t> was_ghost = ghost_;
  // At the first build after a gather every rank still holds every particle as its own:
  // each finds the same lost ones, which count once (rank 0's), and holds every bond.
  const bool everyone_holds_all = every_rank_holds_all_;
  std::vector<double> mine{0.0, 0.0, 0.0};  // thermal energy, mechanical energy, count; then the ids
  for (std::size_t i = 0; i < particles.size(); ++i) {
    if (ghost_[i] || model_.settings.domain.contains(particles.position_m[i])) continue;
    ghost_[i] = 1;
    if (heat_enabled()) mine[0] += particle_thermal_energy_J(i);
    mine[1] += particle_mechanical_energy_J(i);
    mine[2] += 1.0;
    mine.push_back(static_cast<double>(particles.id[i]));
  }
  const std::vector<double> all = halo_->values_of_every_rank(mine);
  double thermal_J = 0.0, mechanical_J = 0.0;
  std::vector<ParticleId> lost_ids;
  for (std::size_t at = 0, rank = 0; at + 3 <= all.size(); ++rank) {
    const auto count = static_cast<std::size_t>(all[at + 2]);
    if (!everyone_holds_all || rank == 0) {
      thermal_J += all[at];
      mechanical_J += all[at + 1];
      for (std::size_t k = 0; k < count; ++k) lost_ids.push_back(static_cast<ParticleId>(all[at + 3 + k]));
    }
    at += 3 + count;
  }
  if (heat_enabled()) ledger_.reference_energy_J -= thermal_J;
  audit_.exchanged_J -= mechanical_J;
  lost_particle_count_ += lost_ids.size();
  if (lost_ids.empty() || !bonds_configured()) return;  // the same on every rank
  // Their bonds go too (not broken: nothing failed in them), what they stored booked once,
  // by the rank of each bond's first end.
  std::sort(lost_ids.begin(), lost_ids.end());
  const auto is_lost = [&](ParticleId id) { return std::binary_search(lost_ids.begin(), lost_ids.end(), id); };
  std::vector<char> keep(bonds_.size(), 1);
  double stored_J = 0.0;
  for (std::size_t b = 0; b < bonds_.size(); ++b) {
    if (!is_lost(bonds_.id_i[b]) && !is_lost(bonds_.id_j[b])) continue;
    keep[b] = 0;
    if (!was_ghost[bonds_.local_i[b]])
      stored_J += regodem::bond_elastic_energy_J(model_.bond_kinds[bonds_.kind[b]], bonds_.section[b], bonds_.loads_of(b));
  }
  if (!everyone_holds_all) halo_->sum_in_rank_order(std::span<double>(&stored_J, 1));
  if (keeps_energy_audit()) audit_.exchanged_J -= stored_J;
  bonds_.keep_in_sequence_order(keep);
}

void Simulation::sum_totals_over_ranks() {
  // One message a pass: every total packed, summed, unpacked.
  std::vector<double> totals;
  const auto pack = [&totals](double value) { totals.push_back(value); };
  for (std::size_t b = 0; b < walls.bodies.size(); ++b) {
    for (const Vec3& v : {walls.bodies[b].force_N, walls.bodies[b].torque_N_m}) {
      pack(v.x);
      pack(v.y);
      pack(v.z);
    }
  }
  for (const std::vector<double>* values : {&wall_power_W_, &wall_generated_heat_W_, &node_heat_in_W_})
    for (const double value : *values) pack(value);
  for (const ThermalWallState& wall : wall_thermal_state) pack(wall.heat_flow_to_particles_W);
  for (const double value : {generated_heat_W_, dissipated_power_W_, contact_elastic_energy_J_, spring_source_W_,
                             static_cast<double>(stats_.particle_contacts), static_cast<double>(stats_.wall_contacts)})
    pack(value);

  halo_->sum_in_rank_order(totals);

  std::size_t at = 0;
  const auto take = [&totals, &at]() { return totals[at++]; };
  for (WallBody& body : walls.bodies)
    for (Vec3* v : {&body.force_N, &body.torque_N_m}) {
      v->x = take();
      v->y = take();
      v->z = take();
    }
  for (std::vector<double>* values : {&wall_power_W_, &wall_generated_heat_W_, &node_heat_in_W_})
    for (double& value : *values) value = take();
  for (ThermalWallState& wall : wall_thermal_state) wall.heat_flow_to_particles_W = take();
  for (double* value : {&generated_heat_W_, &dissipated_power_W_, &contact_elastic_energy_J_, &spring_source_W_})
    *value = take();
  // Counts below 2^53 are exact as doubles.
  stats_.particle_contacts = static_cast<std::uint64_t>(take());
  stats_.wall_contacts = static_cast<std::uint64_t>(take());
}

double Simulation::total_over_ranks(ExactSum mine) const {
  merge_over_ranks(std::span<ExactSum>(&mine, 1));
  return mine.value();
}

double Simulation::largest_over_ranks(double mine) const { return halo_ ? halo_->max_over_ranks(mine) : mine; }

}  // namespace regodem
