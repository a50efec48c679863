#pragma once
// The simulation state and its time step: particles, materials, walls, neighbour
// lists, and the velocity-Verlet integrator around one contact pass per step.
#include <atomic>
#include <cstdint>
#include <exception>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "contact/bond_store.hpp"
#include "contact/contact_parameters.hpp"
#include "contact/neighbor_list.hpp"
#include "core/exact_sum.hpp"
#include "core/material.hpp"
#include "core/particle_store.hpp"
#include "geometry/wall_set.hpp"
#include "sim/energy_audit.hpp"
#include "sim/impact_record.hpp"
#include "sim/particle_halo.hpp"
#include "sim/simulation_model.hpp"
#include "thermal/conduction_parameters.hpp"
#include "thermal/heat_partition.hpp"
#include "thermal/thermal_ledger.hpp"
#include "thermal/thermal_network.hpp"
#include "thermal/thermal_wall.hpp"

namespace regodem {

class Checkpoint;

/// The particles a checkpoint holds, with the names of the materials they index.
struct CheckpointParticles {
  ParticleStore particles;
  std::vector<std::string> material_names;
  double time_s = 0.0;
};
/// Reads them (simulation_checkpoint.cpp); throws CheckpointError.
CheckpointParticles read_checkpoint_particles(const Checkpoint& checkpoint);

/// Contact counts and extremes seen in the last force pass.
struct ContactStatistics {
  std::uint64_t particle_contacts = 0;
  std::uint64_t wall_contacts = 0;
};

class Simulation {
 public:
  /// wall_thermal: one per wall body (adiabatic if empty).
  Simulation(MaterialTable materials, WallSet walls, const SimulationSettings& settings,
             std::vector<ThermalWall> wall_thermal = {});

  /// Advances one time step. Throws SimulationError on a blow-up (non-finite state,
  /// a particle moving more than half its radius in one step) or an escape (unless
  /// settings.lost_particles is `remove`).
  void step();
  void advance(std::uint64_t steps);

  /// Adds particles; forces and neighbour lists are refreshed before the next step.
  void add_particle(const NewParticle& p);
  /// What the run does not change while it steps: settings, materials, their tables, bond kinds.
  const SimulationModel& model() const { return model_; }
  /// Replaces the materials (a stage's overrides of the pair properties, and their
  /// undoing), deriving the model's tables again; forces are found again before the next step.
  void set_materials(MaterialTable materials);
  /// Removes the flagged particles (flags by index) between steps, with their bonds and
  /// contact history; their heat leaves the ledger's reference, as for lost particles.
  void remove_particles(const std::vector<char>& remove_flag);
  /// Changes made from outside a run between steps (the Python module), which keep the
  /// books closed. A particle's velocity and spin: the audit books the change of its
  /// kinetic energy as exchanged, as for an added particle, and the forces are found
  /// again (their damping) before the next step. A particle whose rotation is locked
  /// keeps its spin. Throws InputError for a particle held fixed or a non-finite value.
  void set_particle_velocity(std::size_t i, const Vec3& velocity_m_per_s, const Vec3& angular_velocity_rad_per_s);
  /// A particle's temperature (heat on): the ledger's reference takes the change of its
  /// thermal energy, as it takes an inserted particle's; its k follows, and its peak if
  /// the new value is above it. Throws InputError without heat or for T <= 0 K.
  void set_particle_temperature_K(std::size_t i, double temperature_K);
  /// Moves the clock forward to time_s without moving the particles, the walls along
  /// their motions (in up to 10,000 pieces): `regodem estimate` samples a stage where
  /// its drill will be, on a bed it has built itself. Not for a run.
  void jump_to(double time_s);

  double time_s() const { return time_s_; }
  std::uint64_t step_count() const { return step_; }
  double time_step_s() const { return model_.settings.time_step_s; }
  int threads() const { return model_.settings.threads; }
  /// Threads of the force pass for the current particle count: fewer than threads() when
  /// there are fewer than settings().min_particles_per_thread each (results are the same).
  int force_pass_threads() const;
  const SimulationSettings& settings() const { return model_.settings; }
  const ContactStatistics& contact_statistics() const { return stats_; }
  const NeighborList& neighbor_list() const { return neighbors_; }
  /// Particles removed on leaving the domain (LostParticles::remove), since the start.
  std::uint64_t lost_particle_count() const { return lost_particle_count_; }

  // Measurements over all particles (each a pass over the arrays; under MPI over every
  // rank's own particles, a collective that every rank calls).
  double translational_kinetic_energy_J() const;
  double rotational_kinetic_energy_J() const;
  double gravitational_potential_energy_J() const;  // -sum m g.x
  double max_speed_m_per_s() const;
  /// Largest particle-particle overlap divided by the smaller diameter of the pair.
  double max_overlap_fraction() const;

  // Heat (DESIGN.md section 2; simulation_heat.cpp).
  bool heat_enabled() const { return model_.settings.heat.enabled; }
  /// Sum of m_i h_i(T_i) over particles (h = integral of c from 0 K) plus C_w T_w of lumped walls.
  double thermal_energy_J() const;
  const ThermalLedger& thermal_ledger() const { return ledger_; }
  /// Whether the mechanical energy books are kept: settings().energy_audit, or dissipation
  /// heating, which needs the losses.
  bool keeps_energy_audit() const {
    return model_.settings.energy_audit || (heat_enabled() && model_.settings.heat.dissipation_heating);
  }
  /// The mechanical energy books (sim/energy_audit.hpp), kept whether heat is on or not.
  const EnergyAudit& energy_audit() const { return audit_; }
  /// The fastest impact of any contact so far, against the step (sim/impact_record.hpp).
  const ImpactRecord& fastest_impact() const { return fastest_impact_; }
  /// Elastic energy stored now: the contacts' springs (at the last contact pass) and the bonds.
  double elastic_energy_J() const;
  /// Kinetic, potential and elastic energy now: what the audit balances.
  double mechanical_energy_J() const;
  /// mechanical_energy_J() minus what the audit expects: the integrator's error in a correct run.
  double mechanical_imbalance_J() const { return mechanical_energy_J() - audit_.expected_energy_J(); }
  /// Work done by each wall body on the particles so far (J), index for index with walls.bodies.
  const std::vector<double>& wall_work_J() const { return audit_.wall_work_by_body_J; }
  /// thermal_energy_J() minus what the ledger expects: round-off in a correct run.
  double energy_imbalance_J() const { return thermal_energy_J() - ledger_.expected_energy_J(); }
  /// The conduction network of the current contacts: nodes are the particles (by index)
  /// then the lumped walls; boundaries are the fixed walls. The maps give each wall
  /// body's node or boundary index (-1 where it has none).
  ThermalNetwork thermal_network(std::vector<int>& wall_node, std::vector<int>& wall_boundary);
  /// Explicit stability limit of the heat step, min C_i / sum G_i over the network's
  /// nodes at the current contacts (+inf when nothing conducts).
  double thermal_stability_limit_s();
  /// Static-bed stages: moves the clock by dt with the mechanics frozen, after the
  /// caller advanced the temperatures; fixed walls take their prescribed value at the
  /// new time and the ledger books the boundary heat (J per wall body) of the step.
  void advance_frozen(double dt_s, const std::vector<double>& boundary_heat_in_by_body_J);
  /// Re-reads k of every particle from its material at its temperature.
  void refresh_conductivities();

  // Parallel bonds (DESIGN.md section 2; simulation_bonds.cpp).
  /// The bond kinds and, per material pair (a * materials + b, symmetric), the kind
  /// that bonds them or -1. Bonds form only by form_bonds().
  void configure_bonds(std::vector<BondParameters> kinds, std::vector<int> kind_of_material_pair);
  bool bonds_configured() const { return !model_.bond_kinds.empty(); }
  /// Bonds every pair of particles closer than R_i + R_j + gap min(R_i, R_j) whose
  /// materials have a bond kind, both allowed by `materials` and `regions` (flags by
  /// material index and region tag; empty: all), and not bonded yet. Returns the number
  /// formed. Throws SimulationError if the gap exceeds the neighbour skin or the bonds
  /// would make the time step unstable.
  std::size_t form_bonds(double gap_fraction, const std::vector<char>& materials = {},
                         const std::vector<char>& regions = {});
  const BondStore& bonds() const { return bonds_; }
  BondCounts bond_counts() const;
  /// The bonds broken since the last call, in the order they broke.
  std::vector<BondBreakEvent> take_bond_breaks();
  bool bond_breaks_pending() const { return !bond_breaks_.empty(); }

  // Checkpoints (simulation_checkpoint.cpp; docs/checkpoint-format.md): every piece of
  // state a step reads, the neighbour lists included, so that a restored simulation
  // steps on bit for bit as the saved one does (on any thread count).
  void save_state(Checkpoint& checkpoint) const;
  /// Restores save_state() into a simulation built from the same scenario. Throws
  /// CheckpointError when the checkpoint does not fit it (other walls, particle fields).
  /// Another thread count goes on bit for bit (the owners are only split otherwise).
  void restore_state(const Checkpoint& checkpoint);
  /// A new run's start from another run's checkpoint: its particles, their temperatures,
  /// contact history between particles, and bonds (simulation_checkpoint.cpp).
  /// `material_of_saved`: this run's material index for each saved one.
  /// With a temperature, every adopted particle starts at it (a bed built without heat),
  /// its thermal history from there.
  void adopt_particles(const Checkpoint& checkpoint, const std::vector<MaterialIndex>& material_of_saved,
                       std::optional<double> temperature_K = std::nullopt);

  // A run split over MPI ranks (issue 19; sim/particle_halo.hpp).
  /// From the next step this simulation steps the particles of one rank, and `halo`
  /// (which must outlive it) brings the other ranks' particles near them: the lists are
  /// rebuilt on every rank at once, and at each build the particles move to the rank of
  /// their brick. What each rank's particles do is then bit for bit what they do in one
  /// process. Adding or removing particles and setting a velocity between steps are not
  /// yet over ranks (InputError). The walls' forces, torques, power and heat and the contact totals of each
  /// pass are summed over the ranks (in rank order: within round-off of one process's).
  /// Bonds travel with their ends (a bond across two ranks is held by both). The fastest impact
  /// is each rank's until gather_everywhere() or merge_fastest_impact_over_ranks() merges
  /// them; a run adds particles and books the ledgers' reference energies while gathered,
  /// and measures split (each rank's own particles, the sums merged: merge_over_ranks).
  void distribute(ParticleHalo* halo);
  /// The particles this simulation steps (all of them in one process).
  std::size_t own_particle_count() const;
  /// Each particle's work in a step, for cutting the domain over ranks: 1 for itself and
  /// 1 for each neighbour-list entry it is in, as owner or as partner.
  std::vector<double> particle_work() const;
  /// Whether the particle at index i is another rank's (a ghost).
  bool is_ghost(std::size_t i) const { return !ghost_.empty() && ghost_[i] != 0; }
  /// What the lists' skin adds, at most, to the two radii of a pair they list: a rank
  /// wants another's particle as a ghost within its radius, the largest of one of the
  /// brick's size bands and this of that band's centres (GhostReach).
  double ghost_skin_m() const;
  /// A run over MPI whose every rank built this simulation the same (the same particles):
  /// it starts gathered (gather_everywhere), and its first step splits it (`halo` made
  /// with HaloExchange::Start::replicated, outliving this). The same refusals as distribute().
  void start_gathered(ParticleHalo* halo);
  /// Whether this simulation steps one rank's particles (distributed, not gathered).
  bool distributed() const { return halo_ != nullptr; }
  /// Whether it belongs to a run over MPI ranks, distributed or gathered.
  bool over_ranks() const { return halo_ != nullptr || gathered_halo_ != nullptr; }
  /// Between steps under MPI: every rank then holds all particles of the run, in id order,
  /// with every field and their contact history, the lists rebuilt for them, and the
  /// fastest impact of any rank; until distribute_again() this simulation is one process's
  /// (the same on every rank): what reads or changes the particles between steps
  /// (insertion, snapshots, checkpoints, a static-bed stage) sees the whole run.
  /// Nothing when not distributed.
  void gather_everywhere();
  /// After gather_everywhere(): the next step splits the particles again (each rank keeps
  /// those of its brick, and nothing is sent). Nothing when not gathered.
  void distribute_again();
  /// The run's particle count: when distributed, every rank's own particles at the last
  /// build (particles are added or removed only between steps, gathered).
  std::size_t run_particle_count() const;
  /// Under MPI, `mine` or-ed over the ranks (decisions a rank's clock or a signal makes,
  /// which every rank must take at the same step); `mine` in one process.
  std::uint32_t bits_over_ranks(std::uint32_t mine) const;
  /// The particles a measurement leaves out: when distributed, the ghosts (one flag per
  /// particle; their own ranks count them); empty otherwise.
  std::span<const std::uint8_t> left_out() const {
    return halo_ ? std::span<const std::uint8_t>(ghost_) : std::span<const std::uint8_t>();
  }
  /// When distributed, replaces each of this rank's partial sums (a region's, a profile
  /// bin's: ExactSum, TemperatureAccumulator, ThermalHistorySums) by the merge of every
  /// rank's, the same bits on every rank and as one process's (the sums are exact).
  /// Nothing otherwise. Every rank must call it at the same point of the run.
  template <class Partial>
  void merge_over_ranks(std::span<Partial> partials) const {
    if (!halo_) return;
    std::vector<double> mine;
    for (const Partial& p : partials) p.append_to(mine);
    const std::vector<double> every = halo_->values_of_every_rank(mine);  // rank after rank
    for (Partial& p : partials) p = Partial{};
    for (std::size_t at = 0; at < every.size();)
      for (Partial& p : partials) p.merge(Partial::read_from(every, at));
  }
  /// When distributed, the fastest impact of any rank (the larger key; on a tie the lowest
  /// rank's) becomes every rank's, as at a gather. Every rank must call it at once.
  void merge_fastest_impact_over_ranks();

  ParticleStore particles;
  WallSet walls;
  // Each wall body's temperatures and heat books, index for index with walls.bodies (what
  // each is thermally: model().wall_thermal).
  std::vector<ThermalWallState> wall_thermal_state;

 private:
  void ensure_forces();
  /// history_saved: the contact history was already saved by id (after a removal).
  void rebuild_neighbors(bool history_saved = false);
  /// Whether the lists must be rebuilt, given this rank's answer (every rank's, under MPI,
  /// where an error met here or on another rank is thrown on all).
  bool rebuild_everywhere(bool here, const std::exception_ptr& failed = nullptr);
  /// Under MPI, at a build: drops the ghosts (and, lost_particles: remove, its own
  /// particles outside the domain, from every rank's books), and lets the halo move
  /// particles and bring new ghosts, each with the contact history it owns.
  void redistribute_particles();
  /// Throws InputError under MPI: `what` changes one rank's particles between steps, and
  /// the next step's decisions would then not be every rank's (not yet over ranks).
  void refuse_under_ranks(const char* what) const;
  /// Under MPI, at a build with lost_particles: remove: flags this rank's particles outside
  /// the domain as gone and takes every rank's lost particles, and their bonds, out of
  /// every rank's books and bond list.
  void drop_lost_over_ranks();
  /// Under MPI, at a gather: every rank's bond breaks since the split, in one order, counted.
  void gather_bond_breaks();
  /// Under MPI, after a contact pass: the walls' forces, torques, power and heat and the
  /// contacts' totals, each rank's own, summed over the ranks.
  void sum_totals_over_ranks();
  /// The exact sum, or the largest value, over the ranks; this rank's in one process.
  double total_over_ranks(ExactSum mine) const;
  double largest_over_ranks(double mine) const;
  /// Removes the particles outside the domain, their bonds and contact history.
  void remove_lost_particles();
  /// Removes the flagged particles, their bonds and contact history; rebuilds the lists.
  void drop_particles(const std::vector<char>& flags);
  /// slip_time_s: dt after a step, 0 when re-evaluating an unchanged state.
  void compute_forces(double slip_time_s);
  void apply_own_spin_rolling();  // after every other torque: its static limit needs them
  /// Returns the largest squared displacement since the last neighbour build over the
  /// particle's squared half of the skin (NeighborSkin; above 1: rebuild).
  double first_half_kick_and_drift();
  void second_half_kick();
  template <bool Heat, bool Audit>
  void compute_forces_and_heat(double slip_time_s);
  /// Advances particle and wall temperatures by dt with the heat flows of the last pass.
  void update_temperatures(double dt_s);
  /// Each particle's weight in the heat partition, at its temperature (heat_partition.hpp).
  void fill_partition_weights();
  /// A wall's weight, from its material at the wall's temperature (its own contact conductivity
  /// where the material has none).
  double wall_partition_weight(const WallContactHeat& wall, MaterialIndex wall_material) const;
  double particle_thermal_energy_J(std::size_t i) const;
  /// Adds the bonds' forces, torques and heat to the particles (after the contact
  /// pass); dt_s = 0 re-evaluates the stored loads without advancing them.
  void apply_bonds(double dt_s);
  /// The losses that need the velocities the step ends with (velocity Verlet's v + F dt/2m,
  /// known once the bonds have added their forces): each particle's rolling torques at its
  /// end-of-step spin, and the end-of-step correction of its contacts' damping and friction
  /// work, which the contact pass takes at the half-step velocities.
  void book_end_of_step_losses();
  /// Books the last pass's wall power and losses over dt_s into the audit.
  void book_mechanical_energy(double dt_s);
  /// Kinetic and potential energy of one particle (what insertion brings, a loss takes).
  double particle_mechanical_energy_J(std::size_t i) const;
  /// The bonds' stored elastic energy (their loads; docs/physics.md, "Energy audit").
  double bond_elastic_energy_J() const;
  [[noreturn]] void report_blow_up(const std::string& what, double at_time_s, std::uint64_t at_step) const;

  SimulationModel model_;
  ThermalLedger ledger_;
  EnergyAudit audit_;
  // An old checkpoint held no audit: the contact springs' energy joins it at the next pass.
  bool audit_awaits_contact_elastic_ = false;
  NeighborList neighbors_;
  CellGrid grid_;
  double time_s_ = 0.0;
  std::uint64_t step_ = 0;
  std::uint64_t lost_particle_count_ = 0;
  bool forces_current_ = false;
  int active_threads_ = 1;  // threads of the force pass, set at each neighbour build
  ContactStatistics stats_;

  // The force pass's fixed-order sums (compute_forces_and_heat): per pair entry, the
  // contact's action on the partner (valid where partner_touching_ is 1), gathered by
  // each partner in owner order; per block of owners and wall body, the walls' sums.
  struct PartnerShare {
    Vec3 force_N, torque_N_m;
  };
  std::vector<PartnerShare> partner_share_;
  std::vector<double> partner_heat_W_, partner_own_spin_N_m_;  // only with heat, own-spin rolling
  std::vector<std::uint8_t> partner_touching_;
  // On one thread the owners are visited in ascending order, the order each partner's
  // gather reads its entries in: each contact then adds its share straight to its
  // partner's sum (one 64-byte record per particle), the gather's additions in the
  // gather's order, without the per-entry records and the gather's jumps through them.
  // (Summing straight where a partner's owners all lie in one chunk of one thread was
  // tried for more threads: a quarter of the partners qualify, and it was no faster.)
  struct PartnerSum {
    Vec3 force_N, torque_N_m;
    double heat_W = 0.0, own_spin_N_m = 0.0;
  };
  std::vector<PartnerSum> partner_sum_;
  // Per thread, the next chunk of its own run of owners in the force pass, a cache line
  // each (taken by it first, then by the others once theirs are done).
  struct alignas(64) NextChunk {
    std::atomic<std::uint32_t> chunk{0};
  };
  std::unique_ptr<NextChunk[]> next_chunk_;
  int next_chunk_count_ = 0;
  // The bonds' gather: where each thread's run of particles begins (NeighborList::owner_block_runs_by_entries).
  std::vector<std::size_t> bond_gather_run_;
  struct WallShare {
    Vec3 force_N, torque_N_m;
    double power_W = 0.0;  // the wall's work on the particles per unit time
  };
  std::vector<WallShare> block_wall_share_;  // blocks x wall bodies
  struct NodeHeat {  // per thermal node of the walls (a body, or a segment of one)
    double conduction_W = 0.0, generated_heat_W = 0.0;
  };
  std::vector<NodeHeat> block_node_heat_;  // blocks x wall nodes
  struct BlockEnergy {  // per block of owners, summed in order
    double generated_heat_W = 0.0, dissipated_W = 0.0, elastic_J = 0.0, spring_source_W = 0.0;
    ImpactRecord impact;  // the block's fastest impact this pass
  };
  std::vector<BlockEnergy> block_energy_;
  // With the audit, per particle: the rolling torques on it (both models), the lossy forces
  // on it (normal damping and the tangential force) and their torques, and what the walls'
  // spins put into its rolling torques (tau . omega_wall); per pair entry, the partner's.
  struct LossyActions {
    Vec3 rolling_torque_N_m, lossy_force_N, lossy_torque_N_m;
    LossyActions& operator+=(const LossyActions& o) {
      rolling_torque_N_m += o.rolling_torque_N_m;
      lossy_force_N += o.lossy_force_N;
      lossy_torque_N_m += o.lossy_torque_N_m;
      return *this;
    }
  };
  std::vector<LossyActions> particle_lossy_, partner_lossy_, partner_lossy_sum_;
  std::vector<double> rolling_wall_power_W_;
  // With dissipation heating, per particle: its contacts with walls that take heat, each's
  // lossy actions weighted by the wall's share 1 - s of the heat, in up to two wall nodes
  // (a third node joins the second). The end-of-step part of their loss is then shared as
  // the contact pass shares the rest (book_end_of_step_losses), not left to the particle.
  struct WallLossShare {
    static constexpr std::uint32_t no_node = 0xffffffffu;
    std::uint32_t node[2] = {no_node, no_node};
    LossyActions actions[2];
    double rolling_wall_power_W[2] = {0.0, 0.0};
    double own_spin_resistance_N_m[2] = {0.0, 0.0};  // sum of (1 - s) mu_r F_n R_i
    /// Forgets the last pass: a slot's sums are zeroed when a node first takes it, so a
    /// particle without wall contacts costs two stores a pass.
    void clear() { node[0] = node[1] = no_node; }
    void add(std::uint32_t at_node, double wall_share, const LossyActions& a, double rolling_power_W,
             double own_spin_N_m) {
      const int slot = node[0] == no_node || node[0] == at_node ? 0 : 1;
      if (node[slot] == no_node) {
        node[slot] = at_node;
        actions[slot] = LossyActions{};
        rolling_wall_power_W[slot] = own_spin_resistance_N_m[slot] = 0.0;
      }
      actions[slot] += LossyActions{a.rolling_torque_N_m * wall_share, a.lossy_force_N * wall_share,
                                    a.lossy_torque_N_m * wall_share};
      rolling_wall_power_W[slot] += wall_share * rolling_power_W;
      own_spin_resistance_N_m[slot] += wall_share * own_spin_N_m;
    }
  };
  std::vector<WallLossShare> wall_loss_share_;
  std::vector<double> block_node_end_of_step_W_;  // blocks x wall nodes
  // Per particle, with a partition by conductivity or effusivity: its weight (heat_partition.hpp).
  std::vector<double> partition_weight_;
  // Per particle, each contact pass: the summed own-spin rolling resistance (RollingOwnSpin).
  std::vector<double> own_spin_resistance_N_m_;
  std::vector<Vec3> own_spin_torque_N_m_;  // its rolling torque, kept for the audit
  struct MeshScratch {  // per thread
    MeshTouchFinder finder;
    std::vector<MeshTouch> touches;
    std::vector<char> touched;
  };
  std::vector<MeshScratch> mesh_scratch_;
  // The last pass's sums (contacts, then the bonds' and the rolling torques' additions).
  std::vector<double> wall_generated_heat_W_;  // per wall body: generated heat the wall takes
  // The walls' thermal nodes: body b's are [wall_node_begin_[b], wall_node_begin_[b + 1])
  // (one, or a segmented wall's segments); per node, the heat its contacts put in.
  std::vector<std::uint32_t> wall_node_begin_;
  std::vector<double> node_heat_in_W_;
  std::vector<double> wall_power_W_;           // per wall body: its power into the particles
  double generated_heat_W_ = 0.0;              // heat generated at all contacts and bonds
  double dissipated_power_W_ = 0.0;            // every loss, heat on or off
  ImpactRecord fastest_impact_;
  double contact_elastic_energy_J_ = 0.0;      // stored in the contacts' springs
  double spring_source_W_ = 0.0;            // the tangential springs' own source (EnergyAudit)
  std::vector<WallContactHeat> wall_contact_heat_;  // per wall node, taken at each contact pass

  ParticleHalo* halo_ = nullptr;         // under MPI only
  ParticleHalo* gathered_halo_ = nullptr;  // under MPI, between gather_everywhere and distribute_again
  std::size_t run_particles_ = 0;         // distributed: every rank's own, at the last build
  bool every_rank_holds_all_ = false;     // distributed again since a gather, not yet built
  bool halo_build_pending_ = false;       // distributed since the last build
  std::vector<std::uint8_t> ghost_;       // per particle under MPI, else empty
  // Under MPI, between a build's saving of the contact history and its new lists (set
  // while a build that failed part way leaves the lists not matching the particles).
  bool lists_outdated_ = false;

  BondStore bonds_;
  BondCounts bond_counts_;
  std::vector<BondBreakEvent> bond_breaks_;  // not yet taken
  std::size_t bond_breaks_at_split_ = 0;     // under MPI: those from before the split
};

}  // namespace regodem
