#include "thermal/thermal_network.hpp"

#include <algorithm>
#include <limits>

namespace regodem {

double explicit_stability_limit_s(const ThermalNetwork& network) {
  std::vector<double> conductance_sum(network.node_count(), 0.0);
  for (const ThermalNetwork::Edge& e : network.edges) {
    conductance_sum[e.a] += e.conductance_W_per_K;
    conductance_sum[e.b] += e.conductance_W_per_K;
  }
  for (const ThermalNetwork::BoundaryLink& l : network.boundary_links) conductance_sum[l.node] += l.conductance_W_per_K;
  double limit = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < network.node_count(); ++i)
    if (conductance_sum[i] > 0.0) limit = std::min(limit, network.heat_capacity_J_per_K[i] / conductance_sum[i]);
  return limit;
}

}  // namespace regodem
