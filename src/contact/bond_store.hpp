#pragma once
// The intact parallel bonds as a structure of arrays, keyed by global particle ids
// (particles are re-sorted at every neighbour build), with the local index of each end
// renumbered after each sort (no table sized by the ids), and a per-particle index of
// its bonds (CSR) so that each
// particle gathers its bonds' forces in a fixed order: parallel without races, and
// deterministic for any thread count.
#include <array>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "contact/parallel_bond.hpp"
#include "core/particle_store.hpp"

namespace regodem {

/// One bond broken for good: when, where (the bond centre), how, and its stresses.
struct BondBreakEvent {
  double time_s = 0.0;
  Vec3 position_m;
  BondBreak mode = BondBreak::tension;
  ParticleId particle_i = 0, particle_j = 0;
  double tensile_stress_Pa = 0.0, shear_stress_Pa = 0.0;
  std::uint32_t sequence = 0;  // the bond's (BondStore::sequence): one step's breaks in bond order
};

/// Bond totals for outputs.
struct BondCounts {
  std::uint64_t formed = 0;
  std::uint64_t intact = 0;
  std::uint64_t broken_in_tension = 0;
  std::uint64_t broken_in_shear = 0;
  std::uint64_t broken() const { return broken_in_tension + broken_in_shear; }
};

class BondStore {
 public:
  // Per-bond fields (shape: size()).
  std::vector<ParticleId> id_i, id_j;        // the two ends, global ids
  std::vector<std::uint32_t> local_i, local_j;  // their current indices in the ParticleStore
  std::vector<std::uint16_t> kind;           // index into the bond parameter table
  std::vector<double> rest_length_m;         // L0, the centre distance at formation
  std::vector<BondSection> section;
  // Under MPI: the bond's place in the run's bond list when it was last whole on one rank
  // (numbered by number_in_order() when the run splits; add() and a removal leave it
  // meaningless until then); a rank keeps its bonds in this order, which is one
  // process's, so that each particle sums its bonds as one process does.
  std::vector<std::uint32_t> sequence;
  // The bond's state: the normal n of the last update (from i to j) and the loads, one
  // array per component, so that the bond pass loads and stores a vector of bonds at
  // once (contact/parallel_bond_batch.hpp). Each array holds size() + kStatePadding
  // values: the pass's last vector may reach past the last bond.
  enum StateRow : int {
    normal_x, normal_y, normal_z, normal_force, twist_moment, shear_x, shear_y, shear_z, bend_x, bend_y, bend_z,
    state_rows
  };
  static constexpr std::size_t kStatePadding = bond_kernel::kLanes;
  static constexpr std::uint32_t kEntryPadding = 8;
  std::array<std::vector<double>, state_rows> state;
  // Written by the bond pass, one per bond, then gathered per particle.
  std::vector<BondAction> action;
  std::vector<double> heat_to_i_W;           // conduction through the bond (0 when off)
  std::vector<std::uint8_t> broken;          // BondBreak of this step (none: intact)

  // Bonds of each local particle: entries bond_entry[bond_offset[p] .. bond_offset[p+1]),
  // each 2 b + (0 when p is end i, 1 when end j), in bond order; then kEntryPadding
  // zeros, so that the gather may look that far ahead.
  std::vector<std::uint32_t> bond_offset;
  std::vector<std::uint32_t> bond_entry;

  /// What a per-bond field is to the operations that treat every field alike: a bond's
  /// own value, which goes with it to another rank (and in that order); an end's local
  /// index, found again there; or what the last bond pass wrote.
  enum class FieldRole { travels, local_index, pass_result };
  template <FieldRole R>
  using Role = std::integral_constant<FieldRole, R>;
  /// Calls visit(member, role) for each per-bond field but the state rows (which travel,
  /// after these) and `broken` (a removal's flags): member points at the BondStore
  /// vector, role is a Role<>. A new field listed here (and counted in kFields, which a
  /// static_assert below checks) is taken by every removal, append and transfer between
  /// ranks; add() still gives each travelling field its value at formation, and the local
  /// indices are local_i and local_j alone (refresh_indices, renumber).
  template <class Visit>
  static constexpr void for_each_field(Visit&& visit) {
    constexpr Role<FieldRole::travels> travels;
    constexpr Role<FieldRole::local_index> local_index;
    constexpr Role<FieldRole::pass_result> pass_result;
    visit(&BondStore::id_i, travels);
    visit(&BondStore::id_j, travels);
    visit(&BondStore::local_i, local_index);
    visit(&BondStore::local_j, local_index);
    visit(&BondStore::kind, travels);
    visit(&BondStore::rest_length_m, travels);
    visit(&BondStore::section, travels);
    visit(&BondStore::sequence, travels);
    visit(&BondStore::action, pass_result);
    visit(&BondStore::heat_to_i_W, pass_result);
  }
  static constexpr int kFields = 10;  // for_each_field's (checked below)

  std::size_t size() const { return id_i.size(); }
  bool empty() const { return id_i.empty(); }

  Vec3 normal_of(std::size_t b) const { return {state[normal_x][b], state[normal_y][b], state[normal_z][b]}; }
  BondLoads loads_of(std::size_t b) const {
    return {state[normal_force][b], {state[shear_x][b], state[shear_y][b], state[shear_z][b]},
            state[twist_moment][b], {state[bend_x][b], state[bend_y][b], state[bend_z][b]}};
  }
  void set_state(std::size_t b, const Vec3& normal, const BondLoads& loads);
  /// Sizes the state arrays for `bonds` bonds (and the padding); new values are 0.
  void resize_state(std::size_t bonds);

  /// Appends an unloaded bond between local particles a and b (sizes the scratch fields).
  void add(const ParticleStore& particles, std::uint32_t a, std::uint32_t b, std::uint16_t bond_kind,
           const BondSection& bond_section);
  /// Finds the local indices from the ids (after a restore), and the CSR. Returns the
  /// first bond with an end not among `particles` (then no CSR), or size() when none.
  [[nodiscard]] std::size_t refresh_indices(const ParticleStore& particles);
  /// The particles moved: the one at index p is now at new_index_of_old[p] (a sort, a
  /// removal of particles without bonds). Updates the local indices and the CSR.
  void renumber(const std::vector<std::uint32_t>& new_index_of_old, std::size_t particle_count, int threads = 1);
  /// Removes the bonds flagged broken (keeping the order of the rest) and refreshes the CSR.
  void remove_broken(const ParticleStore& particles, int threads = 1);
  /// Removes the bonds with an end flagged in `removed` (by local index; the particles
  /// are about to be removed), then renumber() for the indices past the removal.
  void remove_with_particles(const ParticleStore& particles, const std::vector<char>& removed);

  // Under MPI (a rank holds the bonds with an end among its own particles).
  /// Numbers the bonds in their order (the store holds the run's whole list).
  void number_in_order();
  /// Keeps the bonds flagged, one of each sequence number, in sequence order. The local
  /// indices are then stale: refresh_indices() finds them.
  void keep_in_sequence_order(const std::vector<char>& keep);
  /// Appends bond b of `from` (what travels: its identity, section and loads; its local
  /// indices unknown until refresh_indices, its pass results zero).
  void append_from(const BondStore& from, std::size_t b);

 private:
  void rebuild_per_particle(std::size_t particle_count);
};

static_assert(
    [] {
      int fields = 0;
      BondStore::for_each_field([&](auto, auto) { ++fields; });
      return fields;
    }() == BondStore::kFields,
    "BondStore::kFields must count for_each_field's fields (remove_broken shares them out by it)");

}  // namespace regodem
