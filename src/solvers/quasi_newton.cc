#include "solvers/quasi_newton.h"

#include <cmath>
#include <limits>
#include <string>

#include "solvers/solver_common.h"

namespace cb {

QuasiNewtonSolver::QuasiNewtonSolver(const SolverOptions& options)
    : options_(options), linear_solver_(MakeLinearSolver(options.linear_solver)) {}

bool QuasiNewtonSolver::ApplyInverse(const Vec& v, Vec* x) {
  if (!linear_solver_->Solve(v, x)) return false;
  // The corrections act in the order they were made: H_k = E_{k-1} ... E_0 J0^{-1}.
  for (int j = 0; j < num_updates_; ++j) {
    const double c = s_.col(j).dot(*x);
    *x += c * p_.col(j);
  }
  return true;
}

SolverSummary QuasiNewtonSolver::Solve(EquationSystem& system, Vec* x,
                                       const IterationCallback& callback) {
  using internal::Finish;
  using internal::FinishStuck;
  internal::CheckInitialPoint(system, x, name());
  linear_solver_->SetStructure(system.structure());
  const int n = system.size();
  f_.resize(n);
  f_trial_.resize(n);
  x_trial_.resize(n);
  dx_.resize(n);
  step_.resize(n);
  w_.resize(n);
  hy_.resize(n);
  p_.resize(n, options_.max_updates);
  s_.resize(n, options_.max_updates);
  num_updates_ = 0;

  SolverSummary summary;
  double merit = 0.0;
  if (internal::StartSolve(system, *x, options_.residual_tol, &f_, &merit, &summary)) {
    return summary;
  }

  // Below this |s^T H y| the Sherman-Morrison denominator is rounding noise.
  const double update_guard = std::sqrt(std::numeric_limits<double>::epsilon());
  bool need_refresh = true;  // evaluate and factorise J at the current point
  bool fresh = false;        // dx_ is the Newton direction of a just-factorised J
  for (int k = 1; k <= options_.max_iterations; ++k) {
    const auto at = [k] { return internal::At(k); };
    internal::LineSearchResult search;
    double trial_merit = 0.0;
    for (;;) {
      if (need_refresh) {
        need_refresh = false;
        fresh = true;
        num_updates_ = 0;
        if (!internal::EvaluateJacobian(system, *x, &jacobian_, &summary)) {
          Finish(Status::kFailed, "non-finite Jacobian" + at(), merit, f_, &summary);
          return summary;
        }
        ++summary.linear_solves;
        if (!linear_solver_->Factorize(jacobian_) || !ApplyInverse(f_, &dx_)) {
          Finish(Status::kFailed,
                 internal::LinearFailure(*linear_solver_) + at() + ": " + linear_solver_->message(),
                 merit, f_, &summary);
          return summary;
        }
        dx_ = -dx_;
      }
      search = internal::BacktrackingLineSearch(
          system, options_, internal::DecreaseTest::kNormDecrease, *x, merit, merit, dx_, &x_trial_,
          &f_trial_, &trial_merit, &summary);
      if (search.accepted) break;
      if (fresh) {
        FinishStuck(
            system, *x, Status::kFailed,
            search.too_short
                ? "stagnation" + at() + ": the line-search step no longer changes x (step_tol)"
                : "line search failed" + at() + " after " + std::to_string(search.trials) +
                      " trials along the Newton direction of a fresh Jacobian",
            merit, f_, options_.residual_tol, &summary);
        return summary;
      }
      // A stale inverse gave a poor direction: retry with the true Jacobian at x.
      need_refresh = true;
    }
    step_ = search.step * dx_;
    *x = x_trial_;
    f_.swap(f_trial_);
    merit = trial_merit;
    if (internal::EndIteration(k, merit, f_, search.step, x, options_.residual_tol, callback,
                               &summary)) {
      return summary;
    }

    // The Broyden update and the next direction, from one application of H_k:
    //   w = H_k F_{k+1},  H_k y_k = w + dx_k  (as H_k F_k = -dx_k),
    //   dx_{k+1} = -H_{k+1} F_{k+1} = -(w + p_k (s_k^T w)).
    fresh = false;
    if (num_updates_ == options_.max_updates || !ApplyInverse(f_, &w_)) {
      need_refresh = true;
      continue;
    }
    hy_ = w_ + dx_;
    const double denominator = step_.dot(hy_);
    if (!(std::abs(denominator) > update_guard * step_.norm() * hy_.norm())) {
      need_refresh = true;
      continue;
    }
    p_.col(num_updates_) = (step_ - hy_) / denominator;
    s_.col(num_updates_) = step_;
    dx_ = -(w_ + p_.col(num_updates_) * step_.dot(w_));
    ++num_updates_;
  }
  FinishStuck(system, *x, Status::kLimitReached,
              "max_iterations (" + std::to_string(options_.max_iterations) + ") reached", merit, f_,
              options_.residual_tol, &summary);
  return summary;
}

}  // namespace cb
