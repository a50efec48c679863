#pragma once
// Heat stepping on a frozen contact network (DESIGN.md section 2, "Thermal stepping"):
// while the bed does not move, temperatures advance on their own, much larger step,
//   C_i dT_i/dt = sum_edges G_ij (T_j - T_i) + sum_links G_ib (T_b - T_i),
// explicitly at the stability limit or implicitly. With L the weighted graph Laplacian
// of the edges plus the link conductances on its diagonal and s_i = sum_links G_ib T_b,
// the theta method (explicit 0, backward Euler 1, Crank-Nicolson 1/2) is
//   (C/dt + theta L) T^{n+1} = (C/dt - (1 - theta) L) T^n + theta s^{n+1} + (1 - theta) s^n.
// The edges cancel in sum_i, so the nodes' energy sum C_i T_i changes by exactly the
// heat the links pass, evaluated the same way; the report gives it per boundary. With c(T)
// the caller takes C at the step's start and reads C_i dT_i as node i's energy, to add to
// its enthalpy (StaticHeatStepper), so energy is kept however C varies.
//
// The implicit matrix is symmetric positive definite. Two ways to solve it, measured on
// a 1e5-node random 3-D network (numbers in static_bed_solver.cpp): Jacobi-preconditioned
// conjugate gradients (no set-up, ~0.04-0.5 s a step as dt grows) and a sparse LDLT
// factorisation (~2 s to factorise, ~0.02 s a solve). Which is faster depends on how
// many steps share one matrix, which only the caller knows, so `automatic` runs CG and
// factorises once CG's extra work on an unchanged matrix would have paid for it.
#include <cstddef>
#include <memory>
#include <vector>

#include "thermal/thermal_network.hpp"

namespace regodem {

enum class StaticBedMethod { explicit_euler, backward_euler, crank_nicolson };

/// How the implicit methods solve their linear system.
enum class StaticBedLinearSolver {
  automatic,           // CG until its work on one matrix would have paid for a factorisation, then LDLT
  conjugate_gradient,  // Jacobi-preconditioned CG from the current temperatures, relative residual 1e-12
  cholesky,            // sparse LDLT (AMD ordering), factorised again when dt or the values change
};

struct StaticStepReport {
  // Per boundary, the heat that entered the nodes during the step, evaluated as the
  // method does: explicit G (T_b^start - T_i^n) dt, backward Euler G (T_b^end - T_i^{n+1}) dt,
  // Crank-Nicolson the average. Their sum equals the change of sum C_i T_i to round-off
  // (explicit, LDLT) or to the CG tolerance.
  std::vector<double> heat_from_boundary_J;
  int solver_iterations = 0;  // CG iterations (with any attempt `automatic` cut short); 0 for explicit
  bool direct_solve = false;  // the LDLT factor solved this step
  bool factorised = false;    // this step computed a new LDLT factorisation
};

class StaticBedSolver {
 public:
  /// Checks the network (indices in range, no self-edges, finite non-negative
  /// conductances, finite positive capacities); throws SimulationError or InputError.
  StaticBedSolver(StaticBedMethod method, ThermalNetwork network,
                  StaticBedLinearSolver linear_solver = StaticBedLinearSolver::automatic);
  ~StaticBedSolver();
  StaticBedSolver(StaticBedSolver&&) noexcept;
  StaticBedSolver& operator=(StaticBedSolver&&) noexcept;
  StaticBedSolver(const StaticBedSolver&) = delete;
  StaticBedSolver& operator=(const StaticBedSolver&) = delete;

  /// Explicit stability limit: min over nodes of C_i / (sum of G of its edges and links);
  /// +inf if no node has any conductance. At or below it the explicit update is a convex
  /// combination of old temperatures, so it cannot overshoot.
  double stability_limit_s() const { return stability_limit_s_; }

  /// Replaces capacities and conductances (same nodes, edges and links in the same
  /// order), e.g. for temperature-dependent properties. The sparsity pattern and its
  /// symbolic analysis are kept; identical values keep the cached matrix and factor.
  void update_values(const std::vector<double>& heat_capacity_J_per_K,
                     const std::vector<double>& edge_conductance_W_per_K,
                     const std::vector<double>& link_conductance_W_per_K);

  /// Advances temperature_K (one per node) by dt_s. boundary_start_K / boundary_end_K:
  /// boundary temperatures at the start and the end of the step (explicit uses start,
  /// backward Euler end, Crank-Nicolson both). Explicit throws SimulationError above
  /// stability_limit_s(). The conjugate_gradient solver throws SimulationError if CG does
  /// not converge; automatic then factorises instead.
  StaticStepReport step(double dt_s, std::vector<double>& temperature_K, const std::vector<double>& boundary_start_K,
                        const std::vector<double>& boundary_end_K);

  const ThermalNetwork& network() const { return network_; }
  StaticBedMethod method() const { return method_; }

 private:
  struct Implicit;  // Eigen matrix, CG and LDLT state, kept out of this header

  void validate_values() const;
  void compute_conductance_sums();
  void step_explicit(double dt_s, std::vector<double>& temperature_K, const std::vector<double>& boundary_start_K,
                     StaticStepReport& report);
  void step_implicit(double dt_s, std::vector<double>& temperature_K, const std::vector<double>& boundary_start_K,
                     const std::vector<double>& boundary_end_K, StaticStepReport& report);

  StaticBedMethod method_;
  StaticBedLinearSolver linear_solver_;
  ThermalNetwork network_;
  std::vector<double> link_conductance_sum_W_per_K_;   // per node: sum of its links' G
  std::vector<double> total_conductance_sum_W_per_K_;  // per node: edges' plus links' G
  double stability_limit_s_ = 0.0;
  std::vector<double> edge_flux_W_;  // scratch: sum over edges of G (T_j - T_i), per node
  std::unique_ptr<Implicit> implicit_;
};

}  // namespace regodem
