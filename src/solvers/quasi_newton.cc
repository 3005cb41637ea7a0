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

bool QuasiNewtonSolver::Refresh(EquationSystem& system, const Vec& x, int k, double merit,
                                SolverSummary* summary) {
  num_updates_ = 0;
  const bool jacobian_finite = internal::EvaluateJacobian(system, x, &jacobian_, summary);
  return internal::NewtonDirection(
      jacobian_finite, jacobian_, linear_solver_.get(),
      [this](const Vec& b, Vec* y) { return ApplyInverse(b, y); }, k, merit, f_, &dx_, summary);
}

bool QuasiNewtonSolver::Search(EquationSystem& system, const Vec& x, int k, double merit,
                               bool* need_refresh, internal::LineSearchResult* search,
                               double* trial_merit, SolverSummary* summary) {
  bool fresh = false;  // dx_ is the Newton direction of a just-factorised J
  for (;;) {
    if (*need_refresh) {
      *need_refresh = false;
      fresh = true;
      if (!Refresh(system, x, k, merit, summary)) return false;
    }
    *search = internal::BacktrackingLineSearch(
        system, options_, internal::DecreaseTest::kNormDecrease, x, merit, merit, dx_, &x_trial_,
        &f_trial_, trial_merit, summary);
    if (search->accepted) return true;
    if (fresh) {
      internal::FinishStuck(
          system, x, Status::kFailed,
          internal::SearchFailure(*search, k, " along the Newton direction of a fresh Jacobian"),
          merit, f_, options_.residual_tol, summary);
      return false;
    }
    // A stale inverse gave a poor direction: retry with the true Jacobian at x.
    *need_refresh = true;
  }
}

bool QuasiNewtonSolver::Update() {
  // Below this |s^T H y| the Sherman-Morrison denominator is rounding noise.
  const double update_guard = std::sqrt(std::numeric_limits<double>::epsilon());
  // The Broyden update and the next direction, from one application of H_k:
  //   w = H_k F_{k+1},  H_k y_k = w + dx_k  (as H_k F_k = -dx_k),
  //   dx_{k+1} = -H_{k+1} F_{k+1} = -(w + p_k (s_k^T w)).
  if (num_updates_ == options_.max_updates || !ApplyInverse(f_, &w_)) return false;
  hy_ = w_ + dx_;
  const double denominator = step_.dot(hy_);
  if (!(std::abs(denominator) > update_guard * step_.norm() * hy_.norm())) return false;
  p_.col(num_updates_) = (step_ - hy_) / denominator;
  s_.col(num_updates_) = step_;
  dx_ = -(w_ + p_.col(num_updates_) * step_.dot(w_));
  ++num_updates_;
  return true;
}

SolverSummary QuasiNewtonSolver::Solve(EquationSystem& system, Vec* x,
                                       const IterationCallback& callback) {
  SolverSummary summary;
  double merit = 0.0;
  p_.resize(system.size(), options_.max_updates);
  s_.resize(system.size(), options_.max_updates);
  num_updates_ = 0;
  if (internal::BeginSolve(system, x, name(), linear_solver_.get(),
                           {&f_trial_, &x_trial_, &dx_, &step_, &w_, &hy_}, options_.residual_tol,
                           &f_, &merit, &summary)) {
    return summary;
  }

  bool need_refresh = true;  // evaluate and factorise J at the current point
  for (int k = 1; k <= options_.max_iterations; ++k) {
    internal::LineSearchResult search;
    double trial_merit = 0.0;
    if (!Search(system, *x, k, merit, &need_refresh, &search, &trial_merit, &summary)) {
      return summary;
    }
    step_ = search.step * dx_;
    *x = x_trial_;
    f_.swap(f_trial_);
    merit = trial_merit;
    if (internal::EndIteration(k, merit, f_, search.step, x, options_.residual_tol, callback,
                               &summary)) {
      return summary;
    }
    need_refresh = !Update();
  }
  internal::FinishAtIterationLimit(system, *x, options_, merit, f_, &summary);
  return summary;
}

}  // namespace cb
