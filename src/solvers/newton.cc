#include "solvers/newton.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace cb {
namespace internal {

double InfNorm(const Vec& v) { return v.size() == 0 ? 0.0 : v.cwiseAbs().maxCoeff(); }

bool EvaluateResidual(EquationSystem& system, const Vec& x, Vec* f, SolverSummary* summary) {
  ++summary->residual_evals;
  if (!system.Residual(x, f)) return false;
  if (f->size() != x.size()) {
    throw std::invalid_argument("EquationSystem::Residual returned a vector of size " +
                                std::to_string(f->size()) + " for a system of size " +
                                std::to_string(x.size()));
  }
  return f->allFinite();
}

bool EvaluateJacobian(EquationSystem& system, const Vec& x, SpMat* jacobian,
                      SolverSummary* summary) {
  ++summary->jacobian_evals;
  system.Jacobian(x, jacobian);
  if (jacobian->rows() != x.size() || jacobian->cols() != x.size()) {
    throw std::invalid_argument("EquationSystem::Jacobian returned a " +
                                std::to_string(jacobian->rows()) + " x " +
                                std::to_string(jacobian->cols()) + " matrix for a system of size " +
                                std::to_string(x.size()));
  }
  const double* values = jacobian->valuePtr();
  return std::all_of(values, values + jacobian->nonZeros(),
                     [](double v) { return std::isfinite(v); });
}

std::string At(int iteration) { return " at iteration " + std::to_string(iteration); }

bool StepTooSmall(const Vec& dx, const Vec& x, double step_tol) {
  return InfNorm(dx) <= step_tol * (1.0 + InfNorm(x));
}

void CheckInitialPoint(const EquationSystem& system, const Vec* x, const std::string& solver) {
  if (x == nullptr) throw std::invalid_argument(solver + ": Solve needs an initial point");
  if (x->size() != system.size()) {
    throw std::invalid_argument(solver + ": initial point has size " + std::to_string(x->size()) +
                                ", the system has size " + std::to_string(system.size()));
  }
}

LineSearchResult BacktrackingLineSearch(EquationSystem& system, const SolverOptions& options,
                                        DecreaseTest test, const Vec& x, double merit,
                                        const Vec& dx, Vec* x_trial, Vec* f_trial,
                                        double* merit_trial, SolverSummary* summary) {
  LineSearchResult result;
  const double dx_inf = InfNorm(dx);
  const double too_short = options.step_tol * (1.0 + InfNorm(x));
  const double slope = -2.0 * merit;  // m'(x; dx) for the exact Newton direction
  double a = 1.0;
  for (int trial = 1; trial <= options.max_backtracks; ++trial) {
    if (a * dx_inf <= too_short) {
      result.too_short = true;
      return result;
    }
    result.trials = trial;
    x_trial->noalias() = x + a * dx;
    const bool evaluated = EvaluateResidual(system, *x_trial, f_trial, summary);
    if (evaluated) {
      const double m = 0.5 * f_trial->squaredNorm();
      const double bound = test == DecreaseTest::kArmijoNewtonSlope
                               ? merit + options.armijo * a * slope
                               : merit * (1.0 - options.armijo * a) * (1.0 - options.armijo * a);
      if (m <= bound) {
        result.accepted = true;
        result.step = a;
        *merit_trial = m;
        return result;
      }
      // Minimiser of q(t) = m(0) + slope t + c t^2 through m(a). A failed sufficient-decrease
      // test implies c > 0 for either test; the guard covers rounding.
      const double c = (m - merit - slope * a) / (a * a);
      const double t = c > 0.0 ? -slope / (2.0 * c) : options.backtrack_max * a;
      a = std::clamp(t, options.backtrack_min * a, options.backtrack_max * a);
    } else {
      a *= std::min(0.5, options.backtrack_max);
    }
  }
  return result;
}

void Finish(Status status, std::string message, double merit, const Vec& f,
            SolverSummary* summary) {
  summary->status = status;
  summary->message = std::move(message);
  summary->final_merit = merit;
  summary->final_residual_inf = InfNorm(f);
}

}  // namespace internal

NewtonSolver::NewtonSolver(const SolverOptions& options)
    : options_(options), linear_solver_(MakeLinearSolver(options.linear_solver)) {}

SolverSummary NewtonSolver::Solve(EquationSystem& system, Vec* x,
                                  const IterationCallback& callback) {
  using internal::Finish;
  internal::CheckInitialPoint(system, x, name());
  const int n = system.size();
  f_.resize(n);
  dx_.resize(n);
  x_trial_.resize(n);
  f_trial_.resize(n);

  SolverSummary summary;
  if (!internal::EvaluateResidual(system, *x, &f_, &summary)) {
    summary.status = Status::kFailed;
    summary.message = "residual cannot be evaluated (or is not finite) at the initial point";
    return summary;
  }
  double merit = 0.5 * f_.squaredNorm();
  summary.initial_merit = merit;
  if (internal::InfNorm(f_) <= options_.residual_tol) {
    Finish(Status::kConverged, "the initial point meets residual_tol", merit, f_, &summary);
    return summary;
  }

  for (int k = 1; k <= options_.max_iterations; ++k) {
    const auto at = [k] { return internal::At(k); };
    if (!internal::EvaluateJacobian(system, *x, &jacobian_, &summary)) {
      Finish(Status::kFailed, "non-finite Jacobian" + at(), merit, f_, &summary);
      return summary;
    }
    ++summary.linear_solves;
    if (!linear_solver_->Factorize(jacobian_)) {
      Finish(Status::kFailed, "singular Jacobian" + at() + ": " + linear_solver_->message(), merit,
             f_, &summary);
      return summary;
    }
    if (!linear_solver_->Solve(f_, &dx_)) {
      Finish(Status::kFailed, "singular Jacobian" + at() + ": " + linear_solver_->message(), merit,
             f_, &summary);
      return summary;
    }
    dx_ = -dx_;

    double trial_merit = 0.0;
    const internal::LineSearchResult search = internal::BacktrackingLineSearch(
        system, options_, internal::DecreaseTest::kArmijoNewtonSlope, *x, merit, dx_, &x_trial_,
        &f_trial_, &trial_merit, &summary);
    if (!search.accepted) {
      Finish(
          Status::kFailed,
          search.too_short
              ? "stagnation" + at() + ": the line-search step no longer changes x (step_tol)"
              : "line search failed" + at() + " after " + std::to_string(search.trials) + " trials",
          merit, f_, &summary);
      return summary;
    }
    *x = x_trial_;
    f_.swap(f_trial_);
    merit = trial_merit;
    summary.iterations = k;

    const double residual_inf = internal::InfNorm(f_);
    bool keep_going = true;
    if (callback) {
      IterationInfo info;
      info.iteration = k;
      info.merit = merit;
      info.residual_inf = residual_inf;
      info.step_length = search.step;
      info.x = x;
      keep_going = callback(info);
    }
    if (residual_inf <= options_.residual_tol) {
      Finish(Status::kConverged, "||F||_inf <= residual_tol", merit, f_, &summary);
      return summary;
    }
    if (!keep_going) {
      Finish(Status::kStoppedByCaller, "the callback stopped the solve" + at(), merit, f_,
             &summary);
      return summary;
    }
  }
  Finish(Status::kLimitReached,
         "max_iterations (" + std::to_string(options_.max_iterations) + ") reached", merit, f_,
         &summary);
  return summary;
}

}  // namespace cb
