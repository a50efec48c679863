// Heat stepping on a frozen network (DESIGN.md section 2, "Thermal stepping"): the
// two-node exponential and each method's order, the series-conductance steady state of
// a chain, the per-step energy balance, refusals, and explicit against implicit on a
// 3-D lattice. Each check states its tolerance.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/rng.hpp"
#include "thermal/static_bed_solver.hpp"

namespace regodem {
namespace {

constexpr StaticBedLinearSolver kLinearSolvers[] = {StaticBedLinearSolver::automatic,
                                                    StaticBedLinearSolver::conjugate_gradient,
                                                    StaticBedLinearSolver::cholesky};

const char* name_of(StaticBedLinearSolver s) {
  switch (s) {
    case StaticBedLinearSolver::automatic: return "automatic";
    case StaticBedLinearSolver::conjugate_gradient: return "conjugate_gradient";
    case StaticBedLinearSolver::cholesky: return "cholesky";
  }
  return "?";
}

double total_energy_J(const ThermalNetwork& net, const std::vector<double>& T) {
  double sum = 0.0;
  for (std::size_t i = 0; i < T.size(); ++i) sum += net.heat_capacity_J_per_K[i] * T[i];
  return sum;
}

ThermalNetwork two_nodes(double c1, double c2, double g) {
  ThermalNetwork net;
  net.heat_capacity_J_per_K = {c1, c2};
  net.edges = {{0, 1, g}};
  return net;
}

// Nodes at random capacities, each joined to 3 random others (duplicates and zero
// conductances included on purpose), and 3 boundaries with 20 links.
ThermalNetwork random_network(std::size_t n, std::uint64_t seed) {
  Rng rng(seed);
  ThermalNetwork net;
  for (std::size_t i = 0; i < n; ++i) net.heat_capacity_J_per_K.push_back(rng.uniform(0.5, 2.0));
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) {
      auto j = static_cast<std::uint32_t>(rng.uniform(0.0, static_cast<double>(n - 1)));
      if (j >= i) ++j;  // never i itself
      const double g = rng.uniform() < 0.05 ? 0.0 : rng.uniform(0.1, 1.0);
      net.edges.push_back({static_cast<std::uint32_t>(i), j, g});
    }
  net.boundary_count = 3;
  for (std::uint32_t k = 0; k < 20; ++k)
    net.boundary_links.push_back({static_cast<std::uint32_t>(rng.uniform(0.0, static_cast<double>(n))), k % 3,
                                  rng.uniform(0.2, 2.0)});
  return net;
}

// nx x ny x nz cubic lattice, C = 1 J/K and G in [0.5, 1.5] W/K per bond, 10 % of the
// bonds missing; the x = 0 face linked (G = 1 W/K) to boundary 0.
ThermalNetwork lattice(int nx, int ny, int nz, std::uint64_t seed) {
  Rng rng(seed);
  ThermalNetwork net;
  auto id = [=](int x, int y, int z) { return static_cast<std::uint32_t>((z * ny + y) * nx + x); };
  net.heat_capacity_J_per_K.assign(static_cast<std::size_t>(nx * ny * nz), 1.0);
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x) {
        const int step[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
        for (const auto& d : step) {
          const int x2 = x + d[0], y2 = y + d[1], z2 = z + d[2];
          if (x2 >= nx || y2 >= ny || z2 >= nz) continue;
          if (rng.uniform() < 0.1) continue;
          net.edges.push_back({id(x, y, z), id(x2, y2, z2), rng.uniform(0.5, 1.5)});
        }
        if (x == 0) net.boundary_links.push_back({id(x, y, z), 0, 1.0});
      }
  net.boundary_count = 1;
  return net;
}

// ---------------------------------------------------------------------------------------
// 1. Two nodes: Delta T = Delta T0 exp(-t / tau), tau = C1 C2 / (G (C1 + C2)).

// |Delta T(t_end) - exact| after `steps` equal steps to t_end = tau.
double two_node_error_K(StaticBedMethod method, StaticBedLinearSolver linear, int steps) {
  const double c1 = 2.0, c2 = 3.0, g = 0.5;
  const double tau = c1 * c2 / (g * (c1 + c2));  // 2.4 s
  StaticBedSolver solver(method, two_nodes(c1, c2, g), linear);
  std::vector<double> T = {400.0, 300.0};
  const double energy0 = total_energy_J(solver.network(), T);
  const double dt = tau / steps;
  for (int s = 0; s < steps; ++s) solver.step(dt, T, {}, {});
  // Closed system: the energy stays, to round-off (1e-13 relative).
  EXPECT_NEAR(total_energy_J(solver.network(), T), energy0, 1e-13 * energy0);
  return std::abs((T[0] - T[1]) - 100.0 * std::exp(-1.0));
}

TEST(StaticBedSolver, TwoNodesDecayExponentiallyAtEachMethodsOrder) {
  struct Case {
    StaticBedMethod method;
    double tolerance_K;  // at 1000 steps per tau, from Delta T0 = 100 K
    double order;
  };
  // Euler: error ~ Delta T0 e^-1 h / (2 tau) = 0.018 K at h = tau/1000, allowed 0.05 K.
  // CN: error ~ Delta T0 e^-1 (h/tau)^2 / 12 = 3e-6 K, allowed 1e-5 K.
  const Case cases[] = {{StaticBedMethod::explicit_euler, 0.05, 1.0},
                        {StaticBedMethod::backward_euler, 0.05, 1.0},
                        {StaticBedMethod::crank_nicolson, 1e-5, 2.0}};
  for (const Case& c : cases)
    for (StaticBedLinearSolver linear : kLinearSolvers) {
      if (c.method == StaticBedMethod::explicit_euler && linear != StaticBedLinearSolver::automatic) continue;
      SCOPED_TRACE(fmt::format("method {} linear solver {}", static_cast<int>(c.method), name_of(linear)));
      EXPECT_LT(two_node_error_K(c.method, linear, 1000), c.tolerance_K);
      // Halving the step divides the error by 2^order; within 2 % at 50 -> 100 steps per tau
      // (measured: 2.008, 1.992, 4.000).
      const double ratio = two_node_error_K(c.method, linear, 50) / two_node_error_K(c.method, linear, 100);
      EXPECT_NEAR(ratio, std::pow(2.0, c.order), 0.02 * std::pow(2.0, c.order));
    }
}

TEST(StaticBedSolver, StabilityLimitIsTheSmallestCapacityOverConductance) {
  // Tolerances: exact formulas, 1e-15 relative.
  StaticBedSolver two(StaticBedMethod::explicit_euler, two_nodes(2.0, 3.0, 0.5));
  EXPECT_NEAR(two.stability_limit_s(), 4.0, 4e-15);  // min(2, 3) / 0.5
  ThermalNetwork net = two_nodes(2.0, 3.0, 0.5);
  net.heat_capacity_J_per_K.push_back(0.1);  // an isolated node limits nothing
  net.boundary_count = 1;
  net.boundary_links.push_back({1, 0, 0.25});  // node 1: 3 / 0.75 = 4 s as well
  net.boundary_links.push_back({0, 0, 1.5});   // node 0: 2 / 2 = 1 s
  EXPECT_NEAR(StaticBedSolver(StaticBedMethod::backward_euler, net).stability_limit_s(), 1.0, 1e-15);
  ThermalNetwork lonely;
  lonely.heat_capacity_J_per_K = {1.0, 2.0};
  EXPECT_EQ(StaticBedSolver(StaticBedMethod::explicit_euler, lonely).stability_limit_s(),
            std::numeric_limits<double>::infinity());
}

TEST(StaticBedSolver, EmptyNetworkStepsToNothing) {
  for (StaticBedMethod method : {StaticBedMethod::explicit_euler, StaticBedMethod::crank_nicolson}) {
    StaticBedSolver solver(method, ThermalNetwork{});
    std::vector<double> T;
    EXPECT_EQ(solver.stability_limit_s(), std::numeric_limits<double>::infinity());
    EXPECT_TRUE(solver.step(1.0, T, {}, {}).heat_from_boundary_J.empty());
  }
}

// ---------------------------------------------------------------------------------------
// 2. A chain between two boundaries reaches the series-conductance steady state.

TEST(StaticBedSolver, ChainReachesSeriesConductanceSteadyState) {
  const std::size_t n = 20;
  ThermalNetwork net;
  for (std::size_t i = 0; i < n; ++i) net.heat_capacity_J_per_K.push_back(1.0 + 0.1 * static_cast<double>(i));
  std::vector<double> g;  // the series: link 0, the n - 1 edges, link 1
  g.push_back(2.0);
  for (std::uint32_t k = 0; k + 1 < n; ++k) {
    g.push_back(0.5 + 0.3 * (k % 4));
    net.edges.push_back({k, k + 1, g.back()});
  }
  g.push_back(0.7);
  net.boundary_count = 2;
  net.boundary_links = {{0, 0, g.front()}, {static_cast<std::uint32_t>(n - 1), 1, g.back()}};
  const double hot_K = 900.0, cold_K = 100.0;
  double resistance_K_per_W = 0.0;
  for (double gk : g) resistance_K_per_W += 1.0 / gk;
  const double q_W = (hot_K - cold_K) / resistance_K_per_W;

  for (StaticBedLinearSolver linear : kLinearSolvers) {
    SCOPED_TRACE(name_of(linear));
    StaticBedSolver solver(StaticBedMethod::backward_euler, net, linear);
    std::vector<double> T(n, 300.0);
    const double dt = 1e6;  // ~1e4 slowest relaxation times: each step leaves ~1e-4 of the transient
    StaticStepReport report;
    for (int s = 0; s < 6; ++s) report = solver.step(dt, T, {hot_K, cold_K}, {hot_K, cold_K});
    double expected_K = hot_K - q_W / g.front();
    for (std::size_t i = 0; i < n; ++i) {
      EXPECT_NEAR(T[i], expected_K, 1e-9 * expected_K) << "node " << i;  // 1e-9 relative
      expected_K -= q_W / g[i + 1];
    }
    // Heat flow through the chain = Delta T / sum(1/G), 1e-9 relative.
    EXPECT_NEAR(report.heat_from_boundary_J[0] / dt, q_W, 1e-9 * q_W);
    EXPECT_NEAR(report.heat_from_boundary_J[1] / dt, -q_W, 1e-9 * q_W);
  }
}

// ---------------------------------------------------------------------------------------
// 3. Energy balance per step: change of sum C_i T_i = sum of boundary heats.

void expect_energy_balance(StaticBedMethod method, StaticBedLinearSolver linear, double dt_over_limit,
                           double tolerance) {
  const ThermalNetwork net = random_network(300, 11);
  StaticBedSolver solver(method, net, linear);
  Rng rng(3);
  std::vector<double> T(net.node_count());
  for (double& t : T) t = rng.uniform(100.0, 1000.0);
  const double dt = dt_over_limit * solver.stability_limit_s();
  for (int s = 0; s < 12; ++s) {
    // Boundary temperatures ramp during the step, so start and end differ.
    const std::vector<double> start = {900.0 + s, 50.0 - s, 400.0};
    const std::vector<double> end = {901.0 + s, 49.0 - s, 430.0};
    const std::vector<double> before = T;
    const StaticStepReport report = solver.step(dt, T, start, end);
    double change_J = 0.0, scale_J = 0.0;
    for (std::size_t i = 0; i < T.size(); ++i) {
      change_J += net.heat_capacity_J_per_K[i] * (T[i] - before[i]);
      scale_J += net.heat_capacity_J_per_K[i] * std::abs(T[i] - before[i]);
    }
    const double heat_J =
        std::accumulate(report.heat_from_boundary_J.begin(), report.heat_from_boundary_J.end(), 0.0);
    // Relative to sum C_i |Delta T_i|, the scale of the round-off in the sum.
    EXPECT_NEAR(change_J, heat_J, tolerance * scale_J) << "step " << s;
  }
}

TEST(StaticBedSolver, EnergyBalanceClosesEachStep) {
  // Explicit at 0.9 x the limit: round-off only, 1e-12 relative.
  expect_energy_balance(StaticBedMethod::explicit_euler, StaticBedLinearSolver::automatic, 0.9, 1e-12);
  // Implicit at 5x and 200x the limit: LDLT to round-off, CG to its 1e-12 residual; 1e-9 relative.
  for (StaticBedMethod method : {StaticBedMethod::backward_euler, StaticBedMethod::crank_nicolson})
    for (StaticBedLinearSolver linear : kLinearSolvers)
      for (double dt_over_limit : {5.0, 200.0}) {
        SCOPED_TRACE(fmt::format("method {} {} dt {}x", static_cast<int>(method), name_of(linear), dt_over_limit));
        expect_energy_balance(method, linear, dt_over_limit, 1e-9);
      }
}

// ---------------------------------------------------------------------------------------
// 4. Refusals.

TEST(StaticBedSolver, ExplicitAboveTheStabilityLimitIsRefused) {
  StaticBedSolver solver(StaticBedMethod::explicit_euler, two_nodes(2.0, 3.0, 0.5));
  std::vector<double> T = {400.0, 300.0};
  const double limit = solver.stability_limit_s();
  EXPECT_NO_THROW(solver.step(limit, T, {}, {}));  // exactly at the limit is allowed
  const double too_long = limit * (1.0 + 1e-9);
  try {
    solver.step(too_long, T, {}, {});
    ADD_FAILURE() << "an explicit step above the limit was taken";
  } catch (const SimulationError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(fmt::format("{}", too_long)), std::string::npos) << message;
    EXPECT_NE(message.find(fmt::format("{}", limit)), std::string::npos) << message;
  }
  // Implicit methods take any step.
  StaticBedSolver implicit(StaticBedMethod::backward_euler, two_nodes(2.0, 3.0, 0.5));
  EXPECT_NO_THROW(implicit.step(1e3 * limit, T, {}, {}));
}

template <typename Error>
void expect_refused(const ThermalNetwork& net, const std::string& says) {
  try {
    StaticBedSolver solver(StaticBedMethod::backward_euler, net);
    ADD_FAILURE() << "accepted a network that should fail with: " << says;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
  }
}

TEST(StaticBedSolver, BadNetworksAreRefused) {
  const ThermalNetwork good = two_nodes(2.0, 3.0, 0.5);
  ThermalNetwork net = good;
  net.edges.push_back({0, 2, 1.0});
  expect_refused<SimulationError>(net, "only 2 nodes");
  net = good;
  net.edges.push_back({1, 1, 1.0});
  expect_refused<SimulationError>(net, "to itself");
  net = good;
  net.edges[0].conductance_W_per_K = -1.0;
  expect_refused<InputError>(net, "conductance -1");
  net = good;
  net.edges[0].conductance_W_per_K = std::nan("");
  expect_refused<InputError>(net, "finite and non-negative");
  net = good;
  net.heat_capacity_J_per_K[1] = 0.0;
  expect_refused<InputError>(net, "node 1 has heat capacity 0");
  net = good;
  net.boundary_count = 1;
  net.boundary_links.push_back({5, 0, 1.0});
  expect_refused<SimulationError>(net, "names node 5");
  net = good;
  net.boundary_count = 1;
  net.boundary_links.push_back({0, 1, 1.0});
  expect_refused<SimulationError>(net, "names boundary 1, but there are only 1");
  net = good;
  net.boundary_count = 1;
  net.boundary_links.push_back({0, 0, std::numeric_limits<double>::infinity()});
  expect_refused<InputError>(net, "boundary link 0");
}

TEST(StaticBedSolver, BadStepsAndUpdatesAreRefusedAndChangeNothing) {
  ThermalNetwork net = two_nodes(2.0, 3.0, 0.5);
  net.boundary_count = 1;
  net.boundary_links.push_back({0, 0, 1.0});
  StaticBedSolver solver(StaticBedMethod::crank_nicolson, net);
  std::vector<double> T = {400.0, 300.0};
  EXPECT_THROW(solver.step(1.0, T, {}, {500.0}), SimulationError);     // boundary count
  EXPECT_THROW(solver.step(0.0, T, {500.0}, {500.0}), SimulationError);  // dt
  std::vector<double> short_T = {400.0};
  EXPECT_THROW(solver.step(1.0, short_T, {500.0}, {500.0}), SimulationError);
  EXPECT_THROW(solver.update_values({2.0}, {0.5}, {1.0}), SimulationError);            // sizes
  EXPECT_THROW(solver.update_values({2.0, 3.0}, {-0.5}, {1.0}), InputError);           // value
  EXPECT_THROW(solver.update_values({2.0, 3.0}, {0.5}, {std::nan("")}), InputError);  // value
  EXPECT_EQ(solver.network().edges[0].conductance_W_per_K, 0.5);
  EXPECT_EQ(solver.network().boundary_links[0].conductance_W_per_K, 1.0);
  EXPECT_EQ(T, (std::vector<double>{400.0, 300.0}));
}

// ---------------------------------------------------------------------------------------
// Values, caching, the linear solvers and determinism.

TEST(StaticBedSolver, UpdatedValuesGiveTheSameStepsAsAFreshSolver) {
  const ThermalNetwork net = random_network(200, 5);
  ThermalNetwork changed = net;
  Rng rng(9);
  for (double& c : changed.heat_capacity_J_per_K) c *= rng.uniform(0.8, 1.2);
  for (auto& e : changed.edges) e.conductance_W_per_K *= rng.uniform(0.8, 1.2);
  for (auto& l : changed.boundary_links) l.conductance_W_per_K *= rng.uniform(0.8, 1.2);
  std::vector<double> edge_g, link_g;
  for (const auto& e : changed.edges) edge_g.push_back(e.conductance_W_per_K);
  for (const auto& l : changed.boundary_links) link_g.push_back(l.conductance_W_per_K);

  for (StaticBedMethod method :
       {StaticBedMethod::explicit_euler, StaticBedMethod::backward_euler, StaticBedMethod::crank_nicolson}) {
    SCOPED_TRACE(static_cast<int>(method));
    StaticBedSolver updated(method, net, StaticBedLinearSolver::cholesky);
    std::vector<double> T_updated(net.node_count(), 200.0);
    const std::vector<double> boundary = {900.0, 100.0, 500.0};
    updated.step(0.5 * updated.stability_limit_s(), T_updated, boundary, boundary);  // builds the caches
    updated.update_values(changed.heat_capacity_J_per_K, edge_g, link_g);
    StaticBedSolver fresh(method, changed, StaticBedLinearSolver::cholesky);
    EXPECT_EQ(updated.stability_limit_s(), fresh.stability_limit_s());
    std::vector<double> T_fresh = T_updated;
    const double dt = 0.9 * fresh.stability_limit_s();
    const StaticStepReport a = updated.step(dt, T_updated, boundary, boundary);
    const StaticStepReport b = fresh.step(dt, T_fresh, boundary, boundary);
    for (std::size_t i = 0; i < T_fresh.size(); ++i) {
      EXPECT_NEAR(T_updated[i], T_fresh[i], 1e-12 * T_fresh[i]);  // 1e-12 relative: the same arithmetic
    }
    for (std::size_t k = 0; k < boundary.size(); ++k) {
      EXPECT_NEAR(a.heat_from_boundary_J[k], b.heat_from_boundary_J[k], 1e-9 * std::abs(b.heat_from_boundary_J[k]));
    }
    if (method != StaticBedMethod::explicit_euler) {
      EXPECT_TRUE(a.factorised);
      // The same values again keep the factor.
      updated.update_values(changed.heat_capacity_J_per_K, edge_g, link_g);
      EXPECT_FALSE(updated.step(dt, T_updated, boundary, boundary).factorised);
    }
  }
}

TEST(StaticBedSolver, AutomaticFactorisesOnceCgWouldCostMoreAndAllSolversAgree) {
  const ThermalNetwork net = lattice(12, 12, 14, 21);
  std::vector<std::vector<double>> results;
  for (StaticBedLinearSolver linear : kLinearSolvers) {
    StaticBedSolver solver(StaticBedMethod::backward_euler, net, linear);
    std::vector<double> T(net.node_count(), 77.0);
    const double dt = 50.0 * solver.stability_limit_s();
    bool used_cg = false, used_factor = false;
    for (int s = 0; s < 40; ++s) {
      const StaticStepReport r = solver.step(dt, T, {973.0}, {973.0});
      used_cg = used_cg || (r.solver_iterations > 0 && !r.direct_solve);
      used_factor = used_factor || r.direct_solve;
      if (linear == StaticBedLinearSolver::conjugate_gradient) {
        EXPECT_FALSE(r.direct_solve);
      }
      if (linear == StaticBedLinearSolver::cholesky) {
        EXPECT_EQ(r.solver_iterations, 0);
      }
    }
    if (linear == StaticBedLinearSolver::automatic) {
      EXPECT_TRUE(used_cg);      // CG first, as the factorisation is not yet paid for
      EXPECT_TRUE(used_factor);  // then the factor, once 40 steps share the matrix
    }
    results.push_back(T);
  }
  // CG's relative residual 1e-12 of ||C/dt T|| (~1e3 K x sqrt(n)): agreement to 1e-7 K.
  for (std::size_t i = 0; i < results[0].size(); ++i) {
    EXPECT_NEAR(results[1][i], results[2][i], 1e-7);
    EXPECT_NEAR(results[0][i], results[2][i], 1e-7);
  }
}

TEST(StaticBedSolver, ValuesChangingEveryStepKeepAutomaticOnConjugateGradients) {
  const ThermalNetwork net = lattice(12, 12, 14, 22);
  StaticBedSolver solver(StaticBedMethod::crank_nicolson, net);
  std::vector<double> T(net.node_count(), 77.0), edge_g, link_g;
  for (const auto& e : net.edges) edge_g.push_back(e.conductance_W_per_K);
  for (const auto& l : net.boundary_links) link_g.push_back(l.conductance_W_per_K);
  std::vector<double> capacity = net.heat_capacity_J_per_K;
  const double dt = 50.0 * solver.stability_limit_s();
  for (int s = 0; s < 20; ++s) {
    for (double& c : capacity) c *= 1.01;  // a temperature-dependent heat capacity, say
    solver.update_values(capacity, edge_g, link_g);
    const StaticStepReport r = solver.step(dt, T, {973.0}, {973.0});
    EXPECT_FALSE(r.direct_solve) << "step " << s;
    EXPECT_GT(r.solver_iterations, 0);
  }
}

TEST(StaticBedSolver, SameInputGivesBitwiseTheSameResult) {
  const ThermalNetwork net = random_network(400, 17);
  for (StaticBedLinearSolver linear : kLinearSolvers) {
    std::vector<std::vector<double>> runs;
    for (int run = 0; run < 2; ++run) {
      StaticBedSolver solver(StaticBedMethod::crank_nicolson, net, linear);
      std::vector<double> T(net.node_count(), 250.0);
      for (int s = 0; s < 10; ++s) solver.step(20.0 * solver.stability_limit_s(), T, {900, 50, 400}, {900, 50, 400});
      runs.push_back(T);
    }
    EXPECT_EQ(runs[0], runs[1]) << name_of(linear);  // exact
  }
}

// ---------------------------------------------------------------------------------------
// 5. Explicit, backward Euler and Crank-Nicolson agree on a 2016-node lattice heated
// from one face, over several relaxation times.

TEST(StaticBedSolver, MethodsAgreeOnALatticeHeatedFromOneSide) {
  const ThermalNetwork net = lattice(14, 12, 12, 7);  // 14 layers from the hot face
  const double cold_K = 77.0, hot_K = 973.0;
  // The slowest mode: heated at x = 0 and insulated at x = 14, tau1 ~ C / (G (pi / 29)^2)
  // ~ 85 s with C = 1 J/K, G ~ 1 W/K. Run 3 x 85 s, compare every 85 s.
  const double t_compare_s = 85.0;
  const int comparisons = 3;
  struct Run {
    StaticBedMethod method;
    double dt_over_limit;
  };
  // The first-order errors have opposite signs (explicit Euler runs ahead of the exact
  // heating, backward Euler behind), so their difference grows with the sum of the two
  // steps: explicit at half its limit, backward Euler at the limit (measured worst
  // differences 0.38 K and, for Crank-Nicolson at 10x the limit, 0.12 K).
  const Run runs[] = {{StaticBedMethod::explicit_euler, 0.5},
                      {StaticBedMethod::backward_euler, 1.0},
                      {StaticBedMethod::crank_nicolson, 10.0}};
  std::vector<std::vector<std::vector<double>>> snapshots;  // [run][comparison][node]
  for (const Run& run : runs) {
    StaticBedSolver solver(run.method, net);
    std::vector<double> T(net.node_count(), cold_K);
    const double limit = solver.stability_limit_s();
    const int steps_per_compare = static_cast<int>(std::ceil(t_compare_s / (run.dt_over_limit * limit)));
    const double dt = t_compare_s / steps_per_compare;  // <= dt_over_limit x the limit
    snapshots.emplace_back();
    for (int c = 0; c < comparisons; ++c) {
      for (int s = 0; s < steps_per_compare; ++s) solver.step(dt, T, {hot_K}, {hot_K});
      snapshots.back().push_back(T);
    }
  }
  // By the end the bed has taken most of the step (measured 93.5 %): several relaxation
  // times have passed.
  const std::vector<double>& last = snapshots[0].back();
  const double mean_K = std::accumulate(last.begin(), last.end(), 0.0) / static_cast<double>(last.size());
  EXPECT_GT(mean_K, cold_K + 0.9 * (hot_K - cold_K));
  // Largest node difference against explicit at each comparison time: within 0.5 K
  // (of a 896 K step).
  for (std::size_t r = 1; r < snapshots.size(); ++r) {
    for (int c = 0; c < comparisons; ++c) {
      double worst_K = 0.0;
      for (std::size_t i = 0; i < last.size(); ++i)
        worst_K = std::max(worst_K, std::abs(snapshots[r][c][i] - snapshots[0][c][i]));
      EXPECT_LT(worst_K, 0.5) << "method " << static_cast<int>(runs[r].method) << " at " << (c + 1) * t_compare_s
                              << " s";
    }
  }
}

}  // namespace
}  // namespace regodem
