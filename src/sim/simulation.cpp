#include "sim/simulation.hpp"

#include <fmt/format.h>
#include <omp.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include "contact/contact_law.hpp"
#include "core/error.hpp"
#include "geometry/mesh_contact.hpp"
#include "sim/contact_walk.hpp"
#include "sim/overlap_scan.hpp"

namespace regodem {

namespace {

/// The velocity-Verlet half kick, v += F dt/(2m) and omega += tau dt/(2I), over raw
/// non-aliasing views of the arrays; both halves of the step use it.
struct HalfKick {
  Vec3* __restrict velocity;
  Vec3* __restrict angular_velocity;
  const Vec3* __restrict force;
  const Vec3* __restrict torque;
  const double* __restrict inv_mass;
  const double* __restrict inv_inertia;
  double half_dt;

  HalfKick(ParticleStore& p, double half_dt_s)
      : velocity(p.velocity_m_per_s.data()),
        angular_velocity(p.angular_velocity_rad_per_s.data()),
        force(p.force_N.data()),
        torque(p.torque_N_m.data()),
        inv_mass(p.inv_mass_per_kg.data()),
        inv_inertia(p.inv_inertia.data()),
        half_dt(half_dt_s) {}

  void operator()(std::size_t i) const {
    velocity[i] += force[i] * (half_dt * inv_mass[i]);
    angular_velocity[i] += torque[i] * (half_dt * inv_inertia[i]);
  }
};

/// What a tangential spring held when its contact opened this step: k_t |xi|^2 / 2 at the
/// overlap of a step ago, delta - v_n dt (delta < 0 now, v_n > 0 closing). The sliding
/// reset can leave a spring holding energy that does not fade with the overlap
/// (contact_law.hpp); the audit books its leaving as the spring source's.
double opened_spring_energy_J(const ContactPairParameters& p, const Vec3& spring_m, double effective_radius_m,
                              double overlap_m, double approach_speed_m_per_s, double dt_s) {
  const double earlier_overlap_m = overlap_m - approach_speed_m_per_s * dt_s;
  if (!(earlier_overlap_m > 0.0)) return 0.0;
  const double stiffness = MindlinTangential::stiffness(
      p.effective_shear_modulus_Pa, HertzNormal::contact_radius_m(effective_radius_m, earlier_overlap_m));
  return 0.5 * stiffness * norm2(spring_m);
}

/// The tangential spring of a mesh contact lives with a triangle's list entry. When a
/// sphere rolls or slides across an edge its contact moves to the next triangle, whose
/// entry has no spring yet: the spring moves with it from the entry that just lost its
/// touch, if that triangle shares a vertex with the new one. Springs of entries not
/// touching are then cleared, as for every other contact; `cleared(entry, spring)` is
/// told of each (the energy audit books what it held).
template <class OnCleared>
void carry_mesh_springs(const TriangleMesh& mesh, const std::uint32_t* triangles, std::uint32_t count,
                        const std::vector<MeshTouch>& touches, Vec3* spring, std::vector<char>& touched,
                        OnCleared&& cleared) {
  touched.assign(count, 0);
  for (const MeshTouch& t : touches) touched[t.entry] = 1;
  const auto share_a_vertex = [&](std::uint32_t a, std::uint32_t b) {
    for (const std::uint32_t va : mesh.triangles[triangles[a]])
      for (const std::uint32_t vb : mesh.triangles[triangles[b]])
        if (va == vb) return true;
    return false;
  };
  for (const MeshTouch& t : touches) {
    if (spring[t.entry] != Vec3{}) continue;
    for (std::uint32_t e = 0; e < count; ++e)
      if (!touched[e] && spring[e] != Vec3{} && share_a_vertex(e, t.entry)) {
        spring[t.entry] = spring[e];
        spring[e] = {};
        break;
      }
  }
  for (std::uint32_t e = 0; e < count; ++e)
    if (!touched[e] && spring[e] != Vec3{}) {
      cleared(e, spring[e]);
      spring[e] = {};
    }
}

}  // namespace

Simulation::Simulation(MaterialTable materials_in, WallSet walls_in, const SimulationSettings& settings,
                       std::vector<ThermalWall> wall_thermal_in)
    : walls(std::move(walls_in)), model_(std::move(materials_in), settings) {
  const std::size_t n_bodies = walls.bodies.size();
  model_.wall_thermal = std::move(wall_thermal_in);
  std::vector<ThermalWall>& wall_thermal = model_.wall_thermal;
  if (wall_thermal.empty()) wall_thermal.resize(n_bodies);
  if (wall_thermal.size() != n_bodies)
    throw InputError(fmt::format("{} wall thermal descriptions for {} walls", wall_thermal.size(), n_bodies));
  mesh_scratch_.resize(model_.settings.threads);
  wall_generated_heat_W_.assign(n_bodies, 0.0);
  wall_power_W_.assign(n_bodies, 0.0);
  audit_.wall_work_by_body_J.assign(n_bodies, 0.0);
  wall_node_begin_.assign(1, 0);
  for (std::size_t b = 0; b < n_bodies; ++b) {
    const ThermalWall& w = wall_thermal[b];
    if (w.mode != WallThermalMode::lumped && w.rod.exchanges())
      throw InputError(fmt::format("wall {}: only a lumped wall has segments, radiation or a held end", b));
    wall_thermal_state.push_back(ThermalWallState::start(w));
    ledger_.reference_energy_J += wall_thermal_state.back().stored_heat_J(w);
    wall_node_begin_.push_back(wall_node_begin_.back() + static_cast<std::uint32_t>(w.node_count()));
  }
  node_heat_in_W_.assign(wall_node_begin_.back(), 0.0);
  for (const MeshWall& mesh : walls.meshes) {
    const std::size_t nodes = wall_thermal[mesh.body].node_count();
    if (nodes > 1 && mesh.triangle_segment.size() != mesh.mesh.triangle_count())
      throw InputError(fmt::format("wall {} has {} thermal segments but its mesh gives its triangles none", mesh.body,
                                   nodes));
  }
}

void Simulation::add_particle(const NewParticle& p) {
  refuse_under_ranks("adding particles");
  const std::size_t i = particles.add(p);
  particles.conductivity_W_per_mK[i] = model_.materials[p.material].conductivity_W_per_mK.at(p.temperature_K);
  if (heat_enabled()) ledger_.reference_energy_J += particle_thermal_energy_J(i);
  audit_.exchanged_J += particle_mechanical_energy_J(i);
  forces_current_ = false;
}

void Simulation::set_materials(MaterialTable materials) {
  model_.materials = std::move(materials);
  model_.derive_tables();
  forces_current_ = false;
}

void Simulation::rebuild_neighbors(bool history_saved) {
  // Under MPI the grid is every rank's (sized for all ranks' particles), so that the sort
  // and every sum over it go in the order of one process.
  std::size_t grid_particles = particles.size();
  if (halo_) {
    redistribute_particles();
    history_saved = true;
    grid_particles = halo_->sum_over_ranks(own_particle_count());
    run_particles_ = grid_particles;
    halo_build_pending_ = false;
  }
  // The grid is sized for the current particle count: the counting sort costs one pass
  // over the cells, which must stay of the order of the particle count.
  const double max_cells = 16.0 * static_cast<double>(grid_particles) + 4096.0;
  if (grid_.cell_count() <= 1 || static_cast<double>(grid_.cell_count()) > max_cells ||
      static_cast<double>(grid_.cell_count()) < 0.25 * max_cells)
    grid_ = CellGrid(model_.settings.domain.min_m, model_.settings.domain.max_m,
                     2.0 * model_.settings.min_particle_radius_m + model_.settings.neighbor_skin_m, max_cells);
  active_threads_ = force_pass_threads();
  NeighborSkin skin(model_.settings.neighbor_skin_m);
  skin.time_step_s = model_.settings.time_step_s;
  skin.body_step_m = walls.surface_steps_m(time_s_, model_.settings.time_step_s);
  neighbors_.rebuild(particles, walls, grid_, skin, active_threads_, history_saved, halo_ ? &ghost_ : nullptr);
  lists_outdated_ = false;
  walls.mark_neighbor_build();
  if (halo_) halo_->follow_sort(neighbors_.sort_order());  // the ghost flags followed it in the rebuild
  if (!bonds_.empty()) {  // the rebuild re-sorted the particles
    const std::vector<std::uint32_t>& order = neighbors_.sort_order();
    const std::size_t n = order.size();
    std::vector<std::uint32_t> new_index_of_old(n);
#pragma omp parallel for schedule(static) num_threads(active_threads_) if (n > 4096)
    for (std::size_t i = 0; i < n; ++i) new_index_of_old[order[i]] = static_cast<std::uint32_t>(i);
    bonds_.renumber(new_index_of_old, particles.size(), active_threads_);
  }
}

int Simulation::force_pass_threads() const {
  // Few particles per thread: fewer threads (the sums do not depend on how many).
  return static_cast<int>(std::clamp<std::size_t>(particles.size() / model_.settings.min_particles_per_thread, 1,
                                                  static_cast<std::size_t>(model_.settings.threads)));
}

void Simulation::ensure_forces() {
  if (forces_current_) return;
  if (rebuild_everywhere(neighbors_.needs_rebuild(particles, walls, model_.settings.threads)))
    rebuild_neighbors();
  else if (halo_)
    halo_->refresh_ghosts(particles);
  // What changed the state without a step (an insertion, a removal, new contact
  // properties) also changed the springs' energy: the audit books it as exchanged.
  const double springs_before_J = contact_elastic_energy_J_;
  compute_forces(0.0);
  audit_.exchanged_J += contact_elastic_energy_J_ - springs_before_J;
  audit_awaits_contact_elastic_ = false;  // an old checkpoint's springs: just booked
  forces_current_ = true;
}

void Simulation::step() {
  ensure_forces();
  // Under MPI a blow-up on one rank is raised on every rank at the next decision they all
  // take, so that none waits for a rank that has stopped.
  std::exception_ptr failed;
  double max_displacement_ratio2 = 0.0;
  try {
    max_displacement_ratio2 = first_half_kick_and_drift();
  } catch (const SimulationError&) {
    if (!halo_) throw;
    failed = std::current_exception();
  }
  walls.advance(time_s_, model_.settings.time_step_s);
  time_s_ += model_.settings.time_step_s;
  ++step_;
  if (rebuild_everywhere(neighbors_.needs_rebuild(particles.size(), max_displacement_ratio2, walls), failed))
    rebuild_neighbors();
  else if (halo_)
    halo_->refresh_ghosts(particles);
  compute_forces(model_.settings.time_step_s);
  if (halo_) {
    try {
      second_half_kick();
    } catch (const SimulationError&) {
      failed = std::current_exception();
    }
    halo_->agree(failed);
  } else {
    second_half_kick();
  }
  book_mechanical_energy(model_.settings.time_step_s);
  if (heat_enabled()) update_temperatures(model_.settings.time_step_s);
}

void Simulation::book_end_of_step_losses() {
  // A force evaluated at step n+1 does its work, in velocity Verlet, at the velocity the
  // step ends with, v + F dt / (2m) with F every force on the body (and omega + T dt/(2I)).
  // A rolling torque's loss is taken whole here: the cap that stops a spin in one step
  // then takes its energy, I omega^2 / 2, not twice it, and several capped contacts that
  // reverse a spin give back what the reversal makes; at a wall the wall's spin adds
  // tau_r . omega_w (its own work). The contact pass took damping and friction at the
  // half-step velocities; their end-of-step part, -G . F dt/(2m) - Lambda . T dt/(2I)
  // with G and Lambda the lossy forces and torques on the body, is added here (at a few
  // steps per contact it is tens of per cent of the loss). With dissipation heating it
  // heats the particle whose velocity it concerns, except the part of its wall contacts
  // that the partition gives the wall (WallLossShare; docs/physics.md, "Energy audit").
  const std::size_t n = particles.size();
  const double half_dt = 0.5 * model_.settings.time_step_s;
  const bool heats = heat_enabled() && model_.settings.heat.dissipation_heating;
  const LossyActions* __restrict lossy = particle_lossy_.data();
  const double* __restrict wall_power = rolling_wall_power_W_.data();
  const Vec3* __restrict w = particles.angular_velocity_rad_per_s.data();
  const Vec3* __restrict force = particles.force_N.data();
  const Vec3* __restrict torque = particles.torque_N_m.data();
  const double* __restrict inv_mass = particles.inv_mass_per_kg.data();
  const double* __restrict inv_inertia = particles.inv_inertia.data();
  double* __restrict heat = particles.heat_flow_W.data();
  BlockEnergy* __restrict block_energy = block_energy_.data();
  constexpr std::uint32_t block_size = NeighborList::kOwnerBlock;
  // The part of a wall contact's loss the wall takes (its share 1 - s, as in the contact
  // pass) goes to the wall's node, block by block in order, so that no heat of a contact
  // with a moving drill is left to the grain alone (docs/drilling-heat.md).
  const WallLossShare* __restrict wall_loss = wall_loss_share_.data();
  const bool shares = heats && wall_loss_share_.size() == n;
  const std::size_t n_nodes = node_heat_in_W_.size();
  const std::size_t blocks = (n + block_size - 1) / block_size;
  if (shares) block_node_end_of_step_W_.assign(blocks * n_nodes, 0.0);
  double* __restrict block_node = block_node_end_of_step_W_.data();
  const double* __restrict own_spin = own_spin_resistance_N_m_.data();
  const Vec3* __restrict own_spin_torque = own_spin_torque_N_m_.data();
  const std::uint8_t* __restrict ghost = ghost_.empty() ? nullptr : ghost_.data();
  const std::size_t run = NeighborList::owner_block_run(n, active_threads_);
#pragma omp parallel for schedule(static, run) num_threads(active_threads_) if (n > 4096)
  for (std::size_t p = 0; p < n; ++p) {
    if (ghost && ghost[p]) continue;  // its own rank books it
    const LossyActions& a = lossy[p];
    const Vec3 velocity_change = force[p] * (half_dt * inv_mass[p]);
    const Vec3 spin_change = torque[p] * (half_dt * inv_inertia[p]);
    const Vec3 end_spin = w[p] + spin_change;
    const double loss = wall_power[p] - dot(a.rolling_torque_N_m, end_spin) -
                        dot(a.lossy_force_N, velocity_change) - dot(a.lossy_torque_N_m, spin_change);
    if (loss == 0.0) continue;
    block_energy[p / block_size].dissipated_W += loss;
    if (!heats) continue;
    block_energy[p / block_size].generated_heat_W += loss;
    double to_walls_W = 0.0;
    if (shares && wall_loss[p].node[0] != WallLossShare::no_node) {
      const WallLossShare& share = wall_loss[p];
      // EDEM's own-spin torque comes from the particle's whole resistance: each wall's
      // part of its loss is in proportion to that wall's (weighted) resistance.
      const double own_spin_loss_W = own_spin[p] > 0.0 ? -dot(own_spin_torque[p], end_spin) : 0.0;
      for (int slot = 0; slot < 2 && share.node[slot] != WallLossShare::no_node; ++slot) {
        const LossyActions& s = share.actions[slot];
        double wall_W = share.rolling_wall_power_W[slot] - dot(s.rolling_torque_N_m, end_spin) -
                        dot(s.lossy_force_N, velocity_change) - dot(s.lossy_torque_N_m, spin_change);
        if (own_spin[p] > 0.0) wall_W += share.own_spin_resistance_N_m[slot] / own_spin[p] * own_spin_loss_W;
        block_node[(p / block_size) * n_nodes + share.node[slot]] += wall_W;
        to_walls_W += wall_W;
      }
    }
    heat[p] += loss - to_walls_W;
  }
  if (!shares) return;
  for (std::size_t b = 0; b + 1 < wall_node_begin_.size(); ++b)
    for (std::uint32_t node = wall_node_begin_[b]; node < wall_node_begin_[b + 1]; ++node) {
      double sum_W = 0.0;
      for (std::size_t k = 0; k < blocks; ++k) sum_W += block_node[k * n_nodes + node];
      node_heat_in_W_[node] += sum_W;
      wall_generated_heat_W_[b] += sum_W;
    }
}

void Simulation::book_mechanical_energy(double dt_s) {
  for (std::size_t b = 0; b < wall_power_W_.size(); ++b) {
    audit_.wall_work_by_body_J[b] += wall_power_W_[b] * dt_s;
    audit_.wall_work_J += wall_power_W_[b] * dt_s;
  }
  audit_.dissipated_J += dissipated_power_W_ * dt_s;
  audit_.spring_source_J += spring_source_W_ * dt_s;
  if (audit_awaits_contact_elastic_) {
    audit_.exchanged_J += contact_elastic_energy_J_;
    audit_awaits_contact_elastic_ = false;
  }
}

double Simulation::particle_mechanical_energy_J(std::size_t i) const {
  double e = -particles.mass_kg[i] * dot(model_.settings.gravity_m_per_s2, particles.position_m[i]);
  if (particles.inv_mass_per_kg[i] > 0.0) e += 0.5 * particles.mass_kg[i] * norm2(particles.velocity_m_per_s[i]);
  if (particles.inv_inertia[i] > 0.0)
    e += 0.5 * norm2(particles.angular_velocity_rad_per_s[i]) / particles.inv_inertia[i];
  return e;
}

void Simulation::set_particle_velocity(std::size_t i, const Vec3& velocity_m_per_s,
                                       const Vec3& angular_velocity_rad_per_s) {
  refuse_under_ranks("setting a particle's velocity");
  const bool finite = std::isfinite(norm2(velocity_m_per_s)) && std::isfinite(norm2(angular_velocity_rad_per_s));
  if (!finite) throw InputError(fmt::format("particle {}: a velocity and spin must be finite", particles.id[i]));
  if (particles.inv_mass_per_kg[i] == 0.0)
    throw InputError(fmt::format("particle {} is held fixed: its velocity cannot be set", particles.id[i]));
  const double before_J = particle_mechanical_energy_J(i);
  particles.velocity_m_per_s[i] = velocity_m_per_s;
  if (particles.inv_inertia[i] > 0.0) particles.angular_velocity_rad_per_s[i] = angular_velocity_rad_per_s;
  audit_.exchanged_J += particle_mechanical_energy_J(i) - before_J;
  forces_current_ = false;  // the damping the next half-kick uses follows the new velocity
}

double Simulation::elastic_energy_J() const { return contact_elastic_energy_J_ + bond_elastic_energy_J(); }

double Simulation::mechanical_energy_J() const {
  return translational_kinetic_energy_J() + rotational_kinetic_energy_J() + gravitational_potential_energy_J() +
         elastic_energy_J();
}

void Simulation::advance(std::uint64_t steps) {
  for (std::uint64_t s = 0; s < steps; ++s) step();
}

double Simulation::first_half_kick_and_drift() {
  const double dt = model_.settings.time_step_s, half_dt = 0.5 * dt;
  const std::size_t n = particles.size();
  const std::vector<Vec3>& at_build = neighbors_.positions_at_build_m();
  int escaped = 0;
  double max_ratio2 = 0.0;
  const HalfKick kick(particles, half_dt);
  Vec3* __restrict x = particles.position_m.data();
  const Vec3* __restrict v = particles.velocity_m_per_s.data();
  const Vec3* __restrict x_build = at_build.data();
  const double* __restrict inv_half2 = neighbors_.inverse_half_skin2().data();
  const Domain domain = model_.settings.domain;
  const std::uint8_t* ghost = ghost_.empty() ? nullptr : ghost_.data();  // their ranks move them
#pragma omp parallel for schedule(static) num_threads(model_.settings.threads) if (n > 2048) \
    reduction(max : escaped, max_ratio2)
  for (std::size_t i = 0; i < n; ++i) {
    if (ghost && ghost[i]) continue;
    kick(i);
    x[i] += v[i] * dt;
    if (!domain.contains(x[i])) escaped = 1;  // also false for NaN
    max_ratio2 = std::max(max_ratio2, norm2(x[i] - x_build[i]) * inv_half2[i]);
  }
  if (escaped) {
    if (model_.settings.lost_particles == LostParticles::stop) report_blow_up("left the domain", time_s_ + dt, step_ + 1);
    if (halo_) {
      // Over ranks the lost go at this step's build, which every rank then makes
      // (redistribute_particles); a non-finite state is a blow-up, raised at the vote.
      for (std::size_t i = 0; i < n; ++i)
        if (!(ghost && ghost[i]) && !domain.contains(x[i]) &&
            !std::isfinite(x[i].x + x[i].y + x[i].z + v[i].x + v[i].y + v[i].z))
          report_blow_up("left the domain", time_s_ + dt, step_ + 1);
      return std::numeric_limits<double>::infinity();
    }
    remove_lost_particles();
    return 0.0;  // the lists were just rebuilt
  }
  return max_ratio2;
}

void Simulation::second_half_kick() {
  const double dt = model_.settings.time_step_s, half_dt = 0.5 * dt;
  const std::size_t n = particles.size();
  int too_fast = 0;
  const HalfKick kick(particles, half_dt);
  const Vec3* __restrict v = particles.velocity_m_per_s.data();
  const double* __restrict radius = particles.radius_m.data();
  const std::uint8_t* ghost = ghost_.empty() ? nullptr : ghost_.data();
#pragma omp parallel for schedule(static) num_threads(model_.settings.threads) if (n > 2048) reduction(max : too_fast)
  for (std::size_t i = 0; i < n; ++i) {
    if (ghost && ghost[i]) continue;
    kick(i);
    // Moving more than half a radius per step means the contacts are no longer resolved.
    const double limit = 0.5 * radius[i];
    if (!(norm2(v[i]) * dt * dt <= limit * limit)) too_fast = 1;  // also true for NaN
  }
  if (too_fast) report_blow_up("moved more than half its radius in one step", time_s_, step_);
}

void Simulation::remove_lost_particles() {
  const std::size_t n = particles.size();
  std::vector<char> lost(n, 0);
  std::size_t count = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& x = particles.position_m[i];
    const Vec3& v = particles.velocity_m_per_s[i];
    // A non-finite state is a blow-up, never a loss.
    if (!std::isfinite(x.x + x.y + x.z + v.x + v.y + v.z))
      report_blow_up("left the domain", time_s_ + model_.settings.time_step_s, step_ + 1);
    if (model_.settings.domain.contains(x)) continue;
    lost[i] = 1;
    ++count;
    // Its heat leaves with it: the ledger's reference drops as insertion raised it; so
    // does its motion, from the audit.
    if (heat_enabled()) ledger_.reference_energy_J -= particle_thermal_energy_J(i);
    audit_.exchanged_J -= particle_mechanical_energy_J(i);
    spdlog::debug("particle {} left the domain at ({:.4g}, {:.4g}, {:.4g}) m at {:.3g} m/s: removed", particles.id[i],
                  x.x, x.y, x.z, norm(v));
  }
  if (lost_particle_count_ == 0)
    spdlog::warn("t = {:.6g} s: {} particle(s) left the domain and were removed (domain.lost_particles: remove); "
                 "the time series counts them in 'particles_lost'",
                 time_s_ + model_.settings.time_step_s, count);
  lost_particle_count_ += count;
  drop_particles(lost);
}

void Simulation::drop_particles(const std::vector<char>& flags) {
  // Contact history is kept by owner, found again past the removal; the bonds of a
  // removed particle go with it (not counted as broken: nothing failed in them).
  neighbors_.save_history(particles);
  neighbors_.history_follows_removal(flags);
  if (!bonds_.empty()) {
    // What the removed bonds stored leaves the books (two passes over the bonds: only when kept).
    const bool books = keeps_energy_audit();
    const double bonds_before_J = books ? bond_elastic_energy_J() : 0.0;
    bonds_.remove_with_particles(particles, flags);
    if (books) audit_.exchanged_J -= bonds_before_J - bond_elastic_energy_J();
    constexpr std::uint32_t kGone = 0xFFFFFFFFu;  // no bond is left on a removed particle
    std::vector<std::uint32_t> new_index_of_old(particles.size(), kGone);
    std::uint32_t kept = 0;
    for (std::size_t i = 0; i < particles.size(); ++i)
      if (!flags[i]) new_index_of_old[i] = kept++;
    bonds_.renumber(new_index_of_old, kept);
  }
  particles.remove_if(flags);
  rebuild_neighbors(true);
}

void Simulation::remove_particles(const std::vector<char>& remove_flag) {
  refuse_under_ranks("removing particles");
  if (std::find(remove_flag.begin(), remove_flag.end(), 1) == remove_flag.end()) return;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    if (!remove_flag[i]) continue;
    if (heat_enabled()) ledger_.reference_energy_J -= particle_thermal_energy_J(i);
    audit_.exchanged_J -= particle_mechanical_energy_J(i);
  }
  drop_particles(remove_flag);
  forces_current_ = false;
}

void Simulation::jump_to(double time_s) {
  if (!(time_s > time_s_)) return;
  const double from_s = time_s_;
  const auto pieces = static_cast<std::uint64_t>(
      std::ceil((time_s - from_s) / std::max(model_.settings.time_step_s, (time_s - from_s) / 10000.0)));
  for (std::uint64_t k = 0; k < pieces; ++k) {
    const double start_s = from_s + (time_s - from_s) * static_cast<double>(k) / static_cast<double>(pieces);
    const double end_s = from_s + (time_s - from_s) * static_cast<double>(k + 1) / static_cast<double>(pieces);
    walls.advance(start_s, end_s - start_s);
  }
  time_s_ = time_s;
  forces_current_ = false;
}

void Simulation::report_blow_up(const std::string& what, double at_time_s, std::uint64_t at_step) const {
  const double dt = model_.settings.time_step_s;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const Vec3& x = particles.position_m[i];
    const Vec3& v = particles.velocity_m_per_s[i];
    const double speed = norm(v);
    const bool bad_state = !std::isfinite(x.x + x.y + x.z + v.x + v.y + v.z);
    const bool escaped = !model_.settings.domain.contains(x);
    const bool too_fast = speed * dt > 0.5 * particles.radius_m[i];
    if (!(bad_state || escaped || too_fast)) continue;
    const std::string state = bad_state ? "has a non-finite position or velocity" : what;
    throw SimulationError(fmt::format(
        "particle {} {} at t = {:.6g} s (step {}): position ({:.6g}, {:.6g}, {:.6g}) m, speed {:.6g} m/s, "
        "radius {:.6g} m. {}",
        particles.id[i], state, at_time_s, at_step, x.x, x.y, x.z, speed, particles.radius_m[i],
        escaped && !bad_state && !too_fast
            ? "If it fell through an open side, close the walls or enlarge the domain; if it was "
              "thrown out, try a smaller time step (rayleigh_fraction or time_step)."
            : fmt::format("The step of {:.3g} s is too large for these contacts: try half of it "
                          "(time_step or rayleigh_fraction), a softer material, or check for overlaps "
                          "in the initial packing.",
                          dt)));
  }
  throw SimulationError(fmt::format("the simulation became unstable at t = {:.6g} s (step {})", at_time_s, at_step));
}

void Simulation::apply_own_spin_rolling() {
  // EDEM's own-spin rolling, once every other torque on the particle is in (contacts and
  // bonds): the implicit static limit needs them all (RollingOwnSpin).
  const std::size_t n = particles.size();
  const double dt = model_.settings.time_step_s;
  const Vec3* __restrict w = particles.angular_velocity_rad_per_s.data();
  const double* __restrict inv_inertia = particles.inv_inertia.data();
  const double* __restrict resistance = own_spin_resistance_N_m_.data();
  Vec3* __restrict torque = particles.torque_N_m.data();
  const bool audit = !particle_lossy_.empty();
  own_spin_torque_N_m_.resize(audit ? n : 0);
  Vec3* __restrict own_spin_torque = own_spin_torque_N_m_.data();
  LossyActions* __restrict lossy = particle_lossy_.data();
#pragma omp parallel for schedule(static) num_threads(active_threads_) if (n > 4096)
  for (std::size_t p = 0; p < n; ++p) {
    const Vec3 t = resistance[p] > 0.0 ? RollingOwnSpin::torque(w[p], torque[p], resistance[p], inv_inertia[p], dt)
                                       : Vec3{};
    torque[p] += t;
    if (audit) {
      own_spin_torque[p] = t;
      lossy[p].rolling_torque_N_m += t;
    }
  }
}

void Simulation::compute_forces(double slip_time_s) {
  // Heat off, or the energy books not kept, costs nothing: the pair loop is compiled for each.
  const bool books = keeps_energy_audit();
  if (heat_enabled())
    books ? compute_forces_and_heat<true, true>(slip_time_s) : compute_forces_and_heat<true, false>(slip_time_s);
  else
    books ? compute_forces_and_heat<false, true>(slip_time_s) : compute_forces_and_heat<false, false>(slip_time_s);
  if (!bonds_.empty()) apply_bonds(slip_time_s);
  if (model_.contact.any_own_spin()) apply_own_spin_rolling();
  if (!particle_lossy_.empty()) book_end_of_step_losses();
  // The losses and stored energy of contacts and bonds, block by block in order.
  generated_heat_W_ = dissipated_power_W_ = contact_elastic_energy_J_ = spring_source_W_ = 0.0;
  ImpactRecord impact;
  for (const BlockEnergy& e : block_energy_) {
    generated_heat_W_ += e.generated_heat_W;
    dissipated_power_W_ += e.dissipated_W;
    contact_elastic_energy_J_ += e.elastic_J;
    spring_source_W_ += e.spring_source_W;
    impact.merge(e.impact);
  }
  impact.time_s = time_s_;
  fastest_impact_.merge(impact);
  if (halo_) sum_totals_over_ranks();
}

template <bool Heat, bool Audit>
void Simulation::compute_forces_and_heat(double slip_time_s) {
  const int threads = active_threads_;
  const double dt = model_.settings.time_step_s;
  const Vec3 gravity = model_.settings.gravity_m_per_s2;
  const double now = time_s_;
  const std::size_t n_bodies = walls.bodies.size();
  std::uint64_t particle_contacts = 0, wall_contacts = 0;

  // Raw, non-aliasing views of the arrays: the force writes cannot then make the
  // compiler reload every other array's address inside the pair loop.
  const Vec3* __restrict x = particles.position_m.data();
  const Vec3* __restrict v = particles.velocity_m_per_s.data();
  const Vec3* __restrict w = particles.angular_velocity_rad_per_s.data();
  const double* __restrict radius = particles.radius_m.data();
  const double* __restrict mass = particles.mass_kg.data();
  const double* __restrict inv_mass = particles.inv_mass_per_kg.data();
  const double* __restrict inv_inertia = particles.inv_inertia.data();
  const MaterialIndex* __restrict material = particles.material.data();
  Vec3* __restrict force = particles.force_N.data();
  Vec3* __restrict torque = particles.torque_N_m.data();
  Vec3* __restrict history = neighbors_.tangential_history_m.data();
  Vec3* __restrict wall_history = neighbors_.wall_tangential_history_m.data();
  const std::uint32_t* __restrict mesh_triangle = neighbors_.mesh_triangle.data();
  Vec3* __restrict mesh_history = neighbors_.mesh_tangential_history_m.data();
  const WallBody* __restrict bodies = walls.bodies.data();
  const std::uint32_t* __restrict owner_offset = neighbors_.owner_offset.data();
  const std::uint32_t* __restrict owner_entry = neighbors_.owner_entry.data();
  const bool own_spin_rolling = model_.contact.any_own_spin();
  // On one thread each share goes straight to its partner's sum (PartnerSum); on more, to
  // the pair's entry, gathered after the barrier. Both add the same terms in owner order.
  const bool direct = threads == 1;
  const std::size_t n_entries = direct ? 0 : neighbors_.partner.size();
  partner_share_.resize(n_entries);
  partner_touching_.resize(n_entries);
  partner_heat_W_.resize(Heat ? n_entries : 0);
  partner_own_spin_N_m_.resize(own_spin_rolling ? n_entries : 0);
  partner_sum_.resize(direct ? particles.size() : 0);
  PartnerSum* __restrict partner_sum = partner_sum_.data();
  PartnerShare* __restrict share = partner_share_.data();
  double* __restrict share_heat = partner_heat_W_.data();
  double* __restrict share_own_spin = partner_own_spin_N_m_.data();
  std::uint8_t* __restrict touching = partner_touching_.data();
  constexpr std::uint32_t block_size = NeighborList::kOwnerBlock;
  const std::size_t blocks = (particles.size() + block_size - 1) / block_size;
  block_wall_share_.resize(blocks * n_bodies);
  const std::uint32_t* node_begin = wall_node_begin_.data();
  const std::size_t n_nodes = Heat ? node_heat_in_W_.size() : 0;
  block_node_heat_.resize(blocks * n_nodes);
  NodeHeat* __restrict block_node = block_node_heat_.data();
  block_energy_.resize(blocks);
  WallShare* __restrict block_wall = block_wall_share_.data();
  BlockEnergy* __restrict block_energy = block_energy_.data();
  const ContactParameterTable& table = model_.contact;
  const ConductionParameterTable& conduction = model_.conduction;
  const double* __restrict temperature = particles.temperature_K.data();
  const double* __restrict conductivity = particles.conductivity_W_per_mK.data();
  double* __restrict heat = particles.heat_flow_W.data();
  own_spin_resistance_N_m_.resize(particles.size());
  double* __restrict own_spin = own_spin_resistance_N_m_.data();
  // Heat from the contacts' losses (docs/physics.md, "Friction heat and its partition"): the sliding
  // power, or every loss; shared by the partition model.
  const bool generate = Heat && model_.settings.heat.generates_heat();
  const bool all_losses = model_.settings.heat.dissipation_heating;
  const HeatPartitionModel partition = model_.settings.heat.partition;
  const double fixed_wall_share = model_.settings.heat.friction_partition;
  constexpr bool audit = Audit;
  const bool weighted = generate && model_.settings.heat.partition_weighs_bodies();
  if (weighted) fill_partition_weights();
  particle_lossy_.resize(audit ? particles.size() : 0);
  rolling_wall_power_W_.resize(audit ? particles.size() : 0);
  partner_lossy_.resize(audit ? n_entries : 0);
  partner_lossy_sum_.resize(audit && direct ? particles.size() : 0);
  LossyActions* __restrict lossy_sum = partner_lossy_sum_.data();
  LossyActions* __restrict lossy = particle_lossy_.data();
  double* __restrict rolling_wall_power = rolling_wall_power_W_.data();
  LossyActions* __restrict share_lossy = partner_lossy_.data();
  // The wall contacts' share of the end-of-step losses (WallLossShare): with every loss as heat.
  const bool shares_wall_losses = audit && generate && all_losses;
  wall_loss_share_.resize(shares_wall_losses ? particles.size() : 0);
  WallLossShare* __restrict wall_loss_share = wall_loss_share_.data();
  const double* __restrict weight = partition_weight_.data();
  // The particle's share of a wall contact's heat (an adiabatic wall takes none).
  const auto wall_share_of_particle = [&](const WallContactHeat& wh, double weight_i, MaterialIndex wall_material) {
    if (!wh.conducts) return 1.0;
    switch (partition) {
      case HeatPartitionModel::fixed: return fixed_wall_share;
      case HeatPartitionModel::equal: return 0.5;
      default: return heat_share_of_first(weight_i, wall_partition_weight(wh, wall_material));
    }
  };
  // Taken once per pass into a member buffer: no allocation per step.
  wall_contact_heat_.resize(n_nodes);
  for (std::size_t b = 0; Heat && b < n_bodies; ++b)
    for (std::uint32_t node = node_begin[b]; node < node_begin[b + 1]; ++node)
      wall_contact_heat_[node] =
          WallContactHeat::of(model_.wall_thermal[b], wall_thermal_state[b], node - node_begin[b]);
  const WallContactHeat* wall_heat = wall_contact_heat_.data();

  // Under MPI a ghost owner's contacts count only for its partners of this rank: its
  // contacts with ghosts and walls are its own rank's (the lists leave them out), and so
  // are its pairs' energies and counts (each contact is then counted once over the ranks).
  const std::uint8_t* __restrict ghost = ghost_.empty() ? nullptr : ghost_.data();

  // Pass 1, each thread over its owners: every contact's action on the owner is summed
  // here, its share for the partner written to the pair's entry, and wall sums go to
  // the owner's block. Pass 2, after the barrier: each particle gathers its shares as a
  // partner, in owner order (on one thread, summed so in pass 1: PartnerSum). Nothing
  // is summed in an order that depends on the thread count, so neither is the result
  // (docs/architecture.md, "The step and threads").
  // The owners go to the threads in chunks of whole blocks (a block's sums are still one
  // thread's, in owner order). Each thread first takes, in order, the chunks of its own
  // run of owners, the particles the integrator's static loops hand it (their lines stay in
  // its cache), and then the chunks the others have not reached (an owner by the drill or
  // a coarse grain costs many times another, more than the lists' estimate of the work
  // tells). On one thread that is every chunk in order, as the direct sums need.
  constexpr std::uint32_t chunk_size = 4 * block_size;
  const std::uint32_t n_owners = static_cast<std::uint32_t>(particles.size());
  const std::uint32_t chunks = (n_owners + chunk_size - 1) / chunk_size;
  const std::uint32_t run_chunks = (chunks + static_cast<std::uint32_t>(threads) - 1) / static_cast<std::uint32_t>(threads);
  if (next_chunk_count_ < threads) {
    next_chunk_ = std::make_unique<NextChunk[]>(static_cast<std::size_t>(threads));
    next_chunk_count_ = threads;
  }
  NextChunk* next_chunk = next_chunk_.get();
  for (int u = 0; u < threads; ++u) next_chunk[u].chunk = static_cast<std::uint32_t>(u) * run_chunks;
#pragma omp parallel num_threads(threads) reduction(+ : particle_contacts, wall_contacts)
  {
    const int t = omp_get_thread_num();
    const ContactWalk walk(particles, neighbors_, walls);  // the thread's own: its views stay in registers
    MeshTouchFinder& finder = mesh_scratch_[t].finder;
    std::vector<MeshTouch>& touches = mesh_scratch_[t].touches;
    std::vector<char>& touched = mesh_scratch_[t].touched;
    int from = t;  // whose run the thread takes chunks from: its own, then the next ones'

    for (std::uint32_t i = 0, end = 0;; ++i) {
      if (i == end) {  // the thread's next chunk, its blocks cleared
        std::uint32_t chunk = chunks;
        for (int tried = 0; tried < threads; ++tried, from = (from + 1) % threads) {
          const std::uint32_t run_end = std::min(chunks, static_cast<std::uint32_t>(from + 1) * run_chunks);
          const std::uint32_t next =
              next_chunk[static_cast<std::size_t>(from)].chunk.fetch_add(1, std::memory_order_relaxed);
          if (next < run_end) {
            chunk = next;
            break;
          }
        }
        if (chunk >= chunks) break;
        i = chunk * chunk_size;
        end = std::min(n_owners, i + chunk_size);
        for (std::size_t k = i / block_size; k < (end + block_size - 1) / block_size; ++k) {
          std::fill(block_wall + k * n_bodies, block_wall + (k + 1) * n_bodies, WallShare{});
          std::fill(block_node + k * n_nodes, block_node + (k + 1) * n_nodes, NodeHeat{});
          block_energy[k] = BlockEnergy{};
        }
      }
      const bool ghost_i = ghost && ghost[i];
      const std::uint64_t particle_contacts_before = particle_contacts;
      const Vec3 xi = x[i], vi = v[i], wi = w[i];
      const double ri = radius[i], inv_mi = inv_mass[i], inv_ii = inv_inertia[i];
      const MaterialIndex mat_i = material[i];
      Vec3 force_i = gravity * mass[i], torque_i;
      double own_spin_i = 0.0, generated_i = 0.0, dissipated_i = 0.0, elastic_i = 0.0, spring_source_i = 0.0;
      LossyActions lossy_i;
      ImpactRecord impact_i;
      double rolling_wall_power_i = 0.0;
      WallShare* __restrict wall_share = block_wall + (i / block_size) * n_bodies;
      NodeHeat* __restrict node_share = block_node + (i / block_size) * n_nodes;
      if (shares_wall_losses) wall_loss_share[i].clear();
      double heat_i = 0.0, temperature_i = 0.0, conductivity_i = 0.0;
      if constexpr (Heat) {
        temperature_i = temperature[i];
        conductivity_i = conductivity[i];
      }

      for (std::uint32_t k = walk.pairs_begin(i), end_k = walk.pairs_end(i); k < end_k; ++k) {
        const ContactWalk::ListedPair pair = walk.listed_pair(xi, ri, k);
        const std::uint32_t j = pair.j;
        const Vec3& d = pair.d_m;
        const double rj = pair.radius_j_m;
        const double sum_r = pair.radius_sum_m;
        if (pair.apart()) {
          // Most list entries are not touching and already cleared: reading instead of
          // storing keeps their cache lines clean (no write-back).
          if (history[k] != Vec3{}) {
            if constexpr (audit) {  // the spring's energy leaves with it (contact_law.hpp)
              const double dist = std::sqrt(pair.distance2_m2);
              spring_source_i -= opened_spring_energy_J(table(mat_i, material[j]), history[k], ri * rj / sum_r,
                                                        sum_r - dist, dot(vi - v[j], d) / dist, dt) / dt;
            }
            history[k] = {};
          }
          if (!direct && touching[k]) touching[k] = 0;
          continue;
        }
        ++particle_contacts;
        const double dist = std::sqrt(pair.distance2_m2);
        const Vec3 normal = d * (1.0 / dist);
        const double overlap = sum_r - dist;
        const double arm_i = ri - 0.5 * overlap, arm_j = rj - 0.5 * overlap;
        const Vec3 wj = w[j];
        ContactGeometry c;
        c.normal = normal;
        c.overlap_m = overlap;
        c.effective_radius_m = ri * rj / sum_r;
        c.effective_mass_kg = effective_mass_kg(inv_mi + inv_mass[j]);
        c.relative_velocity_m_per_s = vi - v[j] + cross(wi * arm_i + wj * arm_j, normal);
        c.angular_velocity_i_rad_per_s = wi;
        c.angular_velocity_j_rad_per_s = wj;
        c.contact_arm_i_m = arm_i;
        c.contact_arm_j_m = arm_j;
        c.inv_inertia_i = inv_ii;
        c.inv_inertia_j = inv_inertia[j];
        c.time_step_s = dt;
        c.slip_time_s = slip_time_s;
        const MaterialIndex mat_j = material[j];
        const ContactPairParameters& law = table(mat_i, mat_j);
        const ContactForces f = HertzMindlinLaw::evaluate<Audit>(law, c, history[k]);
        if (f.approach_speed_m_per_s > 0.0)
          impact_i.consider(hertz_impact_key(inv_mi + inv_mass[j], c.effective_radius_m,
                                             law.effective_youngs_modulus_Pa, f.approach_speed_m_per_s),
                            f.approach_speed_m_per_s, -1);
        const Vec3 lever = cross(normal, f.tangential_force_on_i_N);
        force_i += f.force_on_i_N;
        torque_i += lever * arm_i + f.rolling_torque_on_i_N_m;
        own_spin_i += f.own_spin_resistance_i_N_m;
        if constexpr (audit) {
          dissipated_i += f.dissipated_power_W;
          elastic_i += f.elastic_energy_J;
          spring_source_i += f.spring_source_W;
          // Damping and friction on i: the force less its elastic normal part.
          const Vec3 lossy_force = f.force_on_i_N + f.elastic_normal_force_N * normal;
          lossy_i.rolling_torque_N_m += f.rolling_torque_on_i_N_m;
          lossy_i.lossy_force_N += lossy_force;
          lossy_i.lossy_torque_N_m += lever * arm_i;
          const LossyActions lossy_j{-f.rolling_torque_on_i_N_m, -lossy_force, lever * arm_j};
          if (direct)
            lossy_sum[j] += lossy_j;
          else
            share_lossy[k] = lossy_j;
        }
        const Vec3 torque_j = lever * arm_j - f.rolling_torque_on_i_N_m;
        double heat_j = 0.0;
        if constexpr (Heat) {
          // Q_ij = G (T_j - T_i), G from contact_conductance_W_per_K (another law per pair).
          const ConductionPairParameters& pair_heat = conduction(mat_i, mat_j);
          const double conductance = contact_conductance_W_per_K(
              pair_heat, pair_heat.pair_conductivity(conductivity_i, conductivity[j]), f.contact_radius_m);
          const double q = conductance * (temperature[j] - temperature_i);
          heat_i += q;
          heat_j = -q;
          if (generate) {
            const double generated = all_losses ? f.dissipated_power_W : f.sliding_power_W;
            const double share_i = weighted ? heat_share_of_first(weight[i], weight[j]) : 0.5;
            generated_i += generated;
            heat_i += share_i * generated;
            heat_j += (1.0 - share_i) * generated;
          }
        }
        if (direct) {
          PartnerSum& sum_j = partner_sum[j];
          sum_j.force_N += -f.force_on_i_N;
          sum_j.torque_N_m += torque_j;
          if constexpr (Heat) sum_j.heat_W += heat_j;
          if (own_spin_rolling) sum_j.own_spin_N_m += f.own_spin_resistance_j_N_m;
          continue;
        }
        share[k] = {-f.force_on_i_N, torque_j};
        if constexpr (Heat) share_heat[k] = heat_j;
        if (own_spin_rolling) share_own_spin[k] = f.own_spin_resistance_j_N_m;
        if (!touching[k]) touching[k] = 1;
      }

      // One particle-wall contact, analytic or mesh: R* = R_i, m* = m_i (DESIGN.md section 2).
      // node: the wall's thermal node (the body's first, or a segment of it).
      const auto touch_wall = [&](const WallTouch& touch) {
        ++wall_contacts;
        const double distance_m = touch.distance_m;
        const Vec3& normal = touch.normal;
        const Vec3& contact_point_m = touch.contact_point_m;
        const MaterialIndex wall_material = touch.material;
        const std::uint32_t body = touch.body;
        const std::uint32_t node = node_begin[body] + touch.segment;
        Vec3& wall_spring = touch.on_mesh ? mesh_history[touch.entry] : wall_history[touch.entry];
        const WallMotion& motion = bodies[body].motion;
        const Vec3 wall_omega = motion.active_at(now) ? motion.angular_velocity_rad_per_s : Vec3{};
        const Vec3 surface_velocity = motion.surface_velocity(contact_point_m, now);
        ContactGeometry c;
        c.normal = normal;
        c.overlap_m = ri - distance_m;
        c.effective_radius_m = ri;
        c.effective_mass_kg = effective_mass_kg(inv_mi);
        c.relative_velocity_m_per_s = vi + cross(wi, normal * distance_m) - surface_velocity;
        c.angular_velocity_i_rad_per_s = wi;
        c.angular_velocity_j_rad_per_s = wall_omega;
        c.contact_arm_i_m = distance_m;
        c.inv_inertia_i = inv_ii;
        c.time_step_s = dt;
        c.slip_time_s = slip_time_s;
        const ContactPairParameters& law = table(mat_i, wall_material);
        const ContactForces f = HertzMindlinLaw::evaluate<Audit>(law, c, wall_spring);
        if (f.approach_speed_m_per_s > 0.0)
          impact_i.consider(hertz_impact_key(inv_mi, ri, law.effective_youngs_modulus_Pa, f.approach_speed_m_per_s),
                            f.approach_speed_m_per_s, static_cast<std::int32_t>(body));
        if constexpr (Heat) {
          const WallContactHeat& wh = wall_heat[node];
          if (wh.conducts) {
            const double q = contact_conductance_W_per_K(conduction(mat_i, wall_material),
                                                         wh.contact_conductivity(conductivity_i), f.contact_radius_m) *
                             (wh.temperature_K - temperature_i);
            heat_i += q;
            node_share[node].conduction_W -= q;
          }
          if (generate) {
            const double generated = all_losses ? f.dissipated_power_W : f.sliding_power_W;
            const double share_i = wall_share_of_particle(wh, weighted ? weight[i] : 1.0, wall_material);
            generated_i += generated;
            heat_i += share_i * generated;
            node_share[node].generated_heat_W += (1.0 - share_i) * generated;
            if (shares_wall_losses && share_i < 1.0)
              wall_loss_share[i].add(node, 1.0 - share_i,
                                     LossyActions{f.rolling_torque_on_i_N_m,
                                                  f.force_on_i_N + f.elastic_normal_force_N * normal,
                                                  cross(normal, f.tangential_force_on_i_N) * distance_m},
                                     dot(f.rolling_torque_on_i_N_m, wall_omega), f.own_spin_resistance_i_N_m);
          }
        }
        force_i += f.force_on_i_N;
        torque_i += cross(normal, f.tangential_force_on_i_N) * distance_m + f.rolling_torque_on_i_N_m;
        // EDEM's own-spin rolling torque is not booked on the wall (its default: the wall
        // torque would depend on the mesh size); the relative-spin one is, as a reaction.
        own_spin_i += f.own_spin_resistance_i_N_m;
        if constexpr (audit) {
          dissipated_i += f.dissipated_power_W;
          elastic_i += f.elastic_energy_J;
          spring_source_i += f.spring_source_W;
          lossy_i.rolling_torque_N_m += f.rolling_torque_on_i_N_m;
          lossy_i.lossy_force_N += f.force_on_i_N + f.elastic_normal_force_N * normal;
          lossy_i.lossy_torque_N_m += cross(normal, f.tangential_force_on_i_N) * distance_m;
          rolling_wall_power_i += dot(f.rolling_torque_on_i_N_m, wall_omega);
          // The wall's work on the particle: its force at the surface's velocity, and the
          // relative-spin rolling torque at the wall's spin (the reaction it feels).
          wall_share[body].power_W += dot(f.force_on_i_N, surface_velocity) + dot(f.rolling_torque_on_i_N_m, wall_omega);
        }
        wall_share[body].force_N -= f.force_on_i_N;
        wall_share[body].torque_N_m +=
            cross(contact_point_m - motion.axis_point_m, -f.force_on_i_N) - f.rolling_torque_on_i_N_m;
      };

      // Analytic walls, then meshes (none for a ghost). A mesh's springs move with its
      // touches across edges before the touches act (carry_mesh_springs).
      walk.walls(
          i, finder, touches, touch_wall,
          [&](std::uint32_t k, const WallPrimitive& wall, const WallProximity& prox) {
            if (wall_history[k] == Vec3{}) return;
            if constexpr (audit) {
              if (prox.candidate) {
                const Vec3 surface = bodies[wall.body].motion.surface_velocity(prox.contact_point_m, now);
                spring_source_i -= opened_spring_energy_J(table(mat_i, wall.material), wall_history[k], ri,
                                                          ri - prox.distance_m, dot(vi - surface, prox.normal), dt) /
                                   dt;
              }
            }
            wall_history[k] = {};
          },
          [&](const MeshWall& mesh, std::uint32_t g, std::uint32_t count, const std::vector<MeshTouch>& found) {
            const RigidPose& pose = bodies[mesh.body].pose;
            carry_mesh_springs(mesh.mesh, mesh_triangle + g, count, found, mesh_history + g, touched,
                               [&]([[maybe_unused]] std::uint32_t e, [[maybe_unused]] const Vec3& cleared_spring) {
                                 if constexpr (audit) {  // what it held leaves with it (as for pairs)
                                   const auto& corners = mesh.mesh.triangles[mesh_triangle[g + e]];
                                   const Vec3 point = closest_point_on_triangle(
                                                          xi, pose.to_world(mesh.mesh.vertices[corners[0]]),
                                                          pose.to_world(mesh.mesh.vertices[corners[1]]),
                                                          pose.to_world(mesh.mesh.vertices[corners[2]]))
                                                          .point_m;
                                   const double distance = norm(point - xi);
                                   if (distance > 0.0) {
                                     const Vec3 surface = bodies[mesh.body].motion.surface_velocity(point, now);
                                     spring_source_i -=
                                         opened_spring_energy_J(table(mat_i, mesh.material), cleared_spring, ri,
                                                                ri - distance,
                                                                dot(vi - surface, (point - xi) / distance), dt) /
                                         dt;
                                   }
                                 }
                               });
          });
      force[i] = force_i;
      torque[i] = torque_i;
      own_spin[i] = own_spin_i;
      if constexpr (Heat) heat[i] = heat_i;
      if (ghost_i) {
        particle_contacts = particle_contacts_before;
        continue;
      }
      BlockEnergy& energy = block_energy[i / block_size];
      energy.generated_heat_W += generated_i;
      energy.dissipated_W += dissipated_i;
      energy.elastic_J += elastic_i;
      energy.spring_source_W += spring_source_i;
      energy.impact.merge(impact_i);
      if constexpr (audit) {
        lossy[i] = lossy_i;
        rolling_wall_power[i] = rolling_wall_power_i;
      }
    }
#pragma omp barrier
#pragma omp for schedule(static)
    for (std::uint32_t j = 0; j < n_owners; ++j) {
      PartnerSum sum_j;
      LossyActions lossy_j;
      if (direct) {  // made in pass 1: taken, and cleared for the next pass
        sum_j = partner_sum[j];
        partner_sum[j] = PartnerSum{};
        if constexpr (audit) {
          lossy_j = lossy_sum[j];
          lossy_sum[j] = LossyActions{};
        }
      } else {
        for (std::uint32_t r = owner_offset[j]; r < owner_offset[j + 1]; ++r) {
          const std::uint32_t k = owner_entry[r];
          if (!touching[k]) continue;
          sum_j.force_N += share[k].force_N;
          sum_j.torque_N_m += share[k].torque_N_m;
          if (own_spin_rolling) sum_j.own_spin_N_m += share_own_spin[k];
          if constexpr (Heat) sum_j.heat_W += share_heat[k];
          if constexpr (audit) lossy_j += share_lossy[k];
        }
      }
      force[j] += sum_j.force_N;
      torque[j] += sum_j.torque_N_m;
      own_spin[j] += sum_j.own_spin_N_m;
      if constexpr (Heat) heat[j] += sum_j.heat_W;
      if constexpr (audit) lossy[j] += lossy_j;
    }
  }

  // The walls' sums, block by block in order.
  for (std::size_t b = 0; b < n_bodies; ++b) {
    WallShare sum;
    for (std::size_t k = 0; k < blocks; ++k) {
      const WallShare& part = block_wall[k * n_bodies + b];
      sum.force_N += part.force_N;
      sum.torque_N_m += part.torque_N_m;
      sum.power_W += part.power_W;
    }
    walls.bodies[b].force_N = sum.force_N;
    walls.bodies[b].torque_N_m = sum.torque_N_m;
    wall_power_W_[b] = sum.power_W;
    if constexpr (Heat) {
      double conduction_W = 0.0, generated_W = 0.0;
      for (std::uint32_t node = node_begin[b]; node < node_begin[b + 1]; ++node) {
        NodeHeat node_sum;
        for (std::size_t k = 0; k < blocks; ++k) {
          node_sum.conduction_W += block_node[k * n_nodes + node].conduction_W;
          node_sum.generated_heat_W += block_node[k * n_nodes + node].generated_heat_W;
        }
        node_heat_in_W_[node] = node_sum.conduction_W + node_sum.generated_heat_W;
        conduction_W += node_sum.conduction_W;
        generated_W += node_sum.generated_heat_W;
      }
      wall_thermal_state[b].heat_flow_to_particles_W = -conduction_W;
      wall_generated_heat_W_[b] = generated_W;
    }
  }
  stats_.particle_contacts = particle_contacts;
  stats_.wall_contacts = wall_contacts;
}

double Simulation::translational_kinetic_energy_J() const {
  ExactSum sum;
  for (std::size_t i = 0; i < particles.size(); ++i)
    if (particles.inv_mass_per_kg[i] > 0.0 && !is_ghost(i))
      sum += 0.5 * particles.mass_kg[i] * norm2(particles.velocity_m_per_s[i]);
  return total_over_ranks(sum);
}

double Simulation::rotational_kinetic_energy_J() const {
  ExactSum sum;
  for (std::size_t i = 0; i < particles.size(); ++i)
    if (particles.inv_inertia[i] > 0.0 && !is_ghost(i))
      sum += 0.5 * norm2(particles.angular_velocity_rad_per_s[i]) / particles.inv_inertia[i];
  return total_over_ranks(sum);
}

double Simulation::gravitational_potential_energy_J() const {
  ExactSum sum;
  for (std::size_t i = 0; i < particles.size(); ++i)
    if (!is_ghost(i)) sum += -particles.mass_kg[i] * dot(model_.settings.gravity_m_per_s2, particles.position_m[i]);
  return total_over_ranks(sum);
}

double Simulation::max_speed_m_per_s() const {
  double largest2 = 0.0;
  for (std::size_t i = 0; i < particles.size(); ++i)
    if (!is_ghost(i)) largest2 = std::max(largest2, norm2(particles.velocity_m_per_s[i]));
  return largest_over_ranks(std::sqrt(largest2));
}

double Simulation::max_overlap_fraction() const {
  double largest = 0.0;
  const NeighborList& nl = neighbors_;
  // Not built for these particles yet (the t = 0 sample after an insertion): search
  // them directly, so that a packing that starts overlapped says so.
  if (nl.offset.size() != particles.size() + 1)
    return largest_over_ranks(deepest_overlap(particles.position_m, particles.radius_m).fraction);
  const ContactWalk walk(particles, nl, walls);
  for (std::uint32_t i = 0; i < particles.size(); ++i) {
    if (is_ghost(i)) continue;  // its own rank has its pairs
    walk.pairs(i, [&](std::uint32_t, const ContactWalk::ListedPair& pair) {
      const double overlap = pair.radius_sum_m - std::sqrt(pair.distance2_m2);
      largest = std::max(largest, overlap / (2.0 * std::min(particles.radius_m[i], pair.radius_j_m)));
    });
  }
  return largest_over_ranks(largest);
}

}  // namespace regodem
