#include "solvers/newton.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "solvers/nonmonotone_reference.h"
#include "solvers/solver_common.h"

namespace cb {

NewtonSolver::NewtonSolver(const SolverOptions& options)
    : options_(options), linear_solver_(MakeLinearSolver(options.linear_solver)) {}

bool NewtonSolver::Direction(EquationSystem& system, const Vec& x, bool jacobian_at_x, int k,
                             double merit, SolverSummary* summary) {
  const bool jacobian_finite = jacobian_at_x
                                   ? internal::UseJacobian(x, jacobian_, summary)
                                   : internal::EvaluateJacobian(system, x, &jacobian_, summary);
  return internal::NewtonDirection(
      jacobian_finite, jacobian_, linear_solver_.get(),
      [this](const Vec& b, Vec* x) { return linear_solver_->Solve(b, x); }, k, merit, f_, &dx_,
      summary);
}

SolverSummary NewtonSolver::Solve(EquationSystem& system, Vec* x,
                                  const IterationCallback& callback) {
  SolverSummary summary;
  double merit = 0.0;
  // When the system shares work between them, J(x) comes with F(x) from one pass wherever it
  // will likely be needed: at the start, and at a full step after the previous full step was
  // accepted (a damped search rarely ends at a = 1, so its first trial is evaluated alone). The
  // trial's Jacobian overwrites jacobian_, which the iteration no longer needs once the step is
  // solved for (no second matrix is kept).
  SpMat* const one_pass = system.shares_residual_and_jacobian() ? &jacobian_ : nullptr;
  if (internal::BeginSolve(system, x, name(), linear_solver_.get(), {&dx_, &x_trial_, &f_trial_},
                           options_.residual_tol, &f_, &merit, &summary, one_pass)) {
    return summary;
  }
  bool jacobian_at_x = one_pass != nullptr;

  NonmonotoneReference reference(options_.nonmonotone_window, merit);
  for (int k = 1; k <= options_.max_iterations; ++k) {
    if (!Direction(system, *x, jacobian_at_x, k, merit, &summary)) return summary;
    double trial_merit = 0.0;
    const internal::LineSearchResult search = internal::BacktrackingLineSearch(
        system, options_, internal::DecreaseTest::kArmijoNewtonSlope, *x, merit,
        reference.Reference(merit), dx_, &x_trial_, &f_trial_, &trial_merit, &summary,
        reference.last_step_full() ? one_pass : nullptr);
    if (!search.accepted) {
      internal::FinishStuck(system, *x, Status::kFailed, internal::SearchFailure(search, k, ""),
                            merit, f_, options_.residual_tol, &summary);
      return summary;
    }
    *x = x_trial_;
    f_.swap(f_trial_);
    jacobian_at_x = search.jacobian_at_trial;
    merit = trial_merit;
    reference.Accept(merit, search.step);
    if (internal::EndIteration(k, merit, f_, search.step, x, options_.residual_tol, callback,
                               &summary)) {
      return summary;
    }
  }
  internal::FinishAtIterationLimit(system, *x, options_, merit, f_, &summary);
  return summary;
}

}  // namespace cb
