// Broyden's quasi-Newton method for F(x) = 0 on top of a factorised sparse Jacobian.
// Internal to src/solvers: use MakeEquationSolver("quasi-newton", options).
#pragma once

#include <memory>
#include <string>

#include "core/types.h"
#include "solvers/equation_solver.h"
#include "solvers/equation_system.h"
#include "solvers/linear_solver.h"
#include "solvers/solver_common.h"

namespace cb {

// Broyden's "good" method in inverse product form. The report's truss examples used a
// csolve/BFGS-like quasi-Newton update; BFGS assumes a symmetric Jacobian, and Broyden's update
// is the standard quasi-Newton method for nonsymmetric equations such as the complementarity
// reformulations here.
//
// With J0 the last factorised Jacobian, the inverse approximation after k updates is
//   H_k = E_{k-1} ... E_0 J0^{-1},   E_j = I + p_j s_j^T,
//   p_j = (s_j - H_j y_j) / (s_j^T H_j y_j),  s_j = x_{j+1} - x_j,  y_j = F_{j+1} - F_j,
// which is the Sherman-Morrison inverse of B_{j+1} = B_j + (y_j - B_j s_j) s_j^T / (s_j^T s_j).
// Only the pairs (p_j, s_j) are stored (limited memory, no dense matrix): applying H_k costs one
// triangular solve with J0 plus O(k n). Each iteration needs a single application, because
// H_j y_j = H_j F_{j+1} + dx_j with dx_j = -H_j F_j the previous direction.
//
// The direction dx = -H F is not known to be a descent direction for m = 1/2 ||F||^2, so the
// line search uses the derivative-free test ||F(x + a dx)|| <= (1 - armijo a) ||F(x)||. When it
// fails, or after max_updates updates, or when an update would divide by ~0, the Jacobian is
// re-evaluated and refactorised at the current point and the updates are dropped; a failure
// with a fresh Jacobian (a true Newton direction) ends the solve. A refresh after a failed line
// search is part of the same iteration: iterations counts accepted steps.
class QuasiNewtonSolver final : public EquationSolver {
 public:
  explicit QuasiNewtonSolver(const SolverOptions& options);
  std::string name() const override { return "quasi-newton"; }
  SolverSummary Solve(EquationSystem& system, Vec* x,
                      const IterationCallback& callback = {}) override;

 private:
  // x = H_k v for the current J0 and the first num_updates_ corrections.
  bool ApplyInverse(const Vec& v, Vec* x);
  // The steps of iteration k. Refresh: J evaluated at x and factorised, the updates dropped, and
  // dx_ the Newton direction; false, with the summary finished, when that fails.
  bool Refresh(EquationSystem& system, const Vec& x, int k, double merit, SolverSummary* summary);
  // The line search along dx_, refreshing first when *need_refresh and once more when a stale
  // direction fails; false, with the summary finished, when a fresh direction fails too.
  bool Search(EquationSystem& system, const Vec& x, int k, double merit, bool* need_refresh,
              internal::LineSearchResult* search, double* trial_merit, SolverSummary* summary);
  // After an accepted step step_: the Broyden update and the next direction dx_; false when J
  // must be refreshed instead (the updates are used up, or the update is ill-conditioned).
  bool Update();

  SolverOptions options_;
  std::unique_ptr<LinearSolver> linear_solver_;
  SpMat jacobian_;
  Vec f_, f_trial_, x_trial_, dx_, step_, w_, hy_;
  Mat p_, s_;  // n x max_updates: the stored correction pairs, one per column
  int num_updates_ = 0;
};

}  // namespace cb
