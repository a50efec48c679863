#include "geometry/mesh_grid.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"

namespace regodem {
namespace {

bool finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

double mean_edge_length(const TriangleMesh& mesh) {
  if (mesh.triangles.empty()) return 0.0;
  double sum = 0.0;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
    for (int k = 0; k < 3; ++k) sum += norm(mesh.corner(t, (k + 1) % 3) - mesh.corner(t, k));
  return sum / (3.0 * static_cast<double>(mesh.triangle_count()));
}

double cells_for(const Vec3& extent_m, double h) {
  double cells = 1.0;
  for (int a = 0; a < 3; ++a) cells *= std::max(1.0, std::ceil(extent_m[a] / h));
  return cells;
}

}  // namespace

// ---------------------------------------------------------------------------------
MeshGrid::MeshGrid(const TriangleMesh& mesh, double cell_size_m, std::size_t max_cells)
    : triangle_count_(mesh.triangle_count()) {
  if (std::isnan(cell_size_m) || std::isinf(cell_size_m))
    throw InputError(fmt::format("mesh grid: the cell size {} is not finite", cell_size_m));
  if (max_cells == 0) throw InputError("mesh grid: the cell cap must be at least one cell");
  for (const Vec3& v : mesh.vertices)
    if (!finite(v)) throw InputError(fmt::format("mesh grid: mesh '{}' has a non-finite vertex", mesh.source));
  if (mesh.triangles.size() > std::numeric_limits<std::uint32_t>::max() / 8)
    throw InputError(fmt::format("mesh grid: mesh '{}' has too many triangles", mesh.source));

  const Aabb box = mesh.bounding_box();
  origin_m_ = box.lo_m;
  const Vec3 extent_m = box.hi_m - box.lo_m;
  const double largest_extent = std::max({extent_m.x, extent_m.y, extent_m.z});

  double h = cell_size_m > 0.0 ? cell_size_m : mean_edge_length(mesh);
  if (!(h > 0.0)) h = largest_extent > 0.0 ? largest_extent : 1.0;  // empty or point-like mesh
  // Enlarge the cells until the count fits the cap (the ceil() makes one pass not
  // always enough, so repeat with a small extra factor).
  for (double cells = cells_for(extent_m, h); cells > static_cast<double>(max_cells); cells = cells_for(extent_m, h))
    h *= std::max(1.0 + 1e-6, std::cbrt(cells / static_cast<double>(max_cells)) * 1.0001);
  cell_size_m_ = h;
  for (int a = 0; a < 3; ++a)
    dims_[static_cast<std::size_t>(a)] =
        static_cast<std::size_t>(std::max(1.0, std::ceil(extent_m[a] / h)));

  // Two passes: count the entries of each cell, then fill them (CSR).
  const double half_diagonal = 0.5 * std::sqrt(3.0) * h;
  std::vector<std::uint32_t> counts(cell_count(), 0);
  auto for_each_cell_of = [&](std::size_t t, auto&& visit) {
    const Vec3& a = mesh.corner(t, 0);
    const Vec3& b = mesh.corner(t, 1);
    const Vec3& c = mesh.corner(t, 2);
    const Vec3 lo{std::min({a.x, b.x, c.x}), std::min({a.y, b.y, c.y}), std::min({a.z, b.z, c.z})};
    const Vec3 hi{std::max({a.x, b.x, c.x}), std::max({a.y, b.y, c.y}), std::max({a.z, b.z, c.z})};
    std::array<std::size_t, 3> clo{}, chi{};
    if (!cell_range(lo, hi, clo, chi)) return;
    const Vec3 n = normalized(cross(b - a, c - a));
    // Slack for rounding in the plane distance, relative to the coordinates involved.
    const double slack = 1e-9 * (half_diagonal + norm(a - origin_m_));
    for (std::size_t k = clo[2]; k <= chi[2]; ++k)
      for (std::size_t j = clo[1]; j <= chi[1]; ++j)
        for (std::size_t i = clo[0]; i <= chi[0]; ++i) {
          const Vec3 centre = origin_m_ + Vec3{(static_cast<double>(i) + 0.5) * h,
                                               (static_cast<double>(j) + 0.5) * h,
                                               (static_cast<double>(k) + 0.5) * h};
          if (std::abs(dot(n, centre - a)) > half_diagonal + slack) continue;  // plane misses the cell
          visit(cell_index(i, j, k));
        }
  };
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
    for_each_cell_of(t, [&](std::size_t cell) { ++counts[cell]; });
  cell_start_.assign(cell_count() + 1, 0);
  for (std::size_t cell = 0; cell < cell_count(); ++cell) cell_start_[cell + 1] = cell_start_[cell] + counts[cell];
  triangles_.assign(cell_start_.back(), 0);
  std::vector<std::uint32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
    for_each_cell_of(t, [&](std::size_t cell) { triangles_[fill[cell]++] = static_cast<std::uint32_t>(t); });
}

// ---------------------------------------------------------------------------------
bool MeshGrid::cell_range(const Vec3& lo_m, const Vec3& hi_m, std::array<std::size_t, 3>& lo,
                          std::array<std::size_t, 3>& hi) const {
  for (int a = 0; a < 3; ++a) {
    const auto axis = static_cast<std::size_t>(a);
    const double n = static_cast<double>(dims_[axis]);
    // Reject boxes that miss the grid, then clamp in floating point before converting
    // (a far-away box must not overflow the conversion).
    if (hi_m[a] < origin_m_[a] || lo_m[a] > origin_m_[a] + n * cell_size_m_) return false;
    const double l = std::floor((lo_m[a] - origin_m_[a]) / cell_size_m_);
    const double u = std::floor((hi_m[a] - origin_m_[a]) / cell_size_m_);
    lo[axis] = static_cast<std::size_t>(std::clamp(l, 0.0, n - 1.0));
    hi[axis] = static_cast<std::size_t>(std::clamp(u, 0.0, n - 1.0));
  }
  return true;
}

// ---------------------------------------------------------------------------------
void MeshGrid::candidates(const Vec3& centre_m, double reach_m, std::vector<std::uint32_t>& out) const {
  out.clear();
  if (!(reach_m >= 0.0) || !finite(centre_m)) return;
  const Vec3 r{reach_m, reach_m, reach_m};
  std::array<std::size_t, 3> lo{}, hi{};
  if (!cell_range(centre_m - r, centre_m + r, lo, hi)) return;
  for (std::size_t k = lo[2]; k <= hi[2]; ++k)
    for (std::size_t j = lo[1]; j <= hi[1]; ++j)
      for (std::size_t i = lo[0]; i <= hi[0]; ++i) {
        const std::size_t cell = cell_index(i, j, k);
        out.insert(out.end(), triangles_.begin() + cell_start_[cell], triangles_.begin() + cell_start_[cell + 1]);
      }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

}  // namespace regodem
