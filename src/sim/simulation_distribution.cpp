// The step's side of a run split over MPI ranks (issue 19; sim/particle_halo.hpp): which
// particles are this rank's, the decision to rebuild taken by all ranks, and the hand-over
// of particles and ghosts at each build.
#include <fmt/format.h>

#include <algorithm>

#include "core/error.hpp"
#include "sim/simulation.hpp"

namespace regodem {

void Simulation::distribute(ParticleHalo* halo) {
  if (!bonds_.empty() || bonds_configured())
    throw InputError("bonds are not yet supported in a run over MPI ranks");
  if (settings_.lost_particles == LostParticles::remove)
    throw InputError("domain.lost_particles: remove is not yet supported in a run over MPI ranks");
  for (std::size_t b = 0; b < wall_thermal.size(); ++b)
    if (wall_thermal[b].mode == WallThermalMode::lumped)
      throw InputError(fmt::format("wall '{}' is lumped: lumped walls are not yet supported in a run over MPI ranks",
                                   walls.bodies[b].name));
  halo_ = halo;
  halo_build_pending_ = halo != nullptr;
  // The next build makes the grid afresh for all ranks' particles (the lists' order, and
  // every sum over them, follow the grid): a grid kept from this rank's own count would not
  // be the one of one process.
  grid_ = CellGrid{};
  ghost_.assign(halo ? particles.size() : 0, 0);
  forces_current_ = false;
}

std::size_t Simulation::own_particle_count() const {
  return particles.size() - static_cast<std::size_t>(std::count(ghost_.begin(), ghost_.end(), std::uint8_t{1}));
}

double Simulation::ghost_reach_m(double largest_radius_m) const {
  // A pair is listed within R_i + R_j + h_i + h_j, each half h at most
  // max_half_skin_factor x skin/2 (NeighborSkin); a particle of the brick is inside it at
  // the build, and until the next build no pair closes that was not listed.
  const NeighborSkin skin(settings_.neighbor_skin_m);
  const double largest_half_m = 0.5 * skin.skin_m * std::max(1.0, skin.max_half_skin_factor);
  return 2.0 * largest_radius_m + 2.0 * largest_half_m;
}

bool Simulation::rebuild_everywhere(bool here) {
  if (!halo_) return here;
  // The lists' validity is each rank's, the rebuild every rank's: one rank's grains moving
  // rebuilds all, as in one process.
  return halo_->any_rank(here || halo_build_pending_);
}

void Simulation::redistribute_particles() {
  neighbors_.save_history(particles);
  ghost_.resize(particles.size(), 0);
  ContactHistoryByOwner history = neighbors_.saved_history_of_kept(ghost_);
  particles.remove_if(std::vector<char>(ghost_.begin(), ghost_.end()));
  halo_->redistribute(particles, history, ghost_);
  if (ghost_.size() != particles.size() || history.owners() != particles.size())
    throw SimulationError(fmt::format("the halo returned {} particles with {} ghost flags and {} histories",
                                      particles.size(), ghost_.size(), history.owners()));
  neighbors_.set_saved_history(std::move(history));
}

}  // namespace regodem
