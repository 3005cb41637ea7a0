// The implicit smoothed Fischer-Burmeister formulation of Kanno & Ohsaki (METR 2009-06):
// the step equations (29)-(33) in the unknowns x = (du, g, r, dlambda, rho), with rho an
// unknown tied to the complementarity residual by the eta equation (32).
//
// Scaling (docs/method.md section 2): the contact unknowns are g^ = g / L and r^ = r / R, and the
// rows are made dimensionless, so the system solved is
//   F1 = (grad pi(u) - lambda f) / R - grad phi(u)^T r^               (29) / R,   d rows
//   F2 = g^ + phi(u) / L                                               (30) / L,   nc rows
//   F3_p = psi(g^_p, -r^_p, rho)                                       (31),       nc rows
//          (for the pair of a kink step, g^_p + r^_p: see StepEquationSystem::Residual)
//   F4 = eta equation (32) divided by nc (EtaEquation),                           1 row
//   F5 = step constraint c (StepConstraintValue; (33) / theta^2 - 1 for arc length), 1 row.
// Multiplying rows by constants changes neither the solution nor Newton's iterates, but the
// merit 1/2 ||F||^2 and the solvers' stopping test are then balanced between rows.
//
// F1, F2, F5, the Jacobian assembly and the start of the contact unknowns are shared with the
// nonsmooth formulations (common/step_equations.h); eta_equation.h and implicit_fb_system.h add
// rho, psi (31) and the eta row (32). This file holds the formulation and its registry factory.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "formulations/common/config.h"
#include "formulations/common/start_solvers.h"
#include "formulations/common/step_rows.h"
#include "formulations/implicit_fb/eta_equation.h"
#include "formulations/implicit_fb/implicit_fb_system.h"
#include "solvers/equation_solver.h"
#include "step/formulation.h"

namespace cb {

struct ImplicitFbOptions {
  EtaCase eta = EtaCase::kCase1;
  std::string solver = "newton";  // one of EquationSolverNames()
  SolverOptions solver_options;
  double gamma_tol = 1e-2;  // gamma_ of (37)
  double rho_min = 1e-3;    // rho_ of (42): rho0 = rho* if |rho*| > rho_, else rho_
  // Newton on the contact unknowns alone (common/reduced_step_system.h): unset, wherever it
  // applies (ReducedStepSystem::Applies); true, required (a step it does not apply to is
  // refused); false, never.
  std::optional<bool> reduced_newton;

  bool IsValid(std::string* why) const;
};

// The start of docs/method.md section 4 in the scaled unknowns, with the gamma it chose.
struct ImplicitFbStart {
  Vec x;
  double gamma = 1.0;
  double rho_star = 0.0;  // the compatible rho before the rho_ safeguard (42)
};

// Warm start (38)-(43): du0, dlambda0 from `start` (rescaled onto the arc-length constraint,
// or set to satisfy a fixed-load / displacement constraint), r0 = r^k, g0 = -phi(u^k + du0),
// gamma by (37), rho0 by (42)-(43). Cold start (report section 5.1): du0 = 0, g0^ = -1,
// r0^ = +1, dlambda0 satisfying the step constraint (theta / w for arc length).
ImplicitFbStart MakeImplicitFbStart(const StepProblem& step, const StartPoint& start,
                                    const ImplicitFbOptions& options);

class ImplicitFb final : public Formulation {
 public:
  explicit ImplicitFb(ImplicitFbOptions options = {});
  ~ImplicitFb() override;
  std::string name() const override;
  std::string solver() const override { return options_.solver; }
  std::string settings() const override;
  const ImplicitFbOptions& options() const { return options_; }

 private:
  bool DoAccepts(const StepProblem& step, std::string* why) const override;
  void DoSolve(const StepProblem& step, const StartPoint& start, const SolveControls& controls,
               StepResult* result) override;

  ImplicitFbOptions options_;
  // Caches kept between steps (the warm-state rule, src/step/warm_state.md): the solvers' work
  // storage and symbolic analyses, and the Jacobian's pattern. The previous step reaches a
  // solve only through its StartPoint.
  StartSolvers solvers_;
  std::shared_ptr<ImplicitFbSystem::PatternCache> cache_;
};

// implicit-fb's step as rows (common/step_rows.h; implicit_fb_rows.cc): the system (29)-(33) on
// `local` with the eta equation (32) of the start's gamma, the start (38)-(43) on `step`, and the
// details gamma and rho, as ImplicitFb::DoSolve builds them.
StepRows ImplicitFbRows(const StepProblem& step, const StepProblem& local, const StartPoint& start,
                        const ImplicitFbOptions& options,
                        std::shared_ptr<StepEquationSystem::PatternCache> cache);

// Registry factory: config.solver, config.solver_options and config.eta; backend options
// `gamma_tol`, `rho_min` and `reduced_newton` (an unknown key or a bad value throws
// std::invalid_argument).
std::unique_ptr<Formulation> MakeImplicitFb(const FormulationConfig& config);

}  // namespace cb
