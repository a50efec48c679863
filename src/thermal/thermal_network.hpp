#pragma once
// A frozen heat-conduction network (DESIGN.md section 2, "Thermal stepping"): the
// settled bed's contacts taken once. Nodes are the unknown temperatures (particles,
// then lumped walls); boundaries are bodies held at a prescribed temperature (fixed
// walls). C_i dT_i/dt = sum_edges G_ij (T_j - T_i) + sum_links G_ib (T_b - T_i).
#include <cstdint>
#include <vector>

namespace regodem {

struct ThermalNetwork {
  std::vector<double> heat_capacity_J_per_K;  // C_i = m_i c_i, one per node (> 0)

  struct Edge {
    std::uint32_t a, b;            // node indices, a != b
    double conductance_W_per_K;    // G_ab >= 0
  };
  std::vector<Edge> edges;

  struct BoundaryLink {
    std::uint32_t node;
    std::uint32_t boundary;        // index into the boundary temperatures
    double conductance_W_per_K;
  };
  std::vector<BoundaryLink> boundary_links;
  std::uint32_t boundary_count = 0;

  std::size_t node_count() const { return heat_capacity_J_per_K.size(); }
};

}  // namespace regodem
