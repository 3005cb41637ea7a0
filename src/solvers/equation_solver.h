// Newton-type solvers for F(x) = 0 on an EquationSystem: Newton with a backtracking line
// search, a trust-region dogleg, and a Broyden quasi-Newton method. Options / Summary in the
// manner of Ceres Solver::Options / Solver::Summary.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/types.h"
#include "solvers/equation_system.h"
#include "solvers/linear_solver.h"

namespace cb {

struct SolverOptions {
  // Converged when ||F(x)||_inf <= residual_tol (the formulation's own stopping test; the
  // harness's verdict judges the answer independently).
  double residual_tol = 1e-10;
  // Outer iterations: Newton steps, accepted or rejected dogleg trial steps, quasi-Newton steps.
  int max_iterations = 200;
  // Stop with kFailed when a step changes x by less than step_tol * (1 + ||x||_inf) in the
  // inf-norm while F is not yet small (stagnation).
  double step_tol = 1e-15;

  // Line search (newton, quasi-newton): Armijo sufficient decrease
  //   m(x + a dx) <= m(x) + armijo * a * m'(x; dx),  m = 1/2 ||F||^2,
  // backtracking by safeguarded quadratic interpolation, at most max_backtracks trials.
  double armijo = 1e-4;
  int max_backtracks = 40;
  // Interpolated step factors are clipped to [backtrack_min, backtrack_max] times the last.
  double backtrack_min = 0.1;
  double backtrack_max = 0.5;
  // Newton's stall guard: once two iterations in a row had their full step rejected, the
  // sufficient decrease is measured from the largest merit of the last nonmonotone_window
  // iterates instead of the current one, for the rest of the solve (the nonmonotone test of
  // Grippo, Lampariello and Lucidi, SIAM J. Numer. Anal. 23 (1986)); 1 keeps the search
  // monotone. On the smoothed path from a cold start the full step can raise m ~10x for a few
  // iterations on its way to the quadratic phase; a monotone search then takes steps of
  // backtrack_min, each lowering m by only 19%. Solves whose full steps are accepted (most warm
  // path steps) keep the monotone test, which does not let an iterate wander off towards
  // another solution (another branch of the path).
  int nonmonotone_window = 5;

  // Trust-region dogleg: initial radius = initial_radius_factor * max(1, ||x0||_2); a step is
  // accepted when actual/predicted reduction of m exceeds accept_ratio.
  double initial_radius_factor = 1.0;
  double accept_ratio = 1e-4;

  // Quasi-Newton: Broyden ("good") updates of the inverse Jacobian on top of one factorised
  // Jacobian; after max_updates updates, or when a line search fails, the Jacobian is
  // re-evaluated and refactorised.
  int max_updates = 20;

  // Sparse direct solver, one of LinearSolverNames().
  std::string linear_solver = DefaultLinearSolverName();

  // Returns true when every field is in range; otherwise false with the reason in *why.
  bool IsValid(std::string* why) const;
};

// What a solver reports after each iteration (observation only).
struct IterationInfo {
  int iteration = 0;
  double merit = 0.0;         // 1/2 ||F||^2 after the iteration
  double residual_inf = 0.0;  // ||F||_inf after the iteration
  double step_length = 0.0;   // line-search factor (newton, quasi-newton) or ||dx|| (dogleg)
  const Vec* x = nullptr;     // the iterate
};
// Return false to stop the solve (Status::kStoppedByCaller).
using IterationCallback = std::function<bool(const IterationInfo&)>;

struct SolverSummary {
  Status status = Status::kNotRun;
  std::string message;
  int iterations = 0;
  int residual_evals = 0;
  int jacobian_evals = 0;  // Jacobians used (one evaluated ahead, with a residual, and not
                           // needed is not counted: EquationSystem::ResidualAndJacobian)
  int linear_solves = 0;   // numerical factorisations
  double initial_merit = 0.0;
  double final_merit = 0.0;
  double final_residual_inf = 0.0;
};

class EquationSolver {
 public:
  virtual ~EquationSolver() = default;
  virtual std::string name() const = 0;
  // Solves from *x (the initial point), leaving the last accepted iterate in *x. The solver
  // object may be reused for many systems with the same pattern: its linear solver keeps the
  // symbolic analysis. Throws std::invalid_argument when x has the wrong size.
  virtual SolverSummary Solve(EquationSystem& system, Vec* x,
                              const IterationCallback& callback = {}) = 0;
};

// Names accepted by MakeEquationSolver: "newton", "dogleg", "quasi-newton".
std::vector<std::string> EquationSolverNames();
// Throws std::invalid_argument for an unknown name (listing the valid ones) or invalid options.
std::unique_ptr<EquationSolver> MakeEquationSolver(const std::string& name,
                                                   const SolverOptions& options);

}  // namespace cb
