#include "solvers/dogleg.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "solvers/solver_common.h"

namespace cb {

DoglegSolver::DoglegSolver(const SolverOptions& options)
    : options_(options), linear_solver_(MakeLinearSolver(options.linear_solver)) {}

bool DoglegSolver::BuildModel(EquationSystem& system, const Vec& x, int k, double merit,
                              SolverSummary* summary) {
  if (!internal::EvaluateJacobian(system, x, &jacobian_, summary)) {
    internal::Finish(Status::kFailed, "non-finite Jacobian" + internal::At(k), merit, f_, summary);
    return false;
  }
  ++summary->linear_solves;
  model_.have_newton =
      linear_solver_->Factorize(jacobian_) && linear_solver_->Solve(f_, &newton_step_);
  if (model_.have_newton) {
    newton_step_ = -newton_step_;
    model_.newton_norm = newton_step_.norm();
  }
  gradient_.noalias() = jacobian_.transpose() * f_;
  j_gradient_.noalias() = jacobian_ * gradient_;
  model_.gradient_norm = gradient_.norm();
  const double j_gradient_norm2 = j_gradient_.squaredNorm();
  // g = J^T F at rounding level relative to ||J|| ||F||: a stationary point of m. With a
  // nonsingular J this cannot happen away from a root (the Newton step still exists).
  double jacobian_norm = 0.0;
  for (Eigen::Index i = 0; i < jacobian_.nonZeros(); ++i) {
    jacobian_norm += jacobian_.valuePtr()[i] * jacobian_.valuePtr()[i];
  }
  jacobian_norm = std::sqrt(jacobian_norm);
  const bool stationary = !(model_.gradient_norm >
                            std::numeric_limits<double>::epsilon() * jacobian_norm * f_.norm()) ||
                          !(j_gradient_norm2 > 0.0);
  if (stationary && !model_.have_newton) {
    internal::Finish(Status::kFailed,
                     internal::LinearFailure(*linear_solver_) + " and J^T F = 0" + internal::At(k) +
                         ": a stationary point of ||F||^2 that is not a root (" +
                         linear_solver_->message() + ")",
                     merit, f_, summary);
    return false;
  }
  model_.cauchy_alpha =
      stationary ? 0.0 : model_.gradient_norm * model_.gradient_norm / j_gradient_norm2;
  model_.cauchy_norm = model_.cauchy_alpha * model_.gradient_norm;
  return true;
}

bool DoglegSolver::Step(double radius) {
  const Model& m = model_;
  if (m.have_newton && m.newton_norm <= radius) {
    step_ = newton_step_;
    return false;
  }
  if (m.cauchy_norm >= radius) {
    step_ = (-radius / m.gradient_norm) * gradient_;
    return true;
  }
  if (!m.have_newton) {
    step_ = -m.cauchy_alpha * gradient_;
    return false;
  }
  // d = dC + tau (dN - dC) with ||d|| = radius, tau in [0, 1]; the root of
  // a tau^2 + b tau + c = 0 taken in the cancellation-free form.
  step_ = -m.cauchy_alpha * gradient_;
  const double cauchy_dot_newton = step_.dot(newton_step_);
  const double qa =
      m.newton_norm * m.newton_norm - 2.0 * cauchy_dot_newton + m.cauchy_norm * m.cauchy_norm;
  const double qb = 2.0 * (cauchy_dot_newton - m.cauchy_norm * m.cauchy_norm);
  const double qc = m.cauchy_norm * m.cauchy_norm - radius * radius;
  const double disc = std::sqrt(std::max(0.0, qb * qb - 4.0 * qa * qc));
  double tau = qb <= 0.0 ? (-qb + disc) / (2.0 * qa) : -2.0 * qc / (qb + disc);
  tau = std::clamp(tau, 0.0, 1.0);
  step_ = (1.0 - tau) * step_ + tau * newton_step_;
  return true;
}

double DoglegSolver::TrialRatio(EquationSystem& system, const Vec& x, double merit,
                                double* trial_merit, SolverSummary* summary) {
  // Predicted reduction of m by the linear model, written without the cancellation of
  // 1/2 ||F||^2 - 1/2 ||F + J d||^2.
  j_step_.noalias() = jacobian_ * step_;
  const double predicted = -f_.dot(j_step_) - 0.5 * j_step_.squaredNorm();
  x_trial_.noalias() = x + step_;
  *trial_merit = 0.0;
  double rho = -std::numeric_limits<double>::infinity();
  if (internal::EvaluateResidual(system, x_trial_, &f_trial_, summary)) {
    *trial_merit = 0.5 * f_trial_.squaredNorm();
    if (predicted > 0.0) rho = (merit - *trial_merit) / predicted;
  }
  return rho;
}

std::string DoglegSolver::Stagnation(int k, bool step_too_small) const {
  const std::string why = model_.have_newton
                              ? std::string()
                              : " (" + internal::LinearFailure(*linear_solver_) +
                                    ", Cauchy steps only: " + linear_solver_->message() + ")";
  return "stagnation" + internal::At(k) +
         (step_too_small ? ": the step no longer changes x (step_tol)"
                         : ": the trust region collapsed below step_tol") +
         why;
}

SolverSummary DoglegSolver::Solve(EquationSystem& system, Vec* x,
                                  const IterationCallback& callback) {
  SolverSummary summary;
  double merit = 0.0;
  if (internal::BeginSolve(
          system, x, name(), linear_solver_.get(),
          {&f_trial_, &x_trial_, &newton_step_, &gradient_, &j_gradient_, &step_, &j_step_},
          options_.residual_tol, &f_, &merit, &summary)) {
    return summary;
  }

  double radius = options_.initial_radius_factor * std::max(1.0, x->norm());
  bool need_jacobian = true;
  model_ = Model();
  for (int k = 1; k <= options_.max_iterations; ++k) {
    if (need_jacobian) {
      need_jacobian = false;
      if (!BuildModel(system, *x, k, merit, &summary)) return summary;
    }
    const bool hit_boundary = Step(radius);
    const double step_norm = step_.norm();
    double trial_merit = 0.0;
    const double rho = TrialRatio(system, *x, merit, &trial_merit, &summary);
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
    const bool collapsed = !accepted && radius <= options_.step_tol * (1.0 + internal::InfNorm(*x));
    if (step_too_small || collapsed) {
      internal::FinishStuck(system, *x, Status::kFailed, Stagnation(k, step_too_small), merit, f_,
                            options_.residual_tol, &summary);
      return summary;
    }
  }
  internal::FinishAtIterationLimit(system, *x, options_, merit, f_, &summary);
  return summary;
}

}  // namespace cb
