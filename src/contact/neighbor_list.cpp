#include "contact/neighbor_list.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>

#include "geometry/mesh_contact.hpp"

namespace regodem {

CellGrid::CellGrid(const Vec3& min_m, const Vec3& max_m, double min_cell_size_m, double max_cells)
    : origin_m(min_m) {
  const Vec3 extent = max_m - min_m;
  double size = min_cell_size_m;
  while ((extent.x / size) * (extent.y / size) * (extent.z / size) > max_cells) size *= 1.1;
  auto cells_along = [size](double length) { return std::max(1, static_cast<int>(std::floor(length / size))); };
  nx = cells_along(extent.x);
  ny = cells_along(extent.y);
  nz = cells_along(extent.z);
  // Cells at least `size` wide: stretch them to fill the domain exactly.
  cell_size_m = std::max({extent.x / nx, extent.y / ny, extent.z / nz});
}

void CellGrid::coordinates(const Vec3& x, int& ix, int& iy, int& iz) const {
  auto clamp_cell = [this](double coordinate, double origin, int n) {
    const double c = std::floor((coordinate - origin) / cell_size_m);
    if (!(c >= 0.0)) return 0;  // also catches NaN
    return c >= n ? n - 1 : static_cast<int>(c);
  };
  ix = clamp_cell(x.x, origin_m.x, nx);
  iy = clamp_cell(x.y, origin_m.y, ny);
  iz = clamp_cell(x.z, origin_m.z, nz);
}

void NeighborList::save_history(const ParticleStore& particles, int threads) {
  const std::size_t owners = offset.empty() ? 0 : offset.size() - 1;
  saved_begin_.assign(owners + 1, 0);
  if (mesh_offset.size() != offset.size()) mesh_offset.assign(offset.size(), 0);
  // Two passes, each owner's count and then its entries, so that the threads fill one
  // list in owner order.
  const auto kept = [](const Vec3& history_m) { return norm2(history_m) > 0.0; };
#pragma omp parallel for schedule(static) num_threads(threads) if (owners > 4096)
  for (std::size_t i = 0; i < owners; ++i) {
    std::uint32_t count = 0;
    for (std::uint32_t k = offset[i]; k < offset[i + 1]; ++k) count += kept(tangential_history_m[k]);
    for (std::uint32_t k = wall_offset[i]; k < wall_offset[i + 1]; ++k) count += kept(wall_tangential_history_m[k]);
    for (std::uint32_t k = mesh_offset[i]; k < mesh_offset[i + 1]; ++k) count += kept(mesh_tangential_history_m[k]);
    saved_begin_[i + 1] = count;
  }
  for (std::size_t i = 0; i < owners; ++i) saved_begin_[i + 1] += saved_begin_[i];
  saved_.resize(saved_begin_[owners]);
#pragma omp parallel for schedule(static) num_threads(threads) if (owners > 4096)
  for (std::size_t i = 0; i < owners; ++i) {
    SavedContact* out = saved_.data() + saved_begin_[i];
    for (std::uint32_t k = offset[i]; k < offset[i + 1]; ++k)
      if (kept(tangential_history_m[k])) *out++ = {particles.id[partner[k]], kNoWall, tangential_history_m[k]};
    for (std::uint32_t k = wall_offset[i]; k < wall_offset[i + 1]; ++k)
      if (kept(wall_tangential_history_m[k])) *out++ = {0, wall_primitive[k], wall_tangential_history_m[k]};
    for (std::uint32_t k = mesh_offset[i]; k < mesh_offset[i + 1]; ++k)
      if (kept(mesh_tangential_history_m[k]))
        *out++ = {mesh_triangle[k], kMeshWall + mesh_wall[k], mesh_tangential_history_m[k]};
  }
  // Until the particles change, each is its own saved owner (particles inserted since
  // the last build have indices past the saved ones).
  saved_owner_of_.resize(owners);
  for (std::size_t i = 0; i < owners; ++i) saved_owner_of_[i] = static_cast<std::uint32_t>(i);
}

void NeighborList::history_follows_removal(const std::vector<char>& removed) {
  std::size_t kept = 0;
  for (std::size_t i = 0; i < saved_owner_of_.size(); ++i)
    if (i >= removed.size() || !removed[i]) saved_owner_of_[kept++] = saved_owner_of_[i];
  saved_owner_of_.resize(kept);
}

ContactHistoryByOwner NeighborList::saved_history_of_kept(const std::vector<std::uint8_t>& dropped) const {
  ContactHistoryByOwner kept;
  for (std::size_t p = 0; p < dropped.size(); ++p) {  // one flag per particle
    if (dropped[p]) continue;
    if (p < saved_owner_of_.size()) {  // else inserted since the save: no history
      const std::uint32_t owner = saved_owner_of_[p];
      kept.contacts.insert(kept.contacts.end(), saved_.begin() + saved_begin_[owner],
                           saved_.begin() + saved_begin_[owner + 1]);
    }
    kept.begin.push_back(static_cast<std::uint32_t>(kept.contacts.size()));
  }
  return kept;
}

void NeighborList::set_saved_history(ContactHistoryByOwner history) {
  saved_begin_ = std::move(history.begin);
  saved_ = std::move(history.contacts);
  saved_owner_of_.resize(saved_begin_.size() - 1);
  for (std::size_t p = 0; p < saved_owner_of_.size(); ++p) saved_owner_of_[p] = static_cast<std::uint32_t>(p);
}

void NeighborList::restore_history(const ParticleStore& particles, int threads) {
  const std::size_t n = particles.size();
  tangential_history_m.assign(partner.size(), Vec3{});
  wall_tangential_history_m.assign(wall_primitive.size(), Vec3{});
  mesh_tangential_history_m.assign(mesh_triangle.size(), Vec3{});
  if (saved_.empty()) return;
  constexpr std::uint32_t kNone = 0xFFFFFFFFu;
#pragma omp parallel for schedule(static) num_threads(threads) if (n > 4096)
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t before_sort = sort_order_[i];
    const std::uint32_t owner = before_sort < saved_owner_of_.size() ? saved_owner_of_[before_sort] : kNone;
    if (owner == kNone) continue;  // inserted since
    const std::uint32_t begin = saved_begin_[owner], end = saved_begin_[owner + 1];
    for (std::uint32_t s = begin; s < end; ++s) {
      const SavedContact& c = saved_[s];
      if (c.wall == kNoWall) {
        for (std::uint32_t k = offset[i]; k < offset[i + 1]; ++k)
          if (particles.id[partner[k]] == c.partner_id) { tangential_history_m[k] = c.history_m; break; }
      } else if (c.wall >= kMeshWall) {
        for (std::uint32_t k = mesh_offset[i]; k < mesh_offset[i + 1]; ++k)
          if (mesh_wall[k] == c.wall - kMeshWall && mesh_triangle[k] == c.partner_id) {
            mesh_tangential_history_m[k] = c.history_m;
            break;
          }
      } else {
        for (std::uint32_t k = wall_offset[i]; k < wall_offset[i + 1]; ++k)
          if (wall_primitive[k] == c.wall) { wall_tangential_history_m[k] = c.history_m; break; }
      }
    }
  }
}

void NeighborList::rebuild(ParticleStore& particles, const WallSet& walls, const CellGrid& grid,
                           const NeighborSkin& skin, int threads, bool history_saved,
                           std::vector<std::uint8_t>* ghost_flags) {
  if (!history_saved) save_history(particles, threads);
  const std::size_t n = particles.size();

  // Counting sort of the particles by cell: afterwards each cell's particles are the
  // contiguous index range [cell_start_[c], cell_start_[c+1]).
  const std::size_t cells = grid.cell_count();
  cell_of_particle_.resize(n);
  cell_start_.assign(cells + 1, 0);
#pragma omp parallel for schedule(static) num_threads(threads) if (n > 4096)
  for (std::size_t i = 0; i < n; ++i) {
    int ix, iy, iz;
    grid.coordinates(particles.position_m[i], ix, iy, iz);
    cell_of_particle_[i] = grid.index(ix, iy, iz);
  }
  for (std::size_t i = 0; i < n; ++i) ++cell_start_[cell_of_particle_[i] + 1];
  for (std::size_t c = 0; c < cells; ++c) cell_start_[c + 1] += cell_start_[c];
  {
    std::vector<std::uint32_t>& order = sort_order_;
    order.resize(n);
    sort_fill_.assign(cell_start_.begin(), cell_start_.end() - 1);
    for (std::size_t i = 0; i < n; ++i) order[sort_fill_[cell_of_particle_[i]]++] = static_cast<std::uint32_t>(i);
    // By id within a cell (a cell holds a few particles: one insertion pass over the
    // order), so that the order, and every sum over it, depends on the positions and
    // ids alone, not on the order the particles had (a restore, another rank's
    // insertions).
    const std::vector<ParticleId>& ids = particles.id;
    const auto same_cell = [&](std::uint32_t a, std::uint32_t b) { return cell_of_particle_[a] == cell_of_particle_[b]; };
    for (std::size_t a = 1; a < n; ++a)
      for (std::size_t b = a; b > 0 && same_cell(order[b - 1], order[b]) && ids[order[b - 1]] > ids[order[b]]; --b)
        std::swap(order[b - 1], order[b]);
    particles.permute(order, threads);
    if (ghost_flags) {
      std::vector<std::uint8_t> sorted(n);
      for (std::size_t i = 0; i < n; ++i) sorted[i] = (*ghost_flags)[order[i]];
      *ghost_flags = std::move(sorted);
    }
  }
  // 1 for a ghost (null: none); a pair of two ghosts is no pair here.
  const std::uint8_t* const ghost = ghost_flags && !ghost_flags->empty() ? ghost_flags->data() : nullptr;
  const auto both_ghosts = [ghost](std::size_t a, std::size_t b) { return ghost && ghost[a] && ghost[b]; };

  // Each particle's and each wall body's half of the skin (NeighborSkin).
  const double slow_half = 0.5 * skin.skin_m, most_half = slow_half * std::max(1.0, skin.max_half_skin_factor);
  const auto half_for = [&](double step_m) {
    return std::clamp(skin.steps_ahead * step_m, slow_half, most_half);
  };
  slow_half_skin_m_ = slow_half;
  half_skin_m_.resize(n);
  inverse_half_skin2_.resize(n);
  double largest_radius = 0.0, largest_fast_half = slow_half;
#pragma omp parallel for schedule(static) num_threads(threads) if (n > 4096) \
    reduction(max : largest_radius, largest_fast_half)
  for (std::size_t i = 0; i < n; ++i) {
    // The distance covered in the steps ahead at the build's velocity and acceleration,
    // per step (half_for): (|v| + |a| T / 2) dt.
    const double ahead_s = skin.steps_ahead * skin.time_step_s;
    const double acceleration = norm(particles.force_N[i]) * particles.inv_mass_per_kg[i];
    const double h =
        skin.time_step_s > 0.0
            ? half_for((norm(particles.velocity_m_per_s[i]) + 0.5 * acceleration * ahead_s) * skin.time_step_s)
            : slow_half;
    half_skin_m_[i] = h;
    inverse_half_skin2_[i] = 1.0 / (h * h);
    largest_radius = std::max(largest_radius, particles.radius_m[i]);
    largest_fast_half = std::max(largest_fast_half, h);
  }
  std::vector<std::uint32_t> fast;
  for (std::size_t i = 0; i < n; ++i)
    if (half_skin_m_[i] > slow_half) fast.push_back(static_cast<std::uint32_t>(i));
  body_half_skin_m_.assign(walls.bodies.size(), slow_half);
  for (std::size_t b = 0; b < walls.bodies.size() && b < skin.body_step_m.size(); ++b)
    body_half_skin_m_[b] = half_for(skin.body_step_m[b]);

  const auto& x = particles.position_m;
  const auto& radius = particles.radius_m;
  const auto& id = particles.id;
  const std::vector<double>& half = half_skin_m_;
  search_point_.resize(n);
#pragma omp parallel for schedule(static) num_threads(threads) if (n > 4096)
  for (std::size_t i = 0; i < n; ++i) search_point_[i] = {x[i], radius[i]};
  const SearchPoint* const search_point = search_point_.data();
  // Calls visit_run(begin, end) for each run [begin, end) of particles in a row of cells
  // within reach_m of the point (the grid's sorted order: cells contiguous along x).
  const auto for_each_run_near = [&](const CellGrid& g, const Vec3& point, double reach_m, auto&& visit_run) {
    const int reach = static_cast<int>(std::ceil(reach_m / g.cell_size_m));
    int cx, cy, cz;
    g.coordinates(point, cx, cy, cz);
    for (int iz = std::max(0, cz - reach); iz <= std::min(g.nz - 1, cz + reach); ++iz)
      for (int iy = std::max(0, cy - reach); iy <= std::min(g.ny - 1, cy + reach); ++iy) {
        const std::uint32_t row = g.index(0, iy, iz);
        const std::uint32_t c0 = row + static_cast<std::uint32_t>(std::max(0, cx - reach));
        const std::uint32_t c1 = row + static_cast<std::uint32_t>(std::min(g.nx - 1, cx + reach));
        visit_run(cell_start_[c0], cell_start_[c1 + 1]);
      }
  };
  // The same, visit(j) for every particle j of those cells.
  const auto for_each_particle_near = [&](const CellGrid& g, const Vec3& point, double reach_m, auto&& visit) {
    for_each_run_near(g, point, reach_m, [&](std::uint32_t run_begin, std::uint32_t run_end) {
      for (std::uint32_t j = run_begin; j < run_end; ++j) visit(j);
    });
  };
  // Whether the segment between two particles crosses one of the thin walls (a sieve):
  // two particles that can touch through a wall before the next rebuild are both within
  // reach of it, so it is among either one's thin walls.
  const auto blocked_by = [&](const std::vector<std::uint32_t>& thin_walls, std::size_t i, std::size_t j) {
    for (const std::uint32_t w : thin_walls)
      if (segment_crosses_wall(walls.primitives[w], x[i], x[j])) return true;
    return false;
  };
  const auto thin_walls_of = [&](std::size_t i, std::vector<std::uint32_t>& thin_walls) {
    thin_walls.clear();
    for (std::uint32_t w = 0; w < walls.primitives.size(); ++w) {
      const WallPrimitive& wall = walls.primitives[w];
      if (wall.shape == PrimitiveShape::plane) continue;
      const WallProximity p = closest_wall_point(wall, x[i]);
      if (p.candidate && p.distance_m < radius[i] + half[i] + body_half_skin_m_[wall.body]) thin_walls.push_back(w);
    }
  };

  // The pairs whose partner is fast: each fast particle looks for its owners, of any
  // size, as far as its own half reaches. (Slow partners are found by their owners.)
  fast_pairs_.clear();
  {
    std::vector<std::uint32_t> thin_walls;
    for (const std::uint32_t f : fast) {
      thin_walls_of(f, thin_walls);
      const double reach_m = radius[f] + largest_radius + half[f] + largest_fast_half;
      for_each_particle_near(grid, x[f], reach_m, [&](std::uint32_t k) {
        if (k == f || !owns_pair(radius[k], id[k], radius[f], id[f]) || both_ghosts(k, f)) return;
        const double cutoff = radius[k] + radius[f] + half[k] + half[f];
        if (norm2(x[k] - x[f]) < cutoff * cutoff && !blocked_by(thin_walls, f, k)) fast_pairs_.emplace_back(k, f);
      });
    }
    std::sort(fast_pairs_.begin(), fast_pairs_.end());
    fast_pair_offset_.assign(n + 1, 0);
    for (const auto& pair : fast_pairs_) ++fast_pair_offset_[pair.first + 1];
    for (std::size_t i = 0; i < n; ++i) fast_pair_offset_[i + 1] += fast_pair_offset_[i];
  }

  // The owners in chunks, handed out to the threads as they come free (the work per
  // owner varies: a coarse grain searches many more cells, a grain by the drill its
  // mesh); each chunk's lists go to its own buffers, joined in chunk order below.
  const std::size_t chunks = (n + kBuildChunk - 1) / kBuildChunk;
  if (chunk_lists_.size() < chunks) chunk_lists_.resize(chunks);
  offset.assign(n + 1, 0);
  wall_offset.assign(n + 1, 0);
  mesh_offset.assign(n + 1, 0);

#pragma omp parallel num_threads(threads)
  {
    std::vector<std::uint32_t> thin_walls;  // the owner's disk and cylinder walls
    std::vector<std::uint32_t> candidates;
    std::vector<std::uint32_t> near(256);  // the owner's candidates within reach
#pragma omp for schedule(dynamic, 1)
    for (std::size_t chunk = 0; chunk < chunks; ++chunk) {
      const std::size_t begin = chunk * kBuildChunk, end = std::min(n, begin + kBuildChunk);
      ChunkLists& lists = chunk_lists_[chunk];
      std::vector<std::uint32_t>& partners = lists.partners;
      std::vector<std::uint32_t>& wall_hits = lists.walls;
      std::vector<std::uint32_t>& mesh_hits = lists.mesh_walls;
      std::vector<std::uint32_t>& mesh_triangles = lists.mesh_triangles;
      partners.clear();
      wall_hits.clear();
      mesh_hits.clear();
      mesh_triangles.clear();
      for (std::size_t i = begin; i < end; ++i) {
        const double ri = radius[i], hi = half[i];
        const bool ghost_i = ghost && ghost[i];
        // Walls first: a pair that touches through a thin wall (a sieve) is no pair.
        const std::size_t first_wall = wall_hits.size();
        if (ghost_i) {
          thin_walls_of(i, thin_walls);  // they still block its pairs; its wall contacts are its own rank's
        } else {
          thin_walls.clear();
          for (std::uint32_t w = 0; w < walls.primitives.size(); ++w) {
            const WallPrimitive& wall = walls.primitives[w];
            const WallProximity p = closest_wall_point(wall, x[i]);
            if (p.candidate && p.distance_m < ri + hi + body_half_skin_m_[wall.body]) {
              wall_hits.push_back(w);
              if (wall.shape != PrimitiveShape::plane) thin_walls.push_back(w);
            }
          }
        }
        wall_offset[i + 1] = static_cast<std::uint32_t>(wall_hits.size() - first_wall);
        // Mesh triangles within reach, found through each mesh's grid in its reference frame.
        const std::size_t first_mesh_entry = mesh_triangles.size();
        for (std::uint32_t m = 0; !ghost_i && m < walls.meshes.size(); ++m) {
          const MeshWall& mesh = walls.meshes[m];
          const Vec3 local = walls.bodies[mesh.body].pose.to_reference(x[i]);
          const double reach = ri + hi + body_half_skin_m_[mesh.body];
          if (norm2(local - mesh.bounding_centre_m) > (mesh.bounding_radius_m + reach) * (mesh.bounding_radius_m + reach))
            continue;
          mesh.grid.candidates(local, reach, candidates);
          for (const std::uint32_t tri : candidates) {
            const TriangleClosestPoint q =
                closest_point_on_triangle(local, mesh.mesh.corner(tri, 0), mesh.mesh.corner(tri, 1), mesh.mesh.corner(tri, 2));
            if (norm2(q.point_m - local) < reach * reach) {
              mesh_hits.push_back(m);
              mesh_triangles.push_back(tri);
            }
          }
        }
        mesh_offset[i + 1] = static_cast<std::uint32_t>(mesh_triangles.size() - first_mesh_entry);

        // Slow partners no larger than the owner, within R_i + R_j + h_i + skin/2.
        const std::size_t first = partners.size();
        // The distance first, from one record per candidate, and without a branch: about
        // two candidates in three are out of reach, in no order a branch predictor could
        // learn. Those within reach are collected, then sifted.
        const Vec3 xi = x[i];
        std::uint32_t within = 0;
        for_each_run_near(grid, xi, 2.0 * ri + hi + slow_half, [&](std::uint32_t run_begin, std::uint32_t run_end) {
          const std::uint32_t run = run_end - run_begin;
          if (near.size() < within + run) near.resize(2 * (within + run));
          std::uint32_t* __restrict out = near.data();
          for (std::uint32_t j = run_begin; j < run_end; ++j) {
            const SearchPoint& p = search_point[j];
            const double cutoff = ri + p.radius_m + hi + slow_half;
            out[within] = j;
            within += norm2(p.position_m - xi) < cutoff * cutoff ? 1u : 0u;
          }
        });
        for (std::uint32_t c = 0; c < within; ++c) {
          const std::uint32_t j = near[c];
          if (j == i || half[j] > slow_half || !owns_pair(ri, id[i], radius[j], id[j]) || both_ghosts(i, j)) continue;
          if (!blocked_by(thin_walls, i, j)) partners.push_back(j);
        }
        // And the fast ones found above.
        for (std::uint32_t e = fast_pair_offset_[i]; e < fast_pair_offset_[i + 1]; ++e)
          partners.push_back(fast_pairs_[e].second);
        // Deterministic, cache-friendly order within the owner's list.
        std::sort(partners.begin() + static_cast<std::ptrdiff_t>(first), partners.end());
        offset[i + 1] = static_cast<std::uint32_t>(partners.size() - first);
      }
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    offset[i + 1] += offset[i];
    wall_offset[i + 1] += wall_offset[i];
    mesh_offset[i + 1] += mesh_offset[i];
  }
  partner.resize(offset[n]);
  wall_primitive.resize(wall_offset[n]);
  mesh_wall.resize(mesh_offset[n]);
  mesh_triangle.resize(mesh_offset[n]);
#pragma omp parallel for schedule(static) num_threads(threads) if (n > 4096)
  for (std::size_t chunk = 0; chunk < chunks; ++chunk) {
    const std::size_t begin = chunk * kBuildChunk;
    const ChunkLists& lists = chunk_lists_[chunk];
    std::copy(lists.partners.begin(), lists.partners.end(), partner.begin() + offset[begin]);
    std::copy(lists.walls.begin(), lists.walls.end(), wall_primitive.begin() + wall_offset[begin]);
    std::copy(lists.mesh_walls.begin(), lists.mesh_walls.end(), mesh_wall.begin() + mesh_offset[begin]);
    std::copy(lists.mesh_triangles.begin(), lists.mesh_triangles.end(), mesh_triangle.begin() + mesh_offset[begin]);
  }
  restore_history(particles, threads);

  index_partners(n);

  position_at_build_m_ = particles.position_m;
  ++rebuilds_;
}

void NeighborList::owner_block_runs_by_entries(std::size_t n, int threads, const std::uint32_t* offset,
                                               std::vector<std::size_t>& begin) {
  const std::size_t runs = static_cast<std::size_t>(threads < 1 ? 1 : threads);
  begin.assign(runs + 1, n);
  begin[0] = 0;
  constexpr double kPerParticle = 4.0;  // entries' worth of a particle's own loads and stores
  const auto work_before = [&](std::size_t q) { return kPerParticle * static_cast<double>(q) + offset[q] - offset[0]; };
  const double total = work_before(n);
  std::size_t r = 1;
  for (std::size_t end = kOwnerBlock; r < runs; end += kOwnerBlock) {
    const std::size_t at = std::min(n, end);
    while (r < runs && work_before(at) >= total * static_cast<double>(r) / static_cast<double>(runs)) begin[r++] = at;
    if (at == n) break;
  }
}

void NeighborList::index_partners(std::size_t particle_count) {
  owner_offset.assign(particle_count + 1, 0);
  for (const std::uint32_t j : partner) ++owner_offset[j + 1];
  for (std::size_t j = 0; j < particle_count; ++j) owner_offset[j + 1] += owner_offset[j];
  owner_entry.resize(partner.size());
  std::vector<std::uint32_t> fill(owner_offset.begin(), owner_offset.end() - 1);
  for (std::uint32_t k = 0; k < partner.size(); ++k) owner_entry[fill[partner[k]]++] = k;
}

void NeighborList::restore_build_state(BuildState state) {
  position_at_build_m_ = std::move(state.positions_m);
  half_skin_m_ = std::move(state.half_skin_m);
  inverse_half_skin2_.resize(half_skin_m_.size());
  for (std::size_t i = 0; i < half_skin_m_.size(); ++i) inverse_half_skin2_[i] = 1.0 / (half_skin_m_[i] * half_skin_m_[i]);
  body_half_skin_m_ = std::move(state.body_half_skin_m);
  slow_half_skin_m_ = state.slow_half_skin_m;
  rebuilds_ = state.rebuilds;
}

bool NeighborList::needs_rebuild(const ParticleStore& particles, const WallSet& walls, int threads) const {
  const std::size_t n = particles.size();
  if (position_at_build_m_.size() != n || inverse_half_skin2_.size() != n || offset.size() != n + 1) return true;
  double largest = 0.0;
#pragma omp parallel for schedule(static) num_threads(threads) if (n > 4096) reduction(max : largest)
  for (std::size_t i = 0; i < n; ++i)
    largest = std::max(largest, norm2(particles.position_m[i] - position_at_build_m_[i]) * inverse_half_skin2_[i]);
  return needs_rebuild(n, largest, walls);
}

bool NeighborList::needs_rebuild(std::size_t particle_count, double max_displacement_ratio2, const WallSet& walls) const {
  if (position_at_build_m_.size() != particle_count || inverse_half_skin2_.size() != particle_count ||
      offset.size() != particle_count + 1 || body_half_skin_m_.size() != walls.bodies.size())
    return true;
  // A pair closes by at most the two particles' displacements, each within its own half.
  if (max_displacement_ratio2 > 1.0) return true;
  // A wall may use its own half and what every particle has left of its own (at least
  // skin/2 (1 - the largest ratio), each half being at least skin/2).
  const double particles_left_m = slow_half_skin_m_ * (1.0 - std::sqrt(max_displacement_ratio2));
  for (std::size_t b = 0; b < walls.bodies.size(); ++b)
    if (walls.bodies[b].displacement_since_build_m > body_half_skin_m_[b] + particles_left_m) return true;
  return false;
}

}  // namespace regodem
