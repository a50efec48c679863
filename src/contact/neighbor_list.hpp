#pragma once
// Neighbour search: a cell grid plus Verlet lists with a skin (DESIGN.md section 5).
//
// The pair list is a half list in CSR form: each pair is stored once, by its owner,
// the larger particle (the lower id between equals). A particle then searches only
// for slow partners no larger than itself, within 2R + h_i + skin/2 (fast partners find
// their owners; NeighborSkin), so the grid cells can be sized for the smallest
// particles and a 4:1 size mixture costs no more than it must.
// Rebuilding sorts the particles by cell, and by id within a cell (cache locality, and
// an order that depends on the positions and ids alone), and carries the contact
// history (the tangential spring) across, by owner index (followed through the sort)
// and partner id.
//
// The force pass is the same for any thread count: each contact's share for the
// partner is written to its entry, and each particle then gathers them over its
// entries as a partner (`owner_offset`/`owner_entry`, in owner order); wall sums go by
// fixed blocks of owners (kOwnerBlock), which the threads take whole, a few at a time.
#include <cstdint>
#include <utility>
#include <vector>

#include "core/particle_store.hpp"
#include "geometry/wall_set.hpp"

namespace regodem {

struct CellGrid {
  Vec3 origin_m;
  double cell_size_m = 0.0;
  int nx = 1, ny = 1, nz = 1;

  CellGrid() = default;
  /// Cells at least min_cell_size_m wide, and no more than max_cells of them (a sparse
  /// domain then gets larger cells rather than a huge, mostly empty grid).
  CellGrid(const Vec3& min_m, const Vec3& max_m, double min_cell_size_m, double max_cells);
  std::size_t cell_count() const { return static_cast<std::size_t>(nx) * ny * nz; }
  /// Cell coordinates of a point, clamped into the grid.
  void coordinates(const Vec3& x, int& ix, int& iy, int& iz) const;
  std::uint32_t index(int ix, int iy, int iz) const {
    return static_cast<std::uint32_t>((static_cast<std::size_t>(iz) * ny + iy) * nx + ix);
  }
};

/// True when particle i (radius, id) owns the pair with j.
inline bool owns_pair(double radius_i, ParticleId id_i, double radius_j, ParticleId id_j) {
  return radius_i > radius_j || (radius_i == radius_j && id_i < id_j);
}

/// The lists' skin (DESIGN.md section 5), shared out between the two sides of every
/// pair. Each particle has its own half: skin/2, or, when it moves fast, the distance it
/// covers in `steps_ahead` steps from its velocity and its acceleration at the build
/// (|v| T + |a| T^2 / 2 with T those steps: a grain a flute pushes is sped up; at most
/// max_half_skin_factor x skin/2); each wall body likewise from its surface's speed.
/// Ghosts are sent with their force, so that every rank gives a particle the same half. A pair is listed within
/// R_i + R_j + h_i + h_j, a wall within R_i + h_i + h_wall, and the lists hold until a
/// particle has moved more than its own half or a wall more than its own (plus what the
/// particles have left). A few grains thrown by a drill then no longer rebuild the whole
/// list every step or two (docs/benchmarks.md, "The drilling window").
struct NeighborSkin {
  double skin_m = 0.0;
  double time_step_s = 0.0;  // 0: every particle and wall has skin/2
  double steps_ahead = 8.0;
  double max_half_skin_factor = 4.0;
  // Per wall body: its surface's largest displacement in one step (empty: none move).
  std::vector<double> body_step_m;

  NeighborSkin() = default;
  /// A uniform skin: every half is skin/2.
  NeighborSkin(double skin) : skin_m(skin) {}  // NOLINT(google-explicit-constructor)
};

/// One contact's tangential history, keyed so that it outlives the lists' indices: by the
/// partner's id, a wall primitive, or a mesh wall and triangle. Kept by the pair's owner.
struct SavedContact {
  ParticleId partner_id;  // the triangle for a mesh contact
  std::uint32_t wall;     // primitive index, kNoWall for a particle partner, kMeshWall + mesh
  Vec3 history_m;
  static constexpr std::uint32_t kNoWall = 0xFFFFFFFFu;
  static constexpr std::uint32_t kMeshWall = 0x80000000u;
};

/// Contact history by owner: owner p's contacts are contacts[begin[p] .. begin[p+1]).
/// What a particle takes with it to another rank (issue 19).
struct ContactHistoryByOwner {
  std::vector<std::uint32_t> begin{0};
  std::vector<SavedContact> contacts;
  std::size_t owners() const { return begin.size() - 1; }
};

class NeighborList {
 public:
  // Particle pairs: partners of owner i are partner[offset[i] .. offset[i+1]).
  std::vector<std::uint32_t> offset;
  std::vector<std::uint32_t> partner;
  std::vector<Vec3> tangential_history_m;  // one per pair entry
  // Particle-wall pairs, same layout; wall_primitive indexes WallSet::primitives.
  std::vector<std::uint32_t> wall_offset;
  std::vector<std::uint32_t> wall_primitive;
  std::vector<Vec3> wall_tangential_history_m;
  // Particle-mesh-triangle pairs, same layout: the triangles of mesh wall mesh_wall[k]
  // within reach, grouped by mesh and ascending within a mesh (MeshTouchFinder's input).
  std::vector<std::uint32_t> mesh_offset;
  std::vector<std::uint32_t> mesh_wall;
  std::vector<std::uint32_t> mesh_triangle;
  std::vector<Vec3> mesh_tangential_history_m;
  // Each particle's entries as a partner: pair entries owner_entry[owner_offset[j] ..
  // owner_offset[j+1]) have partner j, ascending (so by owner index). Derived from the
  // pair list (index_partners()), not saved.
  std::vector<std::uint32_t> owner_offset;
  std::vector<std::uint32_t> owner_entry;
  // The force pass's blocks of owners: a block's wall sums are one thread's.
  static constexpr std::uint32_t kOwnerBlock = 64;
  /// One thread's share of n particles in whole owner blocks, in order (a loop's
  /// schedule(static, run)): a block's sums stay one thread's, and each thread sums the
  /// run of particles the integrator's static loops then hand it (the lines stay in its
  /// cache; blocks dealt out in turn were slower on the drilling window: docs/benchmarks.md,
  /// "Each thread keeps its own particles").
  static std::size_t owner_block_run(std::size_t n, int threads) {
    const std::size_t blocks = (n + kOwnerBlock - 1) / kOwnerBlock, t = static_cast<std::size_t>(threads < 1 ? 1 : threads);
    return kOwnerBlock * ((blocks + t - 1) / t);
  }
  /// The same runs, one a thread, cut where each holds its share of the work of a loop over
  /// the particles that reads entries [offset[q], offset[q + 1]) of a CSR for particle q
  /// (with a few entries' worth per particle besides): run r is [begin[r], begin[r + 1])
  /// (`begin` is the caller's, so that a pass each step allocates nothing).
  static void owner_block_runs_by_entries(std::size_t n, int threads, const std::uint32_t* offset,
                                          std::vector<std::size_t>& begin);

  /// Sorts the particles by cell, rebuilds both lists and carries the contact history.
  /// history_saved: save_history() was called before the particles changed (removal),
  /// so the old lists no longer index them. ghost: under MPI, one flag per particle for
  /// the copies of other ranks' particles (issue 19); the flags follow the sort, and the
  /// lists leave out what no rank computes here: pairs of two ghosts, and a ghost's walls
  /// and mesh triangles (its own rank's). A ghost still blocks nothing and is blocked by
  /// the thin walls near it, as its own rank sees it.
  void rebuild(ParticleStore& particles, const WallSet& walls, const CellGrid& grid, const NeighborSkin& skin,
               int threads, bool history_saved = false, std::vector<std::uint8_t>* ghost = nullptr);

  /// Builds owner_offset/owner_entry from the pair list (after a build or a restore).
  void index_partners(std::size_t particle_count);

  /// True once some particle has moved more than its half of the skin since the last
  /// build, or a wall more than its own half and what the particles have left.
  bool needs_rebuild(const ParticleStore& particles, const WallSet& walls, int threads) const;
  /// The same decision when the caller already knows the largest of |x_i - x_i,build|^2
  /// over the particles' inverse squared halves (the integrator measures it while it
  /// moves the particles).
  bool needs_rebuild(std::size_t particle_count, double max_displacement_ratio2, const WallSet& walls) const;
  const std::vector<Vec3>& positions_at_build_m() const { return position_at_build_m_; }
  /// 1 / h_i^2 of each particle at the last build.
  const std::vector<double>& inverse_half_skin2() const { return inverse_half_skin2_; }

  std::size_t pair_count() const { return partner.size(); }
  /// For checkpoints: the positions at the last build and the build count, which the
  /// public arrays above do not hold.
  struct BuildState {
    std::vector<Vec3> positions_m;
    std::vector<double> half_skin_m;       // per particle
    std::vector<double> body_half_skin_m;  // per wall body
    double slow_half_skin_m = 0.0;         // skin/2
    std::uint64_t rebuilds = 0;
  };
  BuildState build_state() const {
    return {position_at_build_m_, half_skin_m_, body_half_skin_m_, slow_half_skin_m_, rebuilds_};
  }
  void restore_build_state(BuildState state);
  std::uint64_t rebuild_count() const { return rebuilds_; }
  /// Keeps the contact history of every owner, by its index now and its partners' ids
  /// (rebuild() does it itself unless told it was done before the particles changed).
  void save_history(const ParticleStore& particles, int threads = 1);
  /// After save_history(): the flagged particles are about to be removed (the rest keep
  /// their order), so the saved owners are found again at their new indices.
  void history_follows_removal(const std::vector<char>& removed);
  /// After save_history(): the saved history of the particles not flagged (one flag per
  /// particle), by owner in their order (a distributed run's own particles, before its
  /// ghosts are dropped).
  ContactHistoryByOwner saved_history_of_kept(const std::vector<std::uint8_t>& dropped) const;
  /// Replaces the saved history by `history`, owner p being the particle at index p now
  /// (particles past its owners have none); the next rebuild(..., true) restores it.
  void set_saved_history(ContactHistoryByOwner history);
  /// The last build's sort: the particle now at index i was at index sort_order()[i].
  const std::vector<std::uint32_t>& sort_order() const { return sort_order_; }

 private:
  void restore_history(const ParticleStore& particles, int threads);

  std::vector<Vec3> position_at_build_m_;
  std::vector<double> half_skin_m_, inverse_half_skin2_;  // per particle
  std::vector<double> body_half_skin_m_;                  // per wall body
  double slow_half_skin_m_ = 0.0;
  std::uint64_t rebuilds_ = 0;
  // Pairs whose partner is fast, found before the owners' search: (owner, partner).
  std::vector<std::pair<std::uint32_t, std::uint32_t>> fast_pairs_;
  std::vector<std::uint32_t> fast_pair_offset_;
  // History saved across a rebuild (only entries with a non-zero spring), by owner index
  // at the save; saved_owner_of_[p]: the saved owner of the particle at index p before
  // the build's sort (kNone: none, inserted since). Nothing here is sized by the ids.
  static constexpr std::uint32_t kNoWall = SavedContact::kNoWall;
  static constexpr std::uint32_t kMeshWall = SavedContact::kMeshWall;
  std::vector<std::uint32_t> saved_begin_;  // CSR over the saved owners
  std::vector<std::uint32_t> saved_owner_of_;
  std::vector<SavedContact> saved_;
  // Reused scratch space.
  struct SearchPoint {  // a particle's position and radius side by side, for the pair search
    Vec3 position_m;
    double radius_m;
  };
  std::vector<SearchPoint> search_point_;
  std::vector<std::uint32_t> cell_start_;
  std::vector<std::uint32_t> cell_of_particle_;
  std::vector<std::uint32_t> sort_order_, sort_fill_;
  static constexpr std::size_t kBuildChunk = 256;  // owners per chunk of a build
  struct ChunkLists {  // a chunk's entries while the build runs
    std::vector<std::uint32_t> partners, walls, mesh_walls, mesh_triangles;
  };
  std::vector<ChunkLists> chunk_lists_;
};

/// Calls visit(mesh_wall, begin, end) for each run of particle i's mesh entries that
/// belong to one mesh wall: entries [begin, end) are that wall's triangles.
template <class Visit>
void for_each_mesh_run(const NeighborList& list, std::size_t i, Visit&& visit) {
  const std::uint32_t last = list.mesh_offset[i + 1];
  for (std::uint32_t g = list.mesh_offset[i]; g < last;) {
    std::uint32_t g_end = g + 1;
    while (g_end < last && list.mesh_wall[g_end] == list.mesh_wall[g]) ++g_end;
    visit(list.mesh_wall[g], g, g_end);
    g = g_end;
  }
}

}  // namespace regodem
