// Powell's trust-region dogleg for F(x) = 0 (MINPACK hybrj; MATLAB fsolve's
// 'trust-region-dogleg'), with the exact Jacobian factorised by the sparse direct solver.
// Internal to src/solvers: use MakeEquationSolver("dogleg", options).
#pragma once

#include <memory>
#include <string>

#include "core/types.h"
#include "solvers/equation_solver.h"
#include "solvers/equation_system.h"
#include "solvers/linear_solver.h"

namespace cb {

// Each iteration tries one step d on the dogleg path inside the radius Delta:
//   Newton step   dN = -J^{-1} F,
//   Cauchy step   dC = -alpha g,  g = J^T F (the gradient of m = 1/2 ||F||^2),
//                 alpha = ||g||^2 / ||J g||^2 (the minimiser of the linear model along -g),
// and judges it by rho = (m(x) - m(x + d)) / (m(x) - 1/2 ||F + J d||^2).
// The step is accepted when rho > accept_ratio. Delta shrinks to 0.25 ||d|| when rho < 0.25
// (0.25 ||d|| rather than 0.25 Delta, so that a rejected Newton step well inside the region
// changes the next trial), and doubles when rho > 0.75 and the step reached the boundary.
//
// SolverSummary::iterations counts every trial step, accepted or rejected, and the callback is
// called once per trial. The Jacobian is evaluated and factorised once per ACCEPTED step:
// while trial steps are rejected the factorisation, dN, g and J g are reused, so
// jacobian_evals = linear_solves <= iterations + 1 (the first factorisation is at x0).
// A singular Jacobian is not fatal: the step is then taken along the Cauchy direction alone.
// A point where g = J^T F vanishes to rounding while J is singular is a stationary point of
// ||F||^2 that is not a root: kFailed.
class DoglegSolver final : public EquationSolver {
 public:
  explicit DoglegSolver(const SolverOptions& options);
  std::string name() const override { return "dogleg"; }
  SolverSummary Solve(EquationSystem& system, Vec* x,
                      const IterationCallback& callback = {}) override;

 private:
  // The scalars of the current linear model, valid until a step is accepted (the vectors are
  // newton_step_, gradient_ = J^T F and j_gradient_ = J g).
  struct Model {
    bool have_newton = false;
    double newton_norm = 0.0;
    double gradient_norm = 0.0;
    double cauchy_alpha = 0.0;  // ||g||^2 / ||J g||^2
    double cauchy_norm = 0.0;   // ||alpha g||
  };

  // The steps of iteration k, as in Ceres' DoglegStrategy. BuildModel: J at x, the Newton step
  // (when J can be factorised) and the Cauchy step; false, with the summary finished, when J is
  // not finite or m is stationary away from a root.
  bool BuildModel(EquationSystem& system, const Vec& x, int k, double merit,
                  SolverSummary* summary);
  // The dogleg step inside `radius` into step_; true when it lies on the boundary.
  bool Step(double radius);
  // Evaluates x + step_ into x_trial_, f_trial_ and *trial_merit, and returns rho, the actual
  // over the predicted reduction (-inf when F cannot be evaluated there).
  double TrialRatio(EquationSystem& system, const Vec& x, double merit, double* trial_merit,
                    SolverSummary* summary);
  // The message of a solve that stagnated at iteration k.
  std::string Stagnation(int k, bool step_too_small) const;

  SolverOptions options_;
  std::unique_ptr<LinearSolver> linear_solver_;
  SpMat jacobian_;
  Vec f_, f_trial_, x_trial_;
  Vec newton_step_, gradient_, j_gradient_, step_, j_step_;
  Model model_;
};

}  // namespace cb
