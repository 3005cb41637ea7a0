#include "solvers/solver_common.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/finite.h"

namespace cb {
namespace internal {

double InfNorm(const Vec& v) { return v.size() == 0 ? 0.0 : v.cwiseAbs().maxCoeff(); }

namespace {

// The checks of an evaluated F(x): its size (a wrong one throws) and finiteness.
bool CheckResidual(const Vec& x, const Vec& f) {
  if (f.size() != x.size()) {
    throw std::invalid_argument("EquationSystem::Residual returned a vector of size " +
                                std::to_string(f.size()) + " for a system of size " +
                                std::to_string(x.size()));
  }
  return f.allFinite();
}

}  // namespace

bool EvaluateResidual(EquationSystem& system, const Vec& x, Vec* f, SolverSummary* summary) {
  ++summary->residual_evals;
  return system.Residual(x, f) && CheckResidual(x, *f);
}

bool EvaluateResidualAndJacobian(EquationSystem& system, const Vec& x, Vec* f, SpMat* jacobian,
                                 SolverSummary* summary) {
  ++summary->residual_evals;
  return system.ResidualAndJacobian(x, f, jacobian) && CheckResidual(x, *f);
}

bool EvaluateJacobian(EquationSystem& system, const Vec& x, SpMat* jacobian,
                      SolverSummary* summary) {
  system.Jacobian(x, jacobian);
  return UseJacobian(x, *jacobian, summary);
}

bool UseJacobian(const Vec& x, const SpMat& jacobian, SolverSummary* summary) {
  ++summary->jacobian_evals;
  if (jacobian.rows() != x.size() || jacobian.cols() != x.size()) {
    throw std::invalid_argument("EquationSystem::Jacobian returned a " +
                                std::to_string(jacobian.rows()) + " x " +
                                std::to_string(jacobian.cols()) + " matrix for a system of size " +
                                std::to_string(x.size()));
  }
  return AllFinite(jacobian.valuePtr(), static_cast<std::size_t>(jacobian.nonZeros()));
}

std::string At(int iteration) { return " at iteration " + std::to_string(iteration); }

std::string LinearFailure(const LinearSolver& solver) {
  return solver.singular() ? "singular Jacobian" : "linear solve failed";
}

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

double NextBacktrackFactor(const SolverOptions& options, double merit, double slope, double a,
                           double trial_merit) {
  // A failed sufficient-decrease test implies c > 0 for either test; the guard covers rounding.
  const double c = (trial_merit - merit - slope * a) / (a * a);
  const double t = c > 0.0 ? -slope / (2.0 * c) : options.backtrack_max * a;
  return std::clamp(t, options.backtrack_min * a, options.backtrack_max * a);
}

LineSearchResult BacktrackingLineSearch(EquationSystem& system, const SolverOptions& options,
                                        DecreaseTest test, const Vec& x, double merit,
                                        double reference_merit, const Vec& dx, Vec* x_trial,
                                        Vec* f_trial, double* merit_trial, SolverSummary* summary,
                                        SpMat* jacobian_trial) {
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
    const bool with_jacobian = jacobian_trial != nullptr && trial == 1;
    const bool evaluated = with_jacobian ? EvaluateResidualAndJacobian(system, *x_trial, f_trial,
                                                                       jacobian_trial, summary)
                                         : EvaluateResidual(system, *x_trial, f_trial, summary);
    if (evaluated) {
      const double m = 0.5 * f_trial->squaredNorm();
      const double bound = test == DecreaseTest::kArmijoNewtonSlope
                               ? reference_merit + options.armijo * a * slope
                               : merit * (1.0 - options.armijo * a) * (1.0 - options.armijo * a);
      if (m <= bound) {
        result.accepted = true;
        result.step = a;
        result.jacobian_at_trial = with_jacobian;
        *merit_trial = m;
        return result;
      }
      a = NextBacktrackFactor(options, merit, slope, a, m);
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

bool WithinResidualFloor(const Vec& f, const Vec* floor, double residual_tol) {
  const bool has_floor = floor != nullptr && floor->size() == f.size();
  for (Eigen::Index i = 0; i < f.size(); ++i) {
    if (!(std::abs(f[i]) <= std::max(residual_tol, has_floor ? (*floor)[i] : 0.0))) return false;
  }
  return true;
}

void FinishStuck(EquationSystem& system, const Vec& x, Status status, std::string message,
                 double merit, const Vec& f, double residual_tol, SolverSummary* summary) {
  Vec floor;
  const bool has_floor = system.ResidualFloor(x, &floor);
  if (has_floor) {
    ++summary->residual_evals;
    ++summary->jacobian_evals;
  }
  if (has_floor && floor.size() == f.size() && WithinResidualFloor(f, &floor, residual_tol)) {
    Finish(Status::kConverged,
           "every row within its rounding floor, ||F||_inf above residual_tol (" + message + ")",
           merit, f, summary);
    return;
  }
  Finish(status, std::move(message), merit, f, summary);
}

bool NewtonDirection(bool jacobian_finite, const SpMat& jacobian, LinearSolver* linear_solver,
                     const std::function<bool(const Vec&, Vec*)>& inverse, int k, double merit,
                     const Vec& f, Vec* dx, SolverSummary* summary) {
  if (!jacobian_finite) {
    Finish(Status::kFailed, "non-finite Jacobian" + At(k), merit, f, summary);
    return false;
  }
  ++summary->linear_solves;
  if (!linear_solver->Factorize(jacobian) || !inverse(f, dx)) {
    Finish(Status::kFailed, LinearFailure(*linear_solver) + At(k) + ": " + linear_solver->message(),
           merit, f, summary);
    return false;
  }
  *dx = -*dx;
  return true;
}

std::string SearchFailure(const LineSearchResult& search, int k, const std::string& after) {
  return search.too_short
             ? "stagnation" + At(k) + ": the line-search step no longer changes x (step_tol)"
             : "line search failed" + At(k) + " after " + std::to_string(search.trials) +
                   " trials" + after;
}

void FinishAtIterationLimit(EquationSystem& system, const Vec& x, const SolverOptions& options,
                            double merit, const Vec& f, SolverSummary* summary) {
  FinishStuck(system, x, Status::kLimitReached,
              "max_iterations (" + std::to_string(options.max_iterations) + ") reached", merit, f,
              options.residual_tol, summary);
}

bool StartSolve(EquationSystem& system, const Vec& x, double residual_tol, Vec* f, double* merit,
                SolverSummary* summary, SpMat* jacobian) {
  const bool evaluated = jacobian != nullptr
                             ? EvaluateResidualAndJacobian(system, x, f, jacobian, summary)
                             : EvaluateResidual(system, x, f, summary);
  if (!evaluated) {
    summary->status = Status::kFailed;
    summary->message = "residual cannot be evaluated (or is not finite) at the initial point";
    return true;
  }
  *merit = 0.5 * f->squaredNorm();
  summary->initial_merit = *merit;
  if (InfNorm(*f) <= residual_tol) {
    Finish(Status::kConverged, "the initial point meets residual_tol", *merit, *f, summary);
    return true;
  }
  return false;
}

bool BeginSolve(EquationSystem& system, const Vec* x, const std::string& solver,
                LinearSolver* linear_solver, std::initializer_list<Vec*> work, double residual_tol,
                Vec* f, double* merit, SolverSummary* summary, SpMat* jacobian) {
  CheckInitialPoint(system, x, solver);
  linear_solver->SetStructure(system.structure());
  const int n = system.size();
  f->resize(n);
  for (Vec* v : work) v->resize(n);
  return StartSolve(system, *x, residual_tol, f, merit, summary, jacobian);
}

bool EndIteration(int k, double merit, const Vec& f, double step_length, const Vec* x,
                  double residual_tol, const IterationCallback& callback, SolverSummary* summary) {
  summary->iterations = k;
  const double residual_inf = InfNorm(f);
  bool keep_going = true;
  if (callback) {
    IterationInfo info;
    info.iteration = k;
    info.merit = merit;
    info.residual_inf = residual_inf;
    info.step_length = step_length;
    info.x = x;
    keep_going = callback(info);
  }
  if (residual_inf <= residual_tol) {
    Finish(Status::kConverged, "||F||_inf <= residual_tol", merit, f, summary);
    return true;
  }
  if (!keep_going) {
    Finish(Status::kStoppedByCaller, "the callback stopped the solve" + At(k), merit, f, summary);
    return true;
  }
  return false;
}

}  // namespace internal

}  // namespace cb
