#pragma once
// Neighbour search: a cell grid plus Verlet lists with a skin (DESIGN.md section 5).
//
// The pair list is a half list in CSR form: each pair is stored once, by its owner,
// the larger particle (the lower id between equals). A particle then searches only
// for partners no larger than itself, within 2R + skin, so the grid cells can be sized
// for the smallest particles and a 4:1 size mixture costs no more than it must.
// Rebuilding sorts the particles by cell (cache locality) and carries the contact
// history (the tangential spring) across, keyed by global particle ids.
#include <cstdint>
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
  // Owner ranges for the force pass: thread t handles [thread_begin[t], thread_begin[t+1]).
  std::vector<std::uint32_t> thread_begin;

  /// Sorts the particles by cell, rebuilds both lists and carries the contact history.
  /// history_saved: save_history() was called before the particles changed (removal),
  /// so the old lists no longer index them.
  void rebuild(ParticleStore& particles, const WallSet& walls, const CellGrid& grid, double skin_m,
               int threads, bool history_saved = false);

  /// True once some particle has moved more than half the skin since the last build,
  /// or a particle and a wall may have closed the skin between them.
  bool needs_rebuild(const ParticleStore& particles, const WallSet& walls, double skin_m, int threads) const;
  /// The same decision when the caller already knows the largest particle displacement
  /// since the build (the integrator measures it while it moves the particles).
  bool needs_rebuild(std::size_t particle_count, double max_displacement_m, const WallSet& walls,
                     double skin_m) const;
  const std::vector<Vec3>& positions_at_build_m() const { return position_at_build_m_; }

  std::size_t pair_count() const { return partner.size(); }
  /// For checkpoints: the positions at the last build and the build count, which the
  /// public arrays above do not hold.
  void restore_build_state(std::vector<Vec3> positions_at_build_m, std::uint64_t rebuilds) {
    position_at_build_m_ = std::move(positions_at_build_m);
    rebuilds_ = rebuilds;
  }
  std::uint64_t rebuild_count() const { return rebuilds_; }
  /// Keeps the contact history by global id (rebuild() does it itself unless told it
  /// was done before the particles changed).
  void save_history(const ParticleStore& particles);

 private:
  void restore_history(const ParticleStore& particles, int threads);

  std::vector<Vec3> position_at_build_m_;
  std::uint64_t rebuilds_ = 0;
  // History saved by owner id across a rebuild (only entries with a non-zero spring).
  struct SavedContact {
    ParticleId partner_id;
    std::uint32_t wall;  // primitive index, kNoWall for a particle partner, kMeshWall + mesh
    Vec3 history_m;       // (partner_id is then the triangle)
  };
  static constexpr std::uint32_t kNoWall = 0xFFFFFFFFu;
  static constexpr std::uint32_t kMeshWall = 0x80000000u;
  std::vector<std::uint32_t> saved_begin_;  // by owner id; size next_id + 1
  std::vector<SavedContact> saved_;
  // Reused scratch space.
  std::vector<std::uint32_t> cell_start_;
  std::vector<std::uint32_t> cell_of_particle_;
  std::vector<std::uint32_t> touching_;  // per owner: partners in contact at the build
  std::vector<std::vector<std::uint32_t>> thread_partners_;
  std::vector<std::vector<std::uint32_t>> thread_walls_;
  std::vector<std::vector<std::uint32_t>> thread_mesh_walls_, thread_mesh_triangles_;
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
