// The implicit smoothed Fischer-Burmeister formulation of Kanno & Ohsaki (METR 2009-06):
// the step equations (29)-(33) in the unknowns x = (du, g, r, dlambda, rho), with rho an
// unknown tied to the complementarity residual by the eta equation (32).
//
// Scaling (METHOD.md section 2): the contact unknowns are g^ = g / L and r^ = r / R, and the
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
// nonsmooth formulations (step_equations.h); this file adds rho, psi (31) and the eta row (32).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "formulations/implicit_fb/step_equations.h"
#include "solvers/equation_solver.h"
#include "step/formulation.h"

namespace cb {

// The eta cases of METHOD.md section 2 (the report's section 5.1).
enum class EtaCase { kCase1 = 1, kCase2 = 2, kCase3 = 3, kNonsmooth = 4 };

// The eta equation (32) divided by nc, in terms of the mean m = g^T r^ / nc (<= 0 at a
// solution) and rho:
//   case 1: -gamma^2 m - (exp(gamma rho) - 1)   eta1(c) = gamma^2 c + 1, eta2(c) = exp(gamma c)
//   case 2: -m - (rho + rho^3)                  eta1(c) = c,             eta2(c) = c + c^3
//   case 3: -m - 2 rho^2                        eta1(c) = c / 2,         eta2(c) = c^2
//   case 4: rho                                 rho fixed at 0 (nonsmooth FB)
struct EtaEquation {
  EtaCase eta = EtaCase::kCase1;
  double gamma = 1.0;  // case 1 only, from (37)

  double Value(double mean_gr, double rho) const;
  double DerivativeMean(double rho) const;  // d/dm
  double DerivativeRho(double rho) const;   // d/drho
  // The rho solving Value(m, rho) = 0: (43) as corrected for case 1, the real root of
  // rho + rho^3 = -m for case 2, sqrt(-m / 2) for case 3 (NaN when m > 0), 0 for case 4.
  double CompatibleRho(double mean_gr) const;
};

// gamma of (37) for a start with mean m0 = g0^T r0 / nc: 1 when m0 < 1 - gamma_tol, else
// sqrt((1 - gamma_tol) / m0), which keeps 1 - gamma^2 m0 >= gamma_tol > 0 so (43) is defined.
double WarmStartGamma(double mean_gr, double gamma_tol);

struct ImplicitFbOptions {
  EtaCase eta = EtaCase::kCase1;
  std::string solver = "newton";  // one of EquationSolverNames()
  SolverOptions solver_options;
  double gamma_tol = 1e-2;  // gamma_ of (37)
  double rho_min = 1e-3;    // rho_ of (42): rho0 = rho* if |rho*| > rho_, else rho_

  bool IsValid(std::string* why) const;
};

// The unknown vector's layout.
struct ImplicitFbLayout {
  int d = 0;
  int nc = 0;
  int du() const { return 0; }
  int g() const { return d; }
  int r() const { return d + nc; }
  int dlambda() const { return d + 2 * nc; }
  int rho() const { return d + 2 * nc + 1; }
  int size() const { return d + 2 * nc + 2; }
};

// The start of METHOD.md section 4 in the scaled unknowns, with the gamma it chose.
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

// The square system (29)-(33) for one step.
class ImplicitFbSystem final : public StepEquationSystem {
 public:
  // The Jacobian pattern (StepEquationSystem::PatternCache), built on first use and reusable by
  // later systems of the same model, constraint kind and index (a path analyses it once).
  using PatternCache = StepEquationSystem::PatternCache;

  ImplicitFbSystem(const StepProblem& step, EtaEquation eta,
                   std::shared_ptr<PatternCache> cache = nullptr);
  ~ImplicitFbSystem() override;

  const ImplicitFbLayout& layout() const { return layout_; }
  const EtaEquation& eta() const { return eta_; }

 private:
  // (31): psi(g^_p, -r^_p, rho), with the generalised-Jacobian element of
  // FischerBurmeisterElement where it is not differentiable (rho = 0, case 4).
  double Complementarity(double a, double b, double rho) const override;
  void ComplementarityElement(double a, double b, double rho, double* d_a, double* d_b,
                              double* d_rho) const override;
  // (32) / nc.
  double ExtraRow(const Vec& x) const override;
  void AppendExtraRowEntries(std::vector<ScatterPattern::Entry>* entries) const override;
  void FillExtraRow(const Vec& x, Cursor* cursor) const override;

  EtaEquation eta_;
  ImplicitFbLayout layout_;
};

class ImplicitFb final : public Formulation {
 public:
  explicit ImplicitFb(ImplicitFbOptions options = {});
  ~ImplicitFb() override;
  std::string name() const override;
  std::string solver() const override { return options_.solver; }
  std::string settings() const override;
  bool Supports(ConstraintKind) const override { return true; }
  const ImplicitFbOptions& options() const { return options_; }

 private:
  void DoSolve(const StepProblem& step, const StartPoint& start, const SolveControls& controls,
               StepResult* result) override;

  ImplicitFbOptions options_;
  std::unique_ptr<EquationSolver> solver_;
  std::shared_ptr<ImplicitFbSystem::PatternCache> cache_;
};

}  // namespace cb
