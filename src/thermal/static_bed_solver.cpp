#include "thermal/static_bed_solver.hpp"

#include <fmt/format.h>

// GCC 12 reports a false -Wmaybe-uninitialized inside its own AVX-512 intrinsics when
// Eigen's dot products are inlined with -march=native (GCC bug 105593); the headers are
// system headers, the warning is not about this file.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "core/error.hpp"

namespace regodem {

namespace {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

// Cost model of `automatic`, in passes over the matrix (one CG iteration: a sparse
// matrix-vector product plus five vector operations). Measured on a 2-core VM with a
// throwaway program (g++ 12 -O2 -march=native, Eigen 3.4), random points in a cube
// joined within a cutoff (2.9 edges per node, conductances over a decade, a hot face):
//                     dt = 1x     10x     100x    1000x the explicit limit
//   1e5 nodes  CG:    0.037   0.091   0.20    0.47  s/step (11, 31, 80, 210 iterations)
//              LDLT:  factorise 1.6-2.1 s (nnz(L) 5.1e6), then 0.02-0.03 s/solve
//   3e5 nodes  CG:    0.10    0.25    0.60    1.5   s/step (11, 29, 76, 194 iterations)
//              LDLT:  factorise 26 s (nnz(L) 2.9e7, 0.47 GB), then 0.11-0.15 s/solve
// (CG with incomplete Cholesky halved the iterations but was slower per step.) A CG
// iteration costs ~3.5 ns per stored entry of A, the numeric factorisation ~0.6 ns per
// squared column count of L, a solve by the factor ~3.4 ns per entry of L.
constexpr double kFactorisationWorkPerPass = 6.0;  // sum_j count_j^2 per (nnz(A) x this) = one pass

constexpr double kCgRelativeResidual = 1e-12;

// Eigen's LDLT keeps L's column pointers after the symbolic analysis (analyzePattern),
// before any numbers: the cost of the numeric factorisation is known in advance.
class CholeskyFactor : public Eigen::SimplicialLDLT<SparseMatrix> {
 public:
  double sum_squared_column_counts() const {
    const int* column_start = m_matrix.outerIndexPtr();
    double sum = 0.0;
    for (Eigen::Index j = 0; j < m_matrix.outerSize(); ++j) {
      const double count = column_start[j + 1] - column_start[j];
      sum += count * count;
    }
    return sum;
  }
  double factor_nonzeros() const {
    return m_matrix.outerSize() > 0 ? m_matrix.outerIndexPtr()[m_matrix.outerSize()] : 0.0;
  }
};

double theta_of(StaticBedMethod method) {
  switch (method) {
    case StaticBedMethod::explicit_euler: return 0.0;
    case StaticBedMethod::backward_euler: return 1.0;
    case StaticBedMethod::crank_nicolson: return 0.5;
  }
  return 1.0;
}

void check_capacity(std::size_t node, double capacity_J_per_K) {
  if (!(std::isfinite(capacity_J_per_K) && capacity_J_per_K > 0.0))
    throw InputError(fmt::format("thermal network: node {} has heat capacity {} J/K; it must be finite and positive "
                                 "(check the material's density and specific heat)",
                                 node, capacity_J_per_K));
}

void check_conductance(const char* what, std::size_t index, double conductance_W_per_K) {
  if (!(std::isfinite(conductance_W_per_K) && conductance_W_per_K >= 0.0))
    throw InputError(fmt::format("thermal network: {} {} has conductance {} W/K; it must be finite and non-negative "
                                 "(check the conductivities and the conduction law)",
                                 what, index, conductance_W_per_K));
}

}  // namespace

// The implicit system C/dt + theta L with a fixed pattern (both triangles, so CG can
// use a plain product), and the solvers' caches. On the heap so that the CG's reference
// to the matrix survives moving the solver.
struct StaticBedSolver::Implicit {
  SparseMatrix matrix;
  std::vector<int> diagonal_entry;  // per node: index into matrix.valuePtr()
  std::vector<int> edge_entry_ab;   // per edge: entries (a, b) and (b, a)
  std::vector<int> edge_entry_ba;

  bool values_current = false;  // matrix holds C/dt + theta L for matrix_dt_s and the current values
  double matrix_dt_s = 0.0;

  Eigen::ConjugateGradient<SparseMatrix, Eigen::Lower | Eigen::Upper, Eigen::DiagonalPreconditioner<double>> cg;
  bool cg_ready = false;

  CholeskyFactor ldlt;
  bool analysed = false;
  bool factor_current = false;
  double factorisation_cost_passes = 0.0;
  double direct_solve_cost_passes = 0.0;
  // Passes CG has spent on this matrix beyond what solves by a factor would have cost.
  double cg_excess_passes = 0.0;

  Eigen::VectorXd rhs;
  Eigen::VectorXd solution;

  void analyse() {
    if (analysed) return;
    ldlt.analyzePattern(matrix);
    const double passes = static_cast<double>(std::max<Eigen::Index>(matrix.nonZeros(), 1));
    factorisation_cost_passes = ldlt.sum_squared_column_counts() / (kFactorisationWorkPerPass * passes);
    direct_solve_cost_passes = (ldlt.factor_nonzeros() + static_cast<double>(matrix.rows())) / passes;
    analysed = true;
  }
};

StaticBedSolver::StaticBedSolver(StaticBedMethod method, ThermalNetwork network, StaticBedLinearSolver linear_solver)
    : method_(method), linear_solver_(linear_solver), network_(std::move(network)) {
  const std::size_t n = network_.node_count();
  if (n > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw SimulationError(fmt::format("thermal network: {} nodes are more than the solver indexes", n));
  for (std::size_t k = 0; k < network_.edges.size(); ++k) {
    const ThermalNetwork::Edge& e = network_.edges[k];
    if (e.a >= n || e.b >= n)
      throw SimulationError(fmt::format("thermal network: edge {} joins nodes {} and {}, but there are only {} nodes",
                                        k, e.a, e.b, n));
    if (e.a == e.b) throw SimulationError(fmt::format("thermal network: edge {} joins node {} to itself", k, e.a));
  }
  for (std::size_t k = 0; k < network_.boundary_links.size(); ++k) {
    const ThermalNetwork::BoundaryLink& l = network_.boundary_links[k];
    if (l.node >= n)
      throw SimulationError(fmt::format("thermal network: boundary link {} names node {}, but there are only {} nodes",
                                        k, l.node, n));
    if (l.boundary >= network_.boundary_count)
      throw SimulationError(fmt::format(
          "thermal network: boundary link {} names boundary {}, but there are only {} boundaries", k, l.boundary,
          network_.boundary_count));
  }
  validate_values();
  compute_conductance_sums();
  edge_flux_W_.assign(n, 0.0);

  if (method_ == StaticBedMethod::explicit_euler || n == 0) return;
  // The pattern is fixed for the solver's life: the diagonal and both triangles of each
  // edge (duplicate edges share entries, which the value fill sums).
  implicit_ = std::make_unique<Implicit>();
  Implicit& im = *implicit_;
  const int size = static_cast<int>(n);
  std::vector<Eigen::Triplet<double, int>> entries;
  entries.reserve(n + 2 * network_.edges.size());
  for (int i = 0; i < size; ++i) entries.emplace_back(i, i, 1.0);
  for (const ThermalNetwork::Edge& e : network_.edges) {
    entries.emplace_back(static_cast<int>(e.a), static_cast<int>(e.b), 1.0);
    entries.emplace_back(static_cast<int>(e.b), static_cast<int>(e.a), 1.0);
  }
  im.matrix.resize(size, size);
  im.matrix.setFromTriplets(entries.begin(), entries.end());
  im.matrix.makeCompressed();
  // Column-major: entry (row, column) lies in column `column`, whose rows are sorted.
  auto entry = [&im](std::uint32_t row, std::uint32_t column) {
    const int* begin = im.matrix.innerIndexPtr() + im.matrix.outerIndexPtr()[column];
    const int* end = im.matrix.innerIndexPtr() + im.matrix.outerIndexPtr()[column + 1];
    const int* found = std::lower_bound(begin, end, static_cast<int>(row));
    if (found == end || *found != static_cast<int>(row))
      throw std::logic_error("static bed solver: an entry is missing from the matrix pattern");
    return static_cast<int>(found - im.matrix.innerIndexPtr());
  };
  im.diagonal_entry.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    im.diagonal_entry[i] = entry(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(i));
  im.edge_entry_ab.resize(network_.edges.size());
  im.edge_entry_ba.resize(network_.edges.size());
  for (std::size_t k = 0; k < network_.edges.size(); ++k) {
    im.edge_entry_ab[k] = entry(network_.edges[k].a, network_.edges[k].b);
    im.edge_entry_ba[k] = entry(network_.edges[k].b, network_.edges[k].a);
  }
  im.rhs.resize(size);
  im.solution.resize(size);
}

StaticBedSolver::~StaticBedSolver() = default;
StaticBedSolver::StaticBedSolver(StaticBedSolver&&) noexcept = default;
StaticBedSolver& StaticBedSolver::operator=(StaticBedSolver&&) noexcept = default;

void StaticBedSolver::validate_values() const {
  for (std::size_t i = 0; i < network_.node_count(); ++i) check_capacity(i, network_.heat_capacity_J_per_K[i]);
  for (std::size_t k = 0; k < network_.edges.size(); ++k)
    check_conductance("edge", k, network_.edges[k].conductance_W_per_K);
  for (std::size_t k = 0; k < network_.boundary_links.size(); ++k)
    check_conductance("boundary link", k, network_.boundary_links[k].conductance_W_per_K);
}

void StaticBedSolver::compute_conductance_sums() {
  const std::size_t n = network_.node_count();
  link_conductance_sum_W_per_K_.assign(n, 0.0);
  total_conductance_sum_W_per_K_.assign(n, 0.0);
  for (const ThermalNetwork::Edge& e : network_.edges) {
    total_conductance_sum_W_per_K_[e.a] += e.conductance_W_per_K;
    total_conductance_sum_W_per_K_[e.b] += e.conductance_W_per_K;
  }
  for (const ThermalNetwork::BoundaryLink& l : network_.boundary_links)
    link_conductance_sum_W_per_K_[l.node] += l.conductance_W_per_K;
  stability_limit_s_ = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    total_conductance_sum_W_per_K_[i] += link_conductance_sum_W_per_K_[i];
    // A node without conductance keeps its temperature and limits nothing.
    if (total_conductance_sum_W_per_K_[i] > 0.0)
      stability_limit_s_ =
          std::min(stability_limit_s_, network_.heat_capacity_J_per_K[i] / total_conductance_sum_W_per_K_[i]);
  }
}

void StaticBedSolver::update_values(const std::vector<double>& heat_capacity_J_per_K,
                                    const std::vector<double>& edge_conductance_W_per_K,
                                    const std::vector<double>& link_conductance_W_per_K) {
  if (heat_capacity_J_per_K.size() != network_.node_count() ||
      edge_conductance_W_per_K.size() != network_.edges.size() ||
      link_conductance_W_per_K.size() != network_.boundary_links.size())
    throw SimulationError(fmt::format(
        "static bed solver: new values for {} nodes, {} edges and {} boundary links, but the network has {}, {} and {}",
        heat_capacity_J_per_K.size(), edge_conductance_W_per_K.size(), link_conductance_W_per_K.size(),
        network_.node_count(), network_.edges.size(), network_.boundary_links.size()));
  // Check everything before changing anything, so a refused update leaves the solver as it was.
  for (std::size_t i = 0; i < heat_capacity_J_per_K.size(); ++i) check_capacity(i, heat_capacity_J_per_K[i]);
  for (std::size_t k = 0; k < edge_conductance_W_per_K.size(); ++k)
    check_conductance("edge", k, edge_conductance_W_per_K[k]);
  for (std::size_t k = 0; k < link_conductance_W_per_K.size(); ++k)
    check_conductance("boundary link", k, link_conductance_W_per_K[k]);

  bool changed = heat_capacity_J_per_K != network_.heat_capacity_J_per_K;
  for (std::size_t k = 0; k < network_.edges.size(); ++k) {
    changed = changed || network_.edges[k].conductance_W_per_K != edge_conductance_W_per_K[k];
    network_.edges[k].conductance_W_per_K = edge_conductance_W_per_K[k];
  }
  for (std::size_t k = 0; k < network_.boundary_links.size(); ++k) {
    changed = changed || network_.boundary_links[k].conductance_W_per_K != link_conductance_W_per_K[k];
    network_.boundary_links[k].conductance_W_per_K = link_conductance_W_per_K[k];
  }
  if (!changed) return;  // the caller may refresh every step with constant properties: keep the factor
  network_.heat_capacity_J_per_K = heat_capacity_J_per_K;
  compute_conductance_sums();
  if (implicit_) implicit_->values_current = false;
}

StaticStepReport StaticBedSolver::step(double dt_s, std::vector<double>& temperature_K,
                                       const std::vector<double>& boundary_start_K,
                                       const std::vector<double>& boundary_end_K) {
  if (!(std::isfinite(dt_s) && dt_s > 0.0))
    throw SimulationError(fmt::format("static bed solver: the time step must be finite and positive (got {} s)", dt_s));
  if (temperature_K.size() != network_.node_count())
    throw SimulationError(fmt::format("static bed solver: {} temperatures for {} nodes", temperature_K.size(),
                                      network_.node_count()));
  for (const std::vector<double>* boundary : {&boundary_start_K, &boundary_end_K}) {
    if (boundary->size() != network_.boundary_count)
      throw SimulationError(fmt::format("static bed solver: {} boundary temperatures for {} boundaries",
                                        boundary->size(), network_.boundary_count));
    for (std::size_t b = 0; b < boundary->size(); ++b)
      if (!std::isfinite((*boundary)[b]))
        throw SimulationError(fmt::format("static bed solver: boundary {} has temperature {} K", b, (*boundary)[b]));
  }

  StaticStepReport report;
  report.heat_from_boundary_J.assign(network_.boundary_count, 0.0);
  if (method_ == StaticBedMethod::explicit_euler) {
    // Beyond the limit the update is no longer a convex combination of the old
    // temperatures: it can overshoot and, further on, diverge. The slack only forgives
    // round-off in a dt computed from the limit.
    if (dt_s > stability_limit_s_ * (1.0 + 1e-12))
      throw SimulationError(fmt::format(
          "explicit static-bed step of {} s exceeds the stability limit {} s (min over nodes of C_i / sum of G); "
          "take a smaller step or an implicit method",
          dt_s, stability_limit_s_));
    step_explicit(dt_s, temperature_K, boundary_start_K, report);
  } else if (network_.node_count() > 0) {
    step_implicit(dt_s, temperature_K, boundary_start_K, boundary_end_K, report);
  }
  return report;
}

void StaticBedSolver::step_explicit(double dt_s, std::vector<double>& temperature_K,
                                    const std::vector<double>& boundary_start_K, StaticStepReport& report) {
  std::fill(edge_flux_W_.begin(), edge_flux_W_.end(), 0.0);
  for (const ThermalNetwork::Edge& e : network_.edges) {
    const double q_W = e.conductance_W_per_K * (temperature_K[e.b] - temperature_K[e.a]);
    edge_flux_W_[e.a] += q_W;
    edge_flux_W_[e.b] -= q_W;
  }
  for (const ThermalNetwork::BoundaryLink& l : network_.boundary_links) {
    const double q_W = l.conductance_W_per_K * (boundary_start_K[l.boundary] - temperature_K[l.node]);
    edge_flux_W_[l.node] += q_W;
    report.heat_from_boundary_J[l.boundary] += q_W * dt_s;
  }
  for (std::size_t i = 0; i < temperature_K.size(); ++i)
    temperature_K[i] += dt_s * edge_flux_W_[i] / network_.heat_capacity_J_per_K[i];
}

void StaticBedSolver::step_implicit(double dt_s, std::vector<double>& temperature_K,
                                    const std::vector<double>& boundary_start_K,
                                    const std::vector<double>& boundary_end_K, StaticStepReport& report) {
  Implicit& im = *implicit_;
  const double theta = theta_of(method_);
  const std::size_t n = network_.node_count();

  // The matrix depends on dt and the values only: refill it (same pattern) when either changed.
  if (!im.values_current || dt_s != im.matrix_dt_s) {
    double* value = im.matrix.valuePtr();
    std::fill(value, value + im.matrix.nonZeros(), 0.0);
    for (std::size_t i = 0; i < n; ++i)
      value[im.diagonal_entry[i]] =
          network_.heat_capacity_J_per_K[i] / dt_s + theta * total_conductance_sum_W_per_K_[i];
    for (std::size_t k = 0; k < network_.edges.size(); ++k) {
      value[im.edge_entry_ab[k]] -= theta * network_.edges[k].conductance_W_per_K;
      value[im.edge_entry_ba[k]] -= theta * network_.edges[k].conductance_W_per_K;
    }
    im.values_current = true;
    im.matrix_dt_s = dt_s;
    im.cg_ready = false;
    im.factor_current = false;
    im.cg_excess_passes = 0.0;
  }

  // Right-hand side C/dt T^n + (1 - theta) (flux at T^n) + theta s^{n+1}, and the
  // explicit part of the boundary heat while T^n is still at hand.
  const double explicit_share = 1.0 - theta;
  if (explicit_share > 0.0) {
    std::fill(edge_flux_W_.begin(), edge_flux_W_.end(), 0.0);
    for (const ThermalNetwork::Edge& e : network_.edges) {
      const double q_W = e.conductance_W_per_K * (temperature_K[e.b] - temperature_K[e.a]);
      edge_flux_W_[e.a] += q_W;
      edge_flux_W_[e.b] -= q_W;
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Index row = static_cast<Eigen::Index>(i);
    im.rhs[row] = network_.heat_capacity_J_per_K[i] / dt_s * temperature_K[i];
    if (explicit_share > 0.0) im.rhs[row] += explicit_share * edge_flux_W_[i];
  }
  for (const ThermalNetwork::BoundaryLink& l : network_.boundary_links) {
    const double start_W = l.conductance_W_per_K * (boundary_start_K[l.boundary] - temperature_K[l.node]);
    im.rhs[static_cast<Eigen::Index>(l.node)] +=
        explicit_share * start_W + theta * l.conductance_W_per_K * boundary_end_K[l.boundary];
    report.heat_from_boundary_J[l.boundary] += explicit_share * start_W * dt_s;
  }

  // CG from the current temperatures, or the LDLT factor: see the header and the cost
  // model above. `automatic` lets CG spend at most what a factorisation would cost beyond
  // solves by the factor (so it is never worse than twice the better of the two).
  bool solved = false;
  if (linear_solver_ == StaticBedLinearSolver::conjugate_gradient ||
      (linear_solver_ == StaticBedLinearSolver::automatic && !im.factor_current)) {
    Eigen::Index max_iterations = std::max<Eigen::Index>(2 * static_cast<Eigen::Index>(n), 100);
    if (linear_solver_ == StaticBedLinearSolver::automatic) {
      im.analyse();
      const double budget_passes = im.factorisation_cost_passes - im.cg_excess_passes;
      max_iterations = budget_passes >= 1.0 ? static_cast<Eigen::Index>(std::ceil(budget_passes)) : 0;
    }
    if (max_iterations > 0) {
      if (!im.cg_ready) {
        im.cg.setTolerance(kCgRelativeResidual);
        im.cg.compute(im.matrix);
        im.cg_ready = true;
      }
      im.cg.setMaxIterations(max_iterations);
      const Eigen::Map<const Eigen::VectorXd> guess(temperature_K.data(), static_cast<Eigen::Index>(n));
      im.solution = im.cg.solveWithGuess(im.rhs, guess);
      report.solver_iterations = static_cast<int>(im.cg.iterations());
      solved = im.cg.info() == Eigen::Success;
      if (!solved && linear_solver_ == StaticBedLinearSolver::conjugate_gradient)
        throw SimulationError(fmt::format(
            "static bed solver: conjugate gradients did not converge in {} iterations (relative residual {}, "
            "wanted {}); try a smaller step or the cholesky linear solver",
            report.solver_iterations, im.cg.error(), kCgRelativeResidual));
      const double passes = static_cast<double>(report.solver_iterations) + 1.0;  // + the initial residual
      im.cg_excess_passes += solved ? std::max(0.0, passes - im.direct_solve_cost_passes) : passes;
    }
  }
  if (!solved) {
    im.analyse();
    if (!im.factor_current) {
      im.ldlt.factorize(im.matrix);
      if (im.ldlt.info() != Eigen::Success)
        throw SimulationError("static bed solver: the LDLT factorisation failed (the matrix is not positive definite)");
      im.factor_current = true;
      report.factorised = true;
    }
    im.solution = im.ldlt.solve(im.rhs);
    report.direct_solve = true;
  }

  for (std::size_t i = 0; i < n; ++i) temperature_K[i] = im.solution[static_cast<Eigen::Index>(i)];
  for (const ThermalNetwork::BoundaryLink& l : network_.boundary_links)
    report.heat_from_boundary_J[l.boundary] +=
        theta * l.conductance_W_per_K * (boundary_end_K[l.boundary] - temperature_K[l.node]) * dt_s;
}

}  // namespace regodem
