// Newton's method with a backtracking line search on the merit m(x) = 1/2 ||F(x)||^2. Internal to
// src/solvers: other code reaches the solvers through MakeEquationSolver.
#pragma once

#include <memory>
#include <string>

#include "core/types.h"
#include "solvers/equation_solver.h"
#include "solvers/equation_system.h"
#include "solvers/linear_solver.h"

namespace cb {

// Newton's method: J(x) dx = -F(x) solved by the sparse direct solver (analysed once, refactorised
// every iteration), then a backtracking Armijo line search on m. One Jacobian evaluation and one
// factorisation per iteration; the Jacobian at an accepted full step comes from the same pass as
// its residual (EquationSystem::ResidualAndJacobian). A singular Jacobian ends the solve (kFailed);
// there is no fallback direction, so that the comparison with the other methods stays clean.
class NewtonSolver final : public EquationSolver {
 public:
  explicit NewtonSolver(const SolverOptions& options);
  std::string name() const override { return "newton"; }
  SolverSummary Solve(EquationSystem& system, Vec* x,
                      const IterationCallback& callback = {}) override;

 private:
  // Step 1 of iteration k: J at x (evaluated, or already evaluated with F when jacobian_at_x),
  // factorised, and the Newton direction dx_ = -J^{-1} F. False, with the summary finished,
  // when J is not finite or the linear solve fails.
  bool Direction(EquationSystem& system, const Vec& x, bool jacobian_at_x, int k, double merit,
                 SolverSummary* summary);

  SolverOptions options_;
  std::unique_ptr<LinearSolver> linear_solver_;
  // Kept between iterations and solves so that the Jacobian's storage and the linear solver's
  // symbolic analysis are reused.
  SpMat jacobian_;
  Vec f_, dx_, x_trial_, f_trial_;
};

}  // namespace cb
