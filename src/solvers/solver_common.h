// The pieces the equation solvers share: counted residual and Jacobian evaluation, the
// backtracking line search, the stagnation test, and the bookkeeping at the start of a solve and
// at the end of each iteration. Internal to src/solvers: other code reaches the solvers through
// MakeEquationSolver.
#pragma once

#include <functional>
#include <initializer_list>
#include <string>

#include "core/types.h"
#include "solvers/equation_solver.h"
#include "solvers/equation_system.h"
#include "solvers/linear_solver.h"

namespace cb {
namespace internal {

// ||v||_inf, zero for an empty vector (Eigen's maxCoeff asserts on one).
double InfNorm(const Vec& v);

// Evaluates F(x) into *f and counts it in summary->residual_evals. Returns false when the
// system says F cannot be evaluated or when F has non-finite entries: either way the point is
// unusable. Throws std::invalid_argument when the system returns a vector of the wrong size.
bool EvaluateResidual(EquationSystem& system, const Vec& x, Vec* f, SolverSummary* summary);

// EvaluateResidual through EquationSystem::ResidualAndJacobian: *jacobian is J(x) as well when
// it returns true. The Jacobian is counted only when a solver uses it (UseJacobian), so that a
// Jacobian evaluated ahead and not needed (the point was rejected, or met the test) does not
// count.
bool EvaluateResidualAndJacobian(EquationSystem& system, const Vec& x, Vec* f, SpMat* jacobian,
                                 SolverSummary* summary);

// Evaluates J(x) into *jacobian and counts it. Returns false when J has a non-finite entry;
// throws std::invalid_argument when the system returns a matrix that is not n x n.
bool EvaluateJacobian(EquationSystem& system, const Vec& x, SpMat* jacobian,
                      SolverSummary* summary);
// The checks and the count of EvaluateJacobian, for a Jacobian already evaluated at x.
bool UseJacobian(const Vec& x, const SpMat& jacobian, SolverSummary* summary);

// " at iteration k", for messages (built only when a solve ends).
std::string At(int iteration);
// "singular Jacobian" when the linear solver found the Jacobian singular, otherwise "linear solve
// failed" (out of memory, a backend error: its message says which).
std::string LinearFailure(const LinearSolver& solver);

// True when a step dx taken from x is too small to change x: ||dx||_inf <= step_tol (1 +
// ||x||_inf).
bool StepTooSmall(const Vec& dx, const Vec& x, double step_tol);

// Throws std::invalid_argument unless x is non-null and has the system's size.
void CheckInitialPoint(const EquationSystem& system, const Vec* x, const std::string& solver);

// Sufficient-decrease tests of the backtracking line search at a trial factor a.
enum class DecreaseTest {
  // Armijo on m with the Newton slope m'(x; dx) = -||F||^2 (exact for dx = -J^{-1} F),
  // from a reference merit m_ref >= m(x) (m(x) itself for a monotone search):
  //   m(x + a dx) <= m_ref - 2 armijo a m(x).
  kArmijoNewtonSlope,
  // Derivative-free decrease of the norm (Griewank; Li and Fukushima), for directions that
  // are not known to be descent directions (quasi-Newton):
  //   ||F(x + a dx)|| <= (1 - armijo a) ||F(x)||.
  kNormDecrease,
};

struct LineSearchResult {
  bool accepted = false;
  double step = 0.0;  // the accepted factor a
  int trials = 0;
  bool too_short = false;          // gave up because a dx no longer changes x (stagnation)
  bool jacobian_at_trial = false;  // *jacobian_trial holds J at the accepted point
};

// Backtracking from a = 1 along dx, with the Armijo test measured from reference_merit >= merit
// (the nonmonotone test of SolverOptions::nonmonotone_window; merit for a monotone search; the
// norm-decrease test always uses merit).. A trial whose residual cannot be evaluated is a failed
// trial; the factor is then halved (capped by backtrack_max), since there is no value to
// interpolate. Otherwise the next factor minimises the quadratic through m(0), the Newton slope
// -2 m(0) and m(a), clipped to [backtrack_min, backtrack_max] * a, so a wrong slope (a
// quasi-Newton direction) cannot make the search stall or jump. On acceptance *x_trial,
// *f_trial, *merit_trial hold the accepted point. With jacobian_trial, the full step a = 1 is
// evaluated with its Jacobian in one pass (EvaluateResidualAndJacobian), for Newton's next
// iteration if that step is accepted (result.jacobian_at_trial).
// The next factor of a backtracking search whose trial at factor a had merit `trial_merit`:
// the minimiser of q(t) = m(0) + slope t + c t^2 through m(a), clipped to [backtrack_min,
// backtrack_max] * a (BacktrackingLineSearch; shared with the distributed Newton's search).
double NextBacktrackFactor(const SolverOptions& options, double merit, double slope, double a,
                           double trial_merit);

LineSearchResult BacktrackingLineSearch(EquationSystem& system, const SolverOptions& options,
                                        DecreaseTest test, const Vec& x, double merit,
                                        double reference_merit, const Vec& dx, Vec* x_trial,
                                        Vec* f_trial, double* merit_trial, SolverSummary* summary,
                                        SpMat* jacobian_trial = nullptr);

// Fills the summary's final fields and status.
void Finish(Status status, std::string message, double merit, const Vec& f, SolverSummary* summary);
// Whether every |F_i| is within max(residual_tol, floor_i) (floor_i = 0 where `floor` is null or
// of another size than f).
bool WithinResidualFloor(const Vec& f, const Vec* floor, double residual_tol);
// Finish for a solver that cannot go on at x (stagnation, a failed line search, the iteration
// limit): kConverged instead of `status` when every |F_i| is within max(residual_tol, floor_i)
// of EquationSystem::ResidualFloor, with `message` kept in the summary's message; the floor's
// evaluation is counted as one residual and one Jacobian evaluation.
void FinishStuck(EquationSystem& system, const Vec& x, Status status, std::string message,
                 double merit, const Vec& f, double residual_tol, SolverSummary* summary);

// The Newton direction dx = -J^{-1} F of iteration k once J is evaluated (`jacobian_finite` says
// whether it is usable): counts the linear solve, factorises J and applies `inverse` (the
// factorisation's solve, or an inverse built on it) to F. False, with the summary finished,
// when J is not finite or the factorisation or the solve fails.
bool NewtonDirection(bool jacobian_finite, const SpMat& jacobian, LinearSolver* linear_solver,
                     const std::function<bool(const Vec&, Vec*)>& inverse, int k, double merit,
                     const Vec& f, Vec* dx, SolverSummary* summary);

// Why a line search that accepted no point ended, for FinishStuck: stagnation (the step no
// longer changes x) or the failure after its trials, with `after` appended to the latter.
std::string SearchFailure(const LineSearchResult& search, int k, const std::string& after);
// FinishStuck with kLimitReached when the iteration limit is reached.
void FinishAtIterationLimit(EquationSystem& system, const Vec& x, const SolverOptions& options,
                            double merit, const Vec& f, SolverSummary* summary);

// The start of every solve: evaluates F at the initial point into *f and *merit, and records the
// initial merit. Returns true when the solve is already over: F cannot be evaluated there
// (kFailed) or it meets residual_tol (kConverged). With jacobian, J(x) is evaluated in the same
// pass (EvaluateResidualAndJacobian).
bool StartSolve(EquationSystem& system, const Vec& x, double residual_tol, Vec* f, double* merit,
                SolverSummary* summary, SpMat* jacobian = nullptr);

// The prologue the solvers share (Newton, dogleg, quasi-Newton): checks the initial point
// (CheckInitialPoint, naming `solver`), hands the linear solver the system's Jacobian structure,
// sizes *f and every vector of `work` to the system, then StartSolve. Returns true when the solve
// is already over (StartSolve).
bool BeginSolve(EquationSystem& system, const Vec* x, const std::string& solver,
                LinearSolver* linear_solver, std::initializer_list<Vec*> work, double residual_tol,
                Vec* f, double* merit, SolverSummary* summary, SpMat* jacobian = nullptr);

// The end of every accepted iteration k: records it, reports it to the callback, and returns
// true when the solve is over, because ||F||_inf <= residual_tol (kConverged, which wins over a
// callback's stop in the same iteration) or because the callback asked to stop.
bool EndIteration(int k, double merit, const Vec& f, double step_length, const Vec* x,
                  double residual_tol, const IterationCallback& callback, SolverSummary* summary);

}  // namespace internal

}  // namespace cb
