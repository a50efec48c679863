#pragma once
// A uniform grid over a TriangleMesh's bounding box that bins its triangles, so the
// triangles a sphere may touch are found by visiting the few cells around it rather
// than every triangle (the drill mesh has thousands; a particle touches a handful).
//
// A triangle goes into every cell its bounding box overlaps, except cells its plane
// misses (the plane is farther from the cell centre than the cell's half-diagonal):
// both tests are conservative, so no triangle that meets a cell is left out of it.
// Cells are stored CSR-style (one offset array, one triangle-index array); each cell's
// list is in increasing triangle order.
//
// The grid lives in the mesh's own frame: a moving mesh wall keeps its grid and
// queries it with the sphere centre mapped into that frame.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/triangle_mesh.hpp"

namespace regodem {

class MeshGrid {
 public:
  static constexpr std::size_t kDefaultMaxCells = std::size_t{1} << 20;

  MeshGrid() = default;
  /// cell_size_m > 0: that cell edge (e.g. the largest particle diameter plus the skin);
  /// cell_size_m <= 0: the mesh's mean edge length. The size is then enlarged, if need
  /// be, until the grid has at most max_cells cells. Throws InputError for a NaN or
  /// infinite cell size, a zero max_cells, or a mesh with a non-finite vertex.
  explicit MeshGrid(const TriangleMesh& mesh, double cell_size_m = 0.0,
                    std::size_t max_cells = kDefaultMaxCells);

  /// Indices of the triangles binned in the cells that the box [centre - reach, centre +
  /// reach] overlaps: a superset of those within reach_m of centre_m. Sorted, without
  /// duplicates. `out` is overwritten.
  void candidates(const Vec3& centre_m, double reach_m, std::vector<std::uint32_t>& out) const;

  double cell_size_m() const { return cell_size_m_; }
  const std::array<std::size_t, 3>& dims() const { return dims_; }
  std::size_t cell_count() const { return dims_[0] * dims_[1] * dims_[2]; }
  /// Total entries over all cells (a triangle counts once per cell it is in).
  std::size_t entry_count() const { return triangles_.size(); }
  std::size_t triangle_count() const { return triangle_count_; }

 private:
  std::size_t cell_index(std::size_t i, std::size_t j, std::size_t k) const {
    return (k * dims_[1] + j) * dims_[0] + i;
  }
  /// The cell range [lo, hi] on each axis that [lo_m, hi_m] overlaps; false if none.
  bool cell_range(const Vec3& lo_m, const Vec3& hi_m, std::array<std::size_t, 3>& lo,
                  std::array<std::size_t, 3>& hi) const;

  Vec3 origin_m_;
  double cell_size_m_ = 1.0;
  std::array<std::size_t, 3> dims_ = {1, 1, 1};
  std::vector<std::uint32_t> cell_start_ = {0, 0};  // cell_count() + 1 offsets
  std::vector<std::uint32_t> triangles_;
  std::size_t triangle_count_ = 0;
};

}  // namespace regodem
