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

SolverSummary NewtonSolver::Solve(EquationSystem& system, Vec* x,
                                  const IterationCallback& callback) {
  using internal::Finish;
  using internal::FinishStuck;
  internal::CheckInitialPoint(system, x, name());
  linear_solver_->SetStructure(system.structure());
  const int n = system.size();
  f_.resize(n);
  dx_.resize(n);
  x_trial_.resize(n);
  f_trial_.resize(n);

  SolverSummary summary;
  double merit = 0.0;
  // When the system shares work between them, J(x) comes with F(x) from one pass wherever it
  // will likely be needed: at the start, and at a full step after the previous full step was
  // accepted (a damped search rarely ends at a = 1, so its first trial is evaluated alone). The
  // trial's Jacobian overwrites jacobian_, which the iteration no longer needs once the step is
  // solved for (no second matrix is kept).
  SpMat* const one_pass = system.shares_residual_and_jacobian() ? &jacobian_ : nullptr;
  if (internal::StartSolve(system, *x, options_.residual_tol, &f_, &merit, &summary, one_pass)) {
    return summary;
  }
  bool jacobian_at_x = one_pass != nullptr;

  NonmonotoneReference reference(options_.nonmonotone_window, merit);
  for (int k = 1; k <= options_.max_iterations; ++k) {
    const auto at = [k] { return internal::At(k); };
    const bool jacobian_finite = jacobian_at_x
                                     ? internal::UseJacobian(*x, jacobian_, &summary)
                                     : internal::EvaluateJacobian(system, *x, &jacobian_, &summary);
    if (!jacobian_finite) {
      Finish(Status::kFailed, "non-finite Jacobian" + at(), merit, f_, &summary);
      return summary;
    }
    ++summary.linear_solves;
    if (!linear_solver_->Factorize(jacobian_) || !linear_solver_->Solve(f_, &dx_)) {
      Finish(Status::kFailed,
             internal::LinearFailure(*linear_solver_) + at() + ": " + linear_solver_->message(),
             merit, f_, &summary);
      return summary;
    }
    dx_ = -dx_;

    double trial_merit = 0.0;
    const internal::LineSearchResult search = internal::BacktrackingLineSearch(
        system, options_, internal::DecreaseTest::kArmijoNewtonSlope, *x, merit,
        reference.Reference(merit), dx_, &x_trial_, &f_trial_, &trial_merit, &summary,
        reference.last_step_full() ? one_pass : nullptr);
    if (!search.accepted) {
      FinishStuck(
          system, *x, Status::kFailed,
          search.too_short
              ? "stagnation" + at() + ": the line-search step no longer changes x (step_tol)"
              : "line search failed" + at() + " after " + std::to_string(search.trials) + " trials",
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
  FinishStuck(system, *x, Status::kLimitReached,
              "max_iterations (" + std::to_string(options_.max_iterations) + ") reached", merit, f_,
              options_.residual_tol, &summary);
  return summary;
}

}  // namespace cb
