#include "solvers/dogleg.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "solvers/solver_common.h"

namespace cb {

DoglegSolver::DoglegSolver(const SolverOptions& options)
    : options_(options), linear_solver_(MakeLinearSolver(options.linear_solver)) {}

SolverSummary DoglegSolver::Solve(EquationSystem& system, Vec* x,
                                  const IterationCallback& callback) {
  using internal::Finish;
  using internal::FinishStuck;
  using internal::InfNorm;
  internal::CheckInitialPoint(system, x, name());
  linear_solver_->SetStructure(system.structure());
  const int n = system.size();
  f_.resize(n);
  f_trial_.resize(n);
  x_trial_.resize(n);
  newton_step_.resize(n);
  gradient_.resize(n);
  j_gradient_.resize(n);
  step_.resize(n);
  j_step_.resize(n);

  SolverSummary summary;
  double merit = 0.0;
  if (internal::StartSolve(system, *x, options_.residual_tol, &f_, &merit, &summary)) {
    return summary;
  }

  double radius = options_.initial_radius_factor * std::max(1.0, x->norm());
  bool need_jacobian = true;
  // Quantities of the current linear model, valid until a step is accepted.
  bool have_newton = false;
  double newton_norm = 0.0;
  double gradient_norm = 0.0;
  double cauchy_alpha = 0.0;  // ||g||^2 / ||J g||^2
  double cauchy_norm = 0.0;   // ||alpha g||

  for (int k = 1; k <= options_.max_iterations; ++k) {
    const auto at = [k] { return internal::At(k); };
    if (need_jacobian) {
      need_jacobian = false;
      if (!internal::EvaluateJacobian(system, *x, &jacobian_, &summary)) {
        Finish(Status::kFailed, "non-finite Jacobian" + at(), merit, f_, &summary);
        return summary;
      }
      ++summary.linear_solves;
      have_newton =
          linear_solver_->Factorize(jacobian_) && linear_solver_->Solve(f_, &newton_step_);
      if (have_newton) {
        newton_step_ = -newton_step_;
        newton_norm = newton_step_.norm();
      }
      gradient_.noalias() = jacobian_.transpose() * f_;
      j_gradient_.noalias() = jacobian_ * gradient_;
      gradient_norm = gradient_.norm();
      const double j_gradient_norm2 = j_gradient_.squaredNorm();
      // g = J^T F at rounding level relative to ||J|| ||F||: a stationary point of m. With a
      // nonsingular J this cannot happen away from a root (the Newton step still exists).
      double jacobian_norm = 0.0;
      for (Eigen::Index i = 0; i < jacobian_.nonZeros(); ++i) {
        jacobian_norm += jacobian_.valuePtr()[i] * jacobian_.valuePtr()[i];
      }
      jacobian_norm = std::sqrt(jacobian_norm);
      const bool stationary =
          !(gradient_norm > std::numeric_limits<double>::epsilon() * jacobian_norm * f_.norm()) ||
          !(j_gradient_norm2 > 0.0);
      if (stationary && !have_newton) {
        Finish(Status::kFailed,
               internal::LinearFailure(*linear_solver_) + " and J^T F = 0" + at() +
                   ": a stationary point of ||F||^2 that is not a root (" +
                   linear_solver_->message() + ")",
               merit, f_, &summary);
        return summary;
      }
      cauchy_alpha = stationary ? 0.0 : gradient_norm * gradient_norm / j_gradient_norm2;
      cauchy_norm = cauchy_alpha * gradient_norm;
    }

    // The dogleg step inside the radius.
    bool hit_boundary = true;
    if (have_newton && newton_norm <= radius) {
      step_ = newton_step_;
      hit_boundary = false;
    } else if (cauchy_norm >= radius) {
      step_ = (-radius / gradient_norm) * gradient_;
    } else if (!have_newton) {
      step_ = -cauchy_alpha * gradient_;
      hit_boundary = false;
    } else {
      // d = dC + tau (dN - dC) with ||d|| = radius, tau in [0, 1]; the root of
      // a tau^2 + b tau + c = 0 taken in the cancellation-free form.
      step_ = -cauchy_alpha * gradient_;
      const double cauchy_dot_newton = step_.dot(newton_step_);
      const double qa =
          newton_norm * newton_norm - 2.0 * cauchy_dot_newton + cauchy_norm * cauchy_norm;
      const double qb = 2.0 * (cauchy_dot_newton - cauchy_norm * cauchy_norm);
      const double qc = cauchy_norm * cauchy_norm - radius * radius;
      const double disc = std::sqrt(std::max(0.0, qb * qb - 4.0 * qa * qc));
      double tau = qb <= 0.0 ? (-qb + disc) / (2.0 * qa) : -2.0 * qc / (qb + disc);
      tau = std::clamp(tau, 0.0, 1.0);
      step_ = (1.0 - tau) * step_ + tau * newton_step_;
    }
    const double step_norm = step_.norm();

    // Predicted reduction of m by the linear model, written without the cancellation of
    // 1/2 ||F||^2 - 1/2 ||F + J d||^2.
    j_step_.noalias() = jacobian_ * step_;
    const double predicted = -f_.dot(j_step_) - 0.5 * j_step_.squaredNorm();
    x_trial_.noalias() = *x + step_;
    double trial_merit = 0.0;
    double rho = -std::numeric_limits<double>::infinity();
    if (internal::EvaluateResidual(system, x_trial_, &f_trial_, &summary)) {
      trial_merit = 0.5 * f_trial_.squaredNorm();
      if (predicted > 0.0) rho = (merit - trial_merit) / predicted;
    }

    if (rho < 0.25) {
      radius = 0.25 * step_norm;
    } else if (rho > 0.75 && hit_boundary) {
      radius = 2.0 * radius;
    }
    const bool accepted = rho > options_.accept_ratio;
    const bool step_too_small = internal::StepTooSmall(step_, *x, options_.step_tol);
    if (accepted) {
      *x = x_trial_;
      f_.swap(f_trial_);
      merit = trial_merit;
      need_jacobian = true;
    }
    // (A rejected dogleg trial leaves F unchanged, so it cannot meet the tolerance here.)
    if (internal::EndIteration(k, merit, f_, step_norm, x, options_.residual_tol, callback,
                               &summary)) {
      return summary;
    }
    const bool collapsed = !accepted && radius <= options_.step_tol * (1.0 + InfNorm(*x));
    if (step_too_small || collapsed) {
      const std::string why = have_newton
                                  ? std::string()
                                  : " (" + internal::LinearFailure(*linear_solver_) +
                                        ", Cauchy steps only: " + linear_solver_->message() + ")";
      FinishStuck(system, *x, Status::kFailed,
                  "stagnation" + at() +
                      (step_too_small ? ": the step no longer changes x (step_tol)"
                                      : ": the trust region collapsed below step_tol") +
                      why,
                  merit, f_, options_.residual_tol, &summary);
      return summary;
    }
  }
  FinishStuck(system, *x, Status::kLimitReached,
              "max_iterations (" + std::to_string(options_.max_iterations) + ") reached", merit, f_,
              options_.residual_tol, &summary);
  return summary;
}

}  // namespace cb
