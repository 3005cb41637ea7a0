// The nonsmooth renderings of a step: the step equations (29) / R, (30) / L and the step
// constraint (33) (or its replacements) of common/step_equations.h in the unknowns
// x = (du, g^, r^, dlambda), with no smoothing unknown, closed by a nonsmooth complementarity
// row per pair (a = g^_p, b = -r^_p):
//
//  `nonsmooth-fb`: psi_FB(a, b) = sqrt(a^2 + b^2) - (a + b)   ((12) with rho = 0),
//  `active-set`:   min(a, b),
//
// solved by a semismooth Newton method: the selected EquationSolver ("newton" by default) run
// on a system whose Jacobian() returns an element of the generalised Jacobian.
//
// nonsmooth-fb. psi_FB is differentiable except at a = b = 0; there the element of
// FischerBurmeisterElement is used (De Luca-Facchinei-Kanzow's construction with the direction
// (a, b) along (1, 1): (1/sqrt2 - 1, 1/sqrt2 - 1)), an element of the B-subdifferential. The
// merit m = 1/2 ||F||^2 of the FB system is continuously differentiable with grad m = H^T F for
// every H in the generalised Jacobian, so for the semismooth Newton direction dx = -H^{-1} F the
// slope is m'(x; dx) = -||F||^2 exactly, the one Newton's Armijo test assumes.
//
// active-set. Newton on min(g^, -r^) = 0 is the primal-dual active set method
// (Hintermueller, Ito and Kunisch, SIAM J. Optim. 13 (2003)): with the active set
// A = {p : g^_p <= -r^_p} the step solves (29), (30), (33) with g^_p = 0 on A and r^_p = 0 off A.
// Ties g^_p = -r^_p go to the active set (the element (1, 0), the limit from a < b): at the
// report's cold start every pair is tied (g^0 = -1 = -r^0), and taking them as closed makes the
// first step solve the fully closed problem instead of the free one (which, e.g. on the two-bar
// truss above its limit load, has no solution and stalls Newton at the limit point). The
// verdict's CountContacts counts ties as open; the two differ only at exact ties. Newton's line
// search tries the full PDAS step first and backtracks only when it does not decrease the merit
// enough (a monotone safeguard; the min merit is not C^1 at ties, where the Armijo slope -||F||^2
// is only approximate): so the iteration cannot cycle between active sets unnoticed, it is bounded
// by max_iterations, and revisits of an earlier active set are counted and reported (details,
// message).
//
// Starts (docs/method.md section 4, MakeStepEquationStart): warm du0, dlambda0 from the StartPoint
// fitted to the constraint, r0 = r^k, g0 = -phi(u^k + du0); cold du0 = 0, g^0 = -1, r^0 = +1.
// The kink step (53) uses the smooth replacement g^ + r^ = 0 for its pair, as implicit-fb does.
//
// Restart (NonsmoothOptions::restart). Where the path turns back in lambda at a kink (a contact
// closing on a descending branch), the warm start's predictor points into the obstacle, and
// without smoothing the iteration stalls at a stationary point of the merit with r > 0 on the
// far side of the arc; the path driver's cut-backs then only approach the kink (a Zeno
// sequence). So a warm arc-length solve that stops far from a solution (||F||_inf >
// restart_residual) is restarted once, from the
// kink geometry: du0 = t du_pred with t in [0, 1] the largest fraction of the predictor that
// opens no gap below min(g^k, 0) (bisection on the gaps: the first contact along the
// predictor), and dlambda0 = -sign(dlambda_pred) sqrt(theta^2 - ||du0||^2) / w (the turn), so
// that (33) holds; r0 = r^k, except on the pairs closed at du0 (g^ <= 1e-8), whose reactions are
// the least-squares solution of (29), G_c^T r_c = grad pi(u0) - lambda0 f, clipped to r <= 0,
// so the start leans on the contact it has just met rather than sitting at the degenerate
// g = r = 0 (from where Newton returns to the free branch). The counts and the history include
// both runs; details["restarted"] says whether it happened.
#pragma once

#include <memory>
#include <string>

#include "formulations/common/config.h"
#include "formulations/common/start_solvers.h"
#include "formulations/common/step_equations.h"
#include "formulations/common/step_rows.h"
#include "step/formulation.h"

namespace cb {

enum class ComplementarityFunction { kFischerBurmeister, kMin };

// min(a, b) and its generalised-Jacobian element: (1, 0) when a <= b, else (0, 1) (ties to the
// active set, see above).
double MinFunction(double a, double b);
void MinElement(double a, double b, double* d_a, double* d_b);

struct NonsmoothOptions {
  ComplementarityFunction function = ComplementarityFunction::kFischerBurmeister;
  std::string solver = "newton";  // one of EquationSolverNames()
  SolverOptions solver_options;
  bool restart = true;  // see "Restart" above
  // Restart only when the first run stopped with ||F||_inf above this: a stall at the rounding
  // floor of (29) (large E A against small residual forces, as on P3) is a usable point that
  // the verdict accepts, and a restart from it could only find the path's other root.
  double restart_residual = 1e-6;

  bool IsValid(std::string* why) const;
};

// The square system (29), (30), C(g^, -r^) = 0, step constraint, of size d + 2 nc + 1.
class NonsmoothSystem final : public StepEquationSystem {
 public:
  NonsmoothSystem(const StepProblem& step, ComplementarityFunction function,
                  std::shared_ptr<PatternCache> cache = nullptr);
  ~NonsmoothSystem() override;

  ComplementarityFunction function() const { return function_; }
  // Jacobian evaluations that met a pair at a nondifferentiable point (FB: a = b = 0; min:
  // a = b) since construction, summed over pairs.
  int nonsmooth_elements() const { return nonsmooth_elements_; }

 private:
  double Complementarity(double a, double b, double rho) const override;
  void ComplementarityElement(double a, double b, double rho, double* d_a, double* d_b,
                              double* d_rho) const override;

  ComplementarityFunction function_;
  mutable int nonsmooth_elements_ = 0;
};

class NonsmoothFormulation final : public Formulation {
 public:
  explicit NonsmoothFormulation(NonsmoothOptions options = {});
  ~NonsmoothFormulation() override;
  // "nonsmooth-fb" or "active-set".
  std::string name() const override;
  std::string solver() const override { return options_.solver; }
  std::string settings() const override;
  const NonsmoothOptions& options() const { return options_; }

 private:
  void DoSolve(const StepProblem& step, const StartPoint& start, const SolveControls& controls,
               StepResult* result) override;

  NonsmoothOptions options_;
  // Caches kept between steps (the warm-state rule, src/step/warm_state.md): the solvers' work
  // storage and symbolic analyses, and the Jacobian's pattern. The previous step reaches a
  // solve only through its StartPoint.
  StartSolvers solvers_;
  std::shared_ptr<StepEquationSystem::PatternCache> cache_;
};

// nonsmooth-fb's (`function` FB) or active-set's (min) step as rows (common/step_rows.h;
// nonsmooth_rows.cc): NonsmoothSystem on `local` from MakeStepEquationStart on `step`.
StepRows NonsmoothRows(const StepProblem& step, const StepProblem& local, const StartPoint& start,
                       ComplementarityFunction function,
                       std::shared_ptr<StepEquationSystem::PatternCache> cache);

// "nonsmooth-fb" (Fischer-Burmeister) or "active-set" (min).
std::string NonsmoothName(ComplementarityFunction function);

// Registry factories (nonsmooth_fb.cc, active_set.cc): config.solver and config.solver_options;
// backend options `restart` (true/false) and `restart_residual` (an unknown key throws
// std::invalid_argument). MakeNonsmooth is what both do with their function.
std::unique_ptr<Formulation> MakeNonsmoothFb(const FormulationConfig& config);
std::unique_ptr<Formulation> MakeActiveSet(const FormulationConfig& config);
std::unique_ptr<Formulation> MakeNonsmooth(ComplementarityFunction function,
                                           const FormulationConfig& config);

}  // namespace cb
