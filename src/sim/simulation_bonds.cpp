// The parallel-bond pass and bond formation (DESIGN.md section 2, "Parallel bonds").
//
// Each step, after the contact pass: every bond is updated on its own (in parallel)
// into its per-bond action, broken bonds act no more, and then every particle gathers
// the actions of its bonds in bond order (the CSR of BondStore): no two threads write
// one particle, and the sums do not depend on the thread count.
#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_set>

#include "contact/parallel_bond_batch.hpp"
#include "sim/contact_walk.hpp"
#include "core/error.hpp"
#include "sim/simulation.hpp"

namespace regodem {

void Simulation::configure_bonds(std::vector<BondParameters> kinds, std::vector<int> kind_of_material_pair) {
  const std::size_t n = model_.materials.size();
  if (kind_of_material_pair.size() != n * n)
    throw InputError(fmt::format("bond kinds given for {} material pairs, expected {}", kind_of_material_pair.size(), n * n));
  for (const BondParameters& p : kinds)
    if (!(p.normal_stiffness_Pa_per_m > 0.0 && p.shear_stiffness_Pa_per_m > 0.0 && p.tensile_strength_Pa > 0.0 &&
          p.shear_strength_Pa > 0.0 && p.radius_multiplier > 0.0 && p.damping_ratio >= 0.0))
      throw InputError(fmt::format(
          "bond parameters must be positive: stiffness {:.4g}, {:.4g} N/m^3, strength {:.4g}, {:.4g} Pa, radius "
          "multiplier {:.4g}, damping ratio {:.4g} (0 or more)",
          p.normal_stiffness_Pa_per_m, p.shear_stiffness_Pa_per_m, p.tensile_strength_Pa, p.shear_strength_Pa,
          p.radius_multiplier, p.damping_ratio));
  for (int k : kind_of_material_pair)
    if (k >= static_cast<int>(kinds.size()))
      throw InputError(fmt::format("bond kind {} of {} does not exist", k, kinds.size()));
  model_.bond_kinds = std::move(kinds);
  model_.bond_kind_of_pair = std::move(kind_of_material_pair);
}

BondCounts Simulation::bond_counts() const {
  BondCounts c = bond_counts_;
  c.intact = bonds_.size();
  if (!halo_) return c;
  // Split: a bond is held by the ranks of both its ends, and counted (and its break
  // recorded) by its first end's; the breaks since the split are each rank's until the
  // next gather.
  std::array<double, 3> mine{0.0, 0.0, 0.0};  // intact, broken in tension, in shear
  for (std::size_t b = 0; b < bonds_.size(); ++b) mine[0] += is_ghost(bonds_.local_i[b]) ? 0.0 : 1.0;
  for (std::size_t e = bond_breaks_at_split_; e < bond_breaks_.size(); ++e)
    mine[bond_breaks_[e].mode == BondBreak::tension ? 1 : 2] += 1.0;
  halo_->sum_in_rank_order(mine);  // counts: exact
  c.intact = static_cast<std::size_t>(mine[0]);
  c.broken_in_tension += static_cast<std::size_t>(mine[1]);
  c.broken_in_shear += static_cast<std::size_t>(mine[2]);
  return c;
}

std::vector<BondBreakEvent> Simulation::take_bond_breaks() {
  // Under MPI only gathered (distributed, each rank holds its own since the split).
  refuse_under_ranks("taking the bond breaks while the particles are split");
  bond_breaks_at_split_ = 0;
  std::vector<BondBreakEvent> taken;
  taken.swap(bond_breaks_);
  return taken;
}

std::size_t Simulation::form_bonds(double gap_fraction, const std::vector<char>& material_allowed,
                                   const std::vector<char>& region_allowed) {
  if (!bonds_configured()) throw InputError("bonds are formed, but no bond kinds are configured");
  refuse_under_ranks("forming bonds while the particles are split (gather them first)");
  if (!(gap_fraction >= 0.0)) throw InputError(fmt::format("the bonding gap must be 0 or more, got {}", gap_fraction));
  // A current list holds every pair closer than R_i + R_j + skin.
  rebuild_neighbors();
  forces_current_ = false;
  const std::size_t n_materials = model_.materials.size();
  auto allowed = [&](std::uint32_t p) {
    const bool material_ok = material_allowed.empty() || material_allowed[particles.material[p]];
    const bool region_ok = region_allowed.empty() ||
                           (particles.region[p] < region_allowed.size() && region_allowed[particles.region[p]]);
    return material_ok && region_ok;
  };
  auto key = [](ParticleId a, ParticleId b) {
    return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
  };
  std::unordered_set<std::uint64_t> existing;
  for (std::size_t b = 0; b < bonds_.size(); ++b) existing.insert(key(bonds_.id_i[b], bonds_.id_j[b]));

  const std::size_t before = bonds_.size();
  const std::size_t n = particles.size();
  // The listed pairs as the contact walk reads them (ContactWalk), here those within the gap.
  const ContactWalk walk(particles, neighbors_, walls);
  for (std::uint32_t i = 0; i < n; ++i) {
    if (!allowed(i)) continue;
    const Vec3 xi = particles.position_m[i];
    const double ri = particles.radius_m[i];
    for (std::uint32_t k = walk.pairs_begin(i); k < walk.pairs_end(i); ++k) {
      const ContactWalk::ListedPair pair = walk.listed_pair(xi, ri, k);
      const std::uint32_t j = pair.j;
      if (!allowed(j)) continue;
      const int bond_kind = model_.bond_kind_of_pair[particles.material[i] * n_materials + particles.material[j]];
      if (bond_kind < 0) continue;
      const double rj = pair.radius_j_m;
      const double gap = gap_fraction * std::min(ri, rj);
      if (gap > model_.settings.neighbor_skin_m)
        throw SimulationError(fmt::format(
            "the bonding gap {:.4g} m ({} x the radius {:.4g} m) is larger than the neighbour skin {:.4g} m, so "
            "pairs that far apart are not all listed: use a smaller gap or a larger neighbor_skin",
            gap, gap_fraction, std::min(ri, rj), model_.settings.neighbor_skin_m));
      if (std::sqrt(pair.distance2_m2) > pair.radius_sum_m + gap) continue;
      if (!existing.insert(key(particles.id[i], particles.id[j])).second) continue;
      const BondParameters& p = model_.bond_kinds[static_cast<std::size_t>(bond_kind)];
      bonds_.add(particles, i, j, static_cast<std::uint16_t>(bond_kind),
                 BondSection::of_radius(p.radius_multiplier * std::min(ri, rj)));
    }
  }
  if (bonds_.refresh_indices(particles) < bonds_.size())
    throw SimulationError("a bond was formed to a particle that is not in the store");
  const std::size_t formed = bonds_.size() - before;
  bond_counts_.formed += formed;

  // Explicit stability of the bond springs: sum over a particle's bonds of k/m (and
  // the rotational stiffness, with the shear spring's lever arm, over its moment of
  // inertia) bounds its highest frequency omega. Velocity Verlet with a damping ratio
  // zeta is stable for omega dt < 2 (sqrt(1 + zeta^2) - zeta); we ask for half of that.
  double worst = 0.0, limit = 1.0;
  std::uint32_t worst_particle = 0;
  for (std::uint32_t q = 0; q < n; ++q) {
    double translational = 0.0, rotational = 0.0;
    for (std::uint32_t e = bonds_.bond_offset[q]; e < bonds_.bond_offset[q + 1]; ++e) {
      const std::uint32_t b = bonds_.bond_entry[e] / 2;
      const BondParameters& p = model_.bond_kinds[bonds_.kind[b]];
      const BondSection& s = bonds_.section[b];
      const double arm = particles.radius_m[q];
      limit = std::min(limit, std::sqrt(1.0 + p.damping_ratio * p.damping_ratio) - p.damping_ratio);
      translational += std::max(p.normal_stiffness_Pa_per_m, p.shear_stiffness_Pa_per_m) * s.area_m2;
      rotational += p.normal_stiffness_Pa_per_m * s.inertia_m4 + p.shear_stiffness_Pa_per_m * s.polar_inertia_m4 +
                    p.shear_stiffness_Pa_per_m * s.area_m2 * arm * arm;
    }
    const double omega2 = std::max(translational * particles.inv_mass_per_kg[q], rotational * particles.inv_inertia[q]);
    if (omega2 > worst) worst = omega2, worst_particle = q;
  }
  const double dt = model_.settings.time_step_s;
  if (std::sqrt(worst) * dt > limit)
    throw SimulationError(fmt::format(
        "the bonds make the time step {:.4g} s unstable: particle {} has a bond frequency of {:.4g} rad/s, which "
        "needs a step below {:.4g} s; use a smaller step, softer bonds or less bond damping",
        dt, particles.id[worst_particle], std::sqrt(worst), limit / std::sqrt(worst)));
  return formed;
}

double Simulation::bond_elastic_energy_J() const {
  // Split over ranks, each bond once: by its first end's rank.
  ExactSum sum;
  for (std::size_t b = 0; b < bonds_.size(); ++b)
    if (!is_ghost(bonds_.local_i[b]))
      sum += regodem::bond_elastic_energy_J(model_.bond_kinds[bonds_.kind[b]], bonds_.section[b], bonds_.loads_of(b));
  return total_over_ranks(sum);
}

void Simulation::apply_bonds(double dt_s) {
  const std::size_t nb = bonds_.size();
  const int threads = active_threads_;
  const Vec3* __restrict x = particles.position_m.data();
  const Vec3* __restrict v = particles.velocity_m_per_s.data();
  const Vec3* __restrict w = particles.angular_velocity_rad_per_s.data();
  const double* __restrict radius = particles.radius_m.data();
  const double* __restrict inv_mass = particles.inv_mass_per_kg.data();
  const double* __restrict inv_inertia = particles.inv_inertia.data();
  const double* __restrict temperature = particles.temperature_K.data();
  const double* __restrict conductivity = particles.conductivity_W_per_mK.data();
  const bool heat = heat_enabled();
  const ConductionPairParameters bond_conduction = geometric_radius_conduction(model_.settings.heat.time_scale_factor);
  int any_broken = 0;

  // Undamped bonds (the paper's, and the default) take their step in batches, a vector
  // of bonds at a time, one bond per lane (parallel_bond_batch.hpp). A lane's result
  // does not depend on the bonds beside it, so neither does the run on the thread count.
  // Damped kinds, and a bond whose spin angle is not small, go through update_bond one
  // bond at a time (the two agree to round-off).
  const bool in_lanes = std::none_of(model_.bond_kinds.begin(), model_.bond_kinds.end(),
                                     [](const BondParameters& p) { return p.damping_ratio > 0.0; });
  constexpr std::size_t batch_size = BondBatch::kBonds;
  const std::size_t batches = (nb + batch_size - 1) / batch_size;

  BondLaneSource source;
  source.position_m = x;
  source.velocity_m_per_s = v;
  source.angular_velocity_rad_per_s = w;
  source.radius_m = radius;
  source.kinds = model_.bond_kinds.data();

#pragma omp parallel num_threads(threads) if (nb > 2048) reduction(max : any_broken)
  {
    BondBatch batch;
#pragma omp for schedule(static)
    for (std::size_t g = 0; g < batches; ++g) {
      const std::size_t first = g * batch_size;
      const int count = static_cast<int>(std::min(batch_size, nb - first));
      if (in_lanes) step_bond_batch(source, bonds_, first, count, dt_s, batch);

      for (int l = 0; l < count; ++l) {
        const std::size_t b = first + static_cast<std::size_t>(l);
        const std::uint32_t i = bonds_.local_i[b], j = bonds_.local_j[b];
        const BondParameters& p = model_.bond_kinds[bonds_.kind[b]];
        const BondSection& section = bonds_.section[b];
        const bool alone = !in_lanes || batch.alone(l);
        const BondLoads loads_before = alone ? bonds_.loads_of(b) : batch.loads_before(l);
        BondAction a;
        if (alone) {
          BondKinematics k;
          k.position_i_m = x[i];
          k.position_j_m = x[j];
          k.velocity_i_m_per_s = v[i];
          k.velocity_j_m_per_s = v[j];
          k.angular_velocity_i_rad_per_s = w[i];
          k.angular_velocity_j_rad_per_s = w[j];
          k.radius_i_m = radius[i];
          k.radius_j_m = radius[j];
          const double inv_m = inv_mass[i] + inv_mass[j], inv_i = inv_inertia[i] + inv_inertia[j];
          Vec3 normal = bonds_.normal_of(b);
          BondLoads loads = loads_before;
          a = update_bond(p, section, bonds_.rest_length_m[b], k, dt_s, inv_m > 0.0 ? 1.0 / inv_m : 0.0,
                          inv_i > 0.0 ? 1.0 / inv_i : 0.0, normal, loads);
          bonds_.set_state(b, normal, loads);
        } else {
          a = batch.action(l);
        }
        const BondLoads loads = bonds_.loads_of(b);
        const BondBreak mode =
            bond_holds(loads, section, p) ? BondBreak::none : bond_failure(bond_stresses(loads, section), p);
        bonds_.broken[b] = static_cast<std::uint8_t>(mode);
        double q = 0.0;
        if (mode != BondBreak::none) {
          // Gone for good: it acts no more, from this step on, and what it stored is lost
          // over this step (docs/physics.md, "Energy audit"). The stretch grew over the step
          // while the pair moved: the energy it had taken is that of mid-step, the mean of
          // before and after (the end alone is one step's work too much).
          a = {};
          a.loss_W = 0.5 *
                     (regodem::bond_elastic_energy_J(p, section, loads_before) +
                      regodem::bond_elastic_energy_J(p, section, loads)) /
                     model_.settings.time_step_s;
          any_broken = 1;
        } else if (heat && p.conducts_heat) {
          // The bond radius as a contact radius: G = 2 k_c R_b S.
          q = contact_conductance_W_per_K(bond_conduction, harmonic_mean(conductivity[i], conductivity[j]),
                                          section.radius_m) *
              (temperature[j] - temperature[i]);
        }
        bonds_.action[b] = a;
        bonds_.heat_to_i_W[b] = q;
      }
    }
  }

  // Each particle sums its own bonds, in bond order.
  const std::size_t n = particles.size();
  Vec3* __restrict force = particles.force_N.data();
  Vec3* __restrict torque = particles.torque_N_m.data();
  double* __restrict heat_flow = particles.heat_flow_W.data();
  const std::uint32_t* __restrict offset = bonds_.bond_offset.data();
  const std::uint32_t* __restrict entry = bonds_.bond_entry.data();
  const BondAction* __restrict action = bonds_.action.data();
  const double* __restrict bond_heat = bonds_.heat_to_i_W.data();
  const std::uint32_t* __restrict local_i = bonds_.local_i.data();
  const std::uint32_t* __restrict local_j = bonds_.local_j.data();
  // Losses go to the contact pass's blocks of particles, each counted at its bond's i;
  // with dissipation heating they heat the two particles by the partition (the contact
  // pass filled the weights).
  const bool losses_heat = heat && model_.settings.heat.dissipation_heating;
  const bool weighted = losses_heat && model_.settings.heat.partition_weighs_bodies();
  const double* __restrict weight = partition_weight_.data();
  BlockEnergy* __restrict block_energy = block_energy_.data();
  constexpr std::uint32_t block_size = NeighborList::kOwnerBlock;
  constexpr std::uint32_t kGatherAhead = BondStore::kEntryPadding;
  // Under MPI a ghost's bonds are its own rank's to sum (and their losses to book).
  const std::uint8_t* __restrict ghost = ghost_.empty() ? nullptr : ghost_.data();
  // The particles in runs of whole blocks (a block's sums are one thread's, in particle
  // order), one a thread, cut where each holds its share of the entries, with a few per
  // particle besides: bonded grains are not spread evenly through the sort order, so runs
  // of equal length left one thread waiting, and blocks dealt out in turn lose the cache
  // the integrator then reads (docs/benchmarks.md, "Each thread keeps its own particles").
  NeighborList::owner_block_runs_by_entries(n, threads, offset, bond_gather_run_);
  const std::vector<std::size_t>& run_begin = bond_gather_run_;
#pragma omp parallel num_threads(threads) if (n > 4096)
  {
    // A smaller team (a few particles: one thread) takes the runs in turn.
    const std::size_t team = static_cast<std::size_t>(omp_get_num_threads());
    for (std::size_t r = static_cast<std::size_t>(omp_get_thread_num()); r + 1 < run_begin.size(); r += team) {
      for (std::size_t q = run_begin[r]; q < run_begin[r + 1]; ++q) {
        if (ghost && ghost[q]) continue;
        Vec3 f, t;
        double h = 0.0, loss = 0.0, generated = 0.0;
        // The actions of the entries a few ahead are asked for early (a bond's j end reads
        // an action far from its neighbours'); the entry list has padding for this.
        for (std::uint32_t e = offset[q]; e < offset[q + 1]; ++e) {
          __builtin_prefetch(&action[entry[e + kGatherAhead] >> 1]);
          const std::uint32_t b = entry[e] >> 1;
          const bool is_i = (entry[e] & 1u) == 0;
          if (is_i) {
            f += action[b].force_on_i_N;
            t += action[b].torque_on_i_N_m;
            h += bond_heat[b];
            loss += action[b].loss_W;
          } else {
            f -= action[b].force_on_i_N;
            t += action[b].torque_on_j_N_m;
            h -= bond_heat[b];
          }
          if (losses_heat && action[b].loss_W != 0.0) {
            const double share_i = weighted ? heat_share_of_first(weight[local_i[b]], weight[local_j[b]]) : 0.5;
            const double mine = (is_i ? share_i : 1.0 - share_i) * action[b].loss_W;
            h += mine;
            generated += mine;
          }
        }
        force[q] += f;
        torque[q] += t;
        if (heat) heat_flow[q] += h;
        if (loss != 0.0 || generated != 0.0) {
          block_energy[q / block_size].dissipated_W += loss;
          block_energy[q / block_size].generated_heat_W += generated;
        }
      }
    }
  }

  if (!any_broken) return;
  for (std::size_t b = 0; b < nb; ++b) {
    if (!bonds_.broken[b]) continue;
    const std::uint32_t i = bonds_.local_i[b], j = bonds_.local_j[b];
    // Under MPI both ends' ranks break it; the first end's records it (counted at the gather).
    if (ghost && ghost[i]) continue;
    const Vec3 n_ij = bonds_.normal_of(b);
    const double length = norm(x[j] - x[i]);
    const BondStresses s = bond_stresses(bonds_.loads_of(b), bonds_.section[b]);
    BondBreakEvent e;
    e.time_s = time_s_;
    e.position_m = x[i] + n_ij * (0.5 * (length + radius[i] - radius[j]));
    e.mode = static_cast<BondBreak>(bonds_.broken[b]);
    e.particle_i = bonds_.id_i[b];
    e.particle_j = bonds_.id_j[b];
    e.tensile_stress_Pa = s.tensile_Pa;
    e.shear_stress_Pa = s.shear_Pa;
    e.sequence = bonds_.sequence[b];
    if (!halo_) (e.mode == BondBreak::tension ? bond_counts_.broken_in_tension : bond_counts_.broken_in_shear)++;
    bond_breaks_.push_back(e);
  }
  bonds_.remove_broken(particles, threads);
}

}  // namespace regodem
