// Powell's trust-region dogleg for F(x) = 0 (MINPACK hybrj; MATLAB fsolve's
// 'trust-region-dogleg'), with the exact Jacobian factorised by the sparse direct solver.
// Internal to src/solvers: use MakeEquationSolver("dogleg", options).
#pragma once

#include <memory>
#include <string>

#include "core/types.h"
#include "solvers/equation_solver.h"
#include "solvers/equation_system.h"
#include "solvers/linear_solver.h"

namespace cb {

// Each iteration tries one step d on the dogleg path inside the radius Delta:
//   Newton step   dN = -J^{-1} F,
//   Cauchy step   dC = -alpha g,  g = J^T F (the gradient of m = 1/2 ||F||^2),
//                 alpha = ||g||^2 / ||J g||^2 (the minimiser of the linear model along -g),
// and judges it by rho = (m(x) - m(x + d)) / (m(x) - 1/2 ||F + J d||^2).
// The step is accepted when rho > accept_ratio. Delta shrinks to 0.25 ||d|| when rho < 0.25
// (0.25 ||d|| rather than 0.25 Delta, so that a rejected Newton step well inside the region
// changes the next trial), and doubles when rho > 0.75 and the step reached the boundary.
//
// SolverSummary::iterations counts every trial step, accepted or rejected, and the callback is
// called once per trial. The Jacobian is evaluated and factorised once per ACCEPTED step:
// while trial steps are rejected the factorisation, dN, g and J g are reused, so
// jacobian_evals = linear_solves <= iterations + 1 (the first factorisation is at x0).
// A singular Jacobian is not fatal: the step is then taken along the Cauchy direction alone.
// A point where g = J^T F vanishes to rounding while J is singular is a stationary point of
// ||F||^2 that is not a root: kFailed.
class DoglegSolver final : public EquationSolver {
 public:
  explicit DoglegSolver(const SolverOptions& options);
  std::string name() const override { return "dogleg"; }
  SolverSummary Solve(EquationSystem& system, Vec* x,
                      const IterationCallback& callback = {}) override;

 private:
  SolverOptions options_;
  std::unique_ptr<LinearSolver> linear_solver_;
  SpMat jacobian_;
  Vec f_, f_trial_, x_trial_;
  Vec newton_step_, gradient_, j_gradient_, step_, j_step_;
};

}  // namespace cb
